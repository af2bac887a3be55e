#include "app_test_util.h"

#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <pty.h>
#include <sys/wait.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include <gtest/gtest.h>
#include <unistd.h>

#include "scene/compile.h"
#include "scene/reader.h"

extern char** environ;

namespace softsub::apptest {

std::string quote(const fs::path& p) {
  std::string out = "'";
  for (char c : p.string()) {
    if (c == '\'') out += "'\\''";
    else out += c;
  }
  return out + "'";
}

RunResult runSoftsub(const std::string& args, const fs::path& cwd) {
  return runCommand(quote(SOFTSUB_BINARY) + " " + args, cwd);
}

fs::path softsubBinary() { return SOFTSUB_BINARY; }

int spawnSoftsub(const std::vector<std::string>& args, const fs::path& errFile) {
  std::vector<std::string> all{SOFTSUB_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, errFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return rc == 0 ? pid : -1;
}

std::string findProgram(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::string_view rest = path ? path : "/usr/bin:/bin";
  for (;;) {
    const auto colon = rest.find(':');
    const fs::path dir(std::string(rest.substr(0, colon)));
    const fs::path candidate = (dir.empty() ? fs::path(".") : dir) / program;
    if (::access(candidate.c_str(), X_OK) == 0 && fs::is_regular_file(candidate)) return candidate.string();
    if (colon == std::string_view::npos) return {};
    rest.remove_prefix(colon + 1);
  }
}

RunResult runCommand(const std::string& commandLine, const fs::path& cwd) {
  static std::atomic<int> counter{0};
  const fs::path base = fs::temp_directory_path() /
                        ("softsub-test-io-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  const fs::path outFile = base.string() + ".out";
  const fs::path errFile = base.string() + ".err";
  const std::string cmd = "cd " + quote(cwd) + " && " + commandLine + " >" + quote(outFile) + " 2>" +
                          quote(errFile) + " </dev/null";
  const int status = std::system(cmd.c_str());
  RunResult r;
  if (status == -1) throw std::runtime_error("could not run: " + cmd);
  if (WIFEXITED(status)) r.code = WEXITSTATUS(status);
  else if (WIFSIGNALED(status)) r.code = 128 + WTERMSIG(status);
  r.out = readFile(outFile);
  r.err = readFile(errFile);
  fs::remove(outFile);
  fs::remove(errFile);
  return r;
}

RunResult runSoftsubInTerminal(const std::string& args, const fs::path& cwd) {
  // The command line is prepared before fork: the child only changes folder and execs.
  const std::string cmd = "cd " + quote(cwd) + " && exec " + quote(SOFTSUB_BINARY) + " " + args;
  int master = -1;
  const pid_t pid = ::forkpty(&master, nullptr, nullptr, nullptr);
  if (pid < 0) throw std::runtime_error("forkpty failed");
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  RunResult r;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  char buf[4096];
  for (;;) {
    pollfd p{master, POLLIN, 0};
    const int ready = ::poll(&p, 1, 100);
    if (ready < 0 && errno != EINTR) break;
    if (ready > 0) {
      const ssize_t n = ::read(master, buf, sizeof buf);
      if (n > 0) {
        r.out.append(buf, static_cast<std::size_t>(n));
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      break;  // EIO (or 0): every slave side is closed, the child is gone
    }
    if (std::chrono::steady_clock::now() > deadline) {
      ADD_FAILURE() << "softsub " << args << " still running after 60 s under a terminal";
      ::kill(pid, SIGKILL);
      break;
    }
  }
  ::close(master);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
  if (WIFEXITED(status)) r.code = WEXITSTATUS(status);
  else if (WIFSIGNALED(status)) r.code = 128 + WTERMSIG(status);
  return r;
}

TempDir::TempDir() {
  std::string pattern = (fs::temp_directory_path() / "softsub-test-XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  path_ = pattern;
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

std::string readFile(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> listFiles(const fs::path& dir) {
  std::vector<std::string> out;
  if (!fs::exists(dir)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out.push_back(fs::relative(e.path(), dir).generic_string());
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> listFrameFiles(const fs::path& dir) {
  std::vector<std::string> files = listFiles(dir);
  std::erase_if(files, [](const std::string& f) { return f.starts_with("manifest/") || f.starts_with("checkpoint/"); });
  return files;
}

std::vector<std::string> listEntries(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

fs::path examplesDir() { return fs::path(SOFTSUB_SOURCE_DIR) / "examples"; }

std::vector<fs::path> exampleScenes() {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(examplesDir()))
    if (e.path().extension() == ".scene") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

fs::path copyInto(const fs::path& from, const fs::path& dir) {
  const fs::path to = dir / from.filename();
  fs::copy_file(from, to, fs::copy_options::overwrite_existing);
  return to;
}

std::vector<std::uint32_t> fluidCounts(const fs::path& scene) {
  const scene::Compiled c = scene::compile(scene::readSceneFile(scene.string()));
  std::vector<std::uint32_t> out;
  for (const auto& f : c.model.fluids) out.push_back(f.count);
  return out;
}

}  // namespace softsub::apptest
