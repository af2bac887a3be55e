#pragma once
/// Helpers for the end-to-end tests: run the softsub binary, temporary folders, files.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace softsub::apptest {

namespace fs = std::filesystem;

/// What a finished softsub process left: exit code and its captured output.
struct RunResult {
  int code = -1;       ///< exit status; 128 + N when killed by signal N
  std::string out;     ///< stdout
  std::string err;     ///< stderr
};

/// Runs `softsub <args>` (args are shell words, already quoted where needed) in `cwd`,
/// capturing stdout and stderr to files. stdin is /dev/null.
RunResult runSoftsub(const std::string& args, const fs::path& cwd);

/// Runs `softsub <args>` in `cwd` under a fresh pseudo-terminal (stdin, stdout and
/// stderr are its slave side, as at an interactive shell) and returns everything it
/// printed, in order, as the terminal received it (newlines arrive as "\r\n"); `out`
/// holds it and `err` is empty. Fails the test on timeout (60 s, the child is killed).
RunResult runSoftsubInTerminal(const std::string& args, const fs::path& cwd);

/// Runs an arbitrary shell command line (words already quoted) in `cwd`, capturing
/// stdout and stderr to files; stdin is /dev/null. For programs that wrap softsub
/// (xvfb-run) or for other tools.
RunResult runCommand(const std::string& commandLine, const fs::path& cwd);

/// Starts softsub with `args` in the background (stdin and stdout /dev/null, stderr to
/// `errFile`); returns its pid (-1 if it could not be started). The caller waits for it.
int spawnSoftsub(const std::vector<std::string>& args, const fs::path& errFile);

/// The full path of `program` found on PATH (an executable file), or empty.
std::string findProgram(const std::string& program);

/// The softsub binary under test.
fs::path softsubBinary();

/// Single-quotes `s` for the shell.
std::string quote(const fs::path& s);

/// A fresh, empty folder removed (with its contents) on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  /// The folder.
  [[nodiscard]] const fs::path& path() const { return path_; }
  /// path() / name.
  [[nodiscard]] fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

/// The whole file.
std::string readFile(const fs::path& p);

/// Every regular file under `dir`, as paths relative to it, sorted.
std::vector<std::string> listFiles(const fs::path& dir);

/// listFiles without the run's journal: its manifest/ and checkpoint/ folders (the
/// frames' cache files only).
std::vector<std::string> listFrameFiles(const fs::path& dir);

/// Every entry (files and folders) directly inside `dir`, by name, sorted.
std::vector<std::string> listEntries(const fs::path& dir);

/// The repository's examples/ folder.
fs::path examplesDir();

/// The example scenes (examples/*.scene), sorted.
std::vector<fs::path> exampleScenes();

/// Copies `from` into `dir` (same file name) and returns the copy's path.
fs::path copyInto(const fs::path& from, const fs::path& dir);

/// The particle count of each fluid of a scene file, in scene order (via read+compile).
std::vector<std::uint32_t> fluidCounts(const fs::path& scene);

}  // namespace softsub::apptest
