#pragma once
/// Errors and the process exit codes they map to (documented in docs/cli.md).
#include <stdexcept>
#include <string>
#include <string_view>

namespace softsub {

/// Process exit codes. Every command uses these and nothing else.
enum class ExitCode : int {
  Ok = 0,
  Internal = 1,     ///< a bug: an unexpected exception
  BadInput = 2,     ///< bad command line, scene or input file; nothing was written
  IoFailure = 3,    ///< an output could not be written or an input could not be read
  BlowUp = 4,       ///< the simulation produced a non-finite value; earlier frames are intact
  Interrupted = 130 ///< stopped by SIGINT/SIGTERM after finishing the current frame
};

/// Where in an input file something is: file, 1-based line (0 = unknown), element.
struct InputLocation {
  std::string file;
  int line = 0;
  std::string element;
};

/// Bad input: a file, line, element, the problem and what is allowed.
/// what() is the one-line message `<file>:<line>: <element>: <problem> (allowed: <rule>)`.
class InputError : public std::runtime_error {
 public:
  InputError(InputLocation where, std::string problem, std::string allowed = {});
  [[nodiscard]] const InputLocation& where() const { return where_; }
  [[nodiscard]] const std::string& problem() const { return problem_; }
  [[nodiscard]] const std::string& allowed() const { return allowed_; }

 private:
  InputLocation where_;
  std::string problem_;
  std::string allowed_;
};

/// An input or output file could not be read or written (exit code 3).
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The simulation produced a non-finite or impossible value (exit code 4).
class BlowUpError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Formats an InputError message from its parts (used by InputError::what()).
/// A file name as messages show it: control characters escaped (\t, \n, \r, \xHH), so
/// that a message stays one line and an odd name can be told and typed.
[[nodiscard]] std::string displayFile(std::string_view file);

std::string formatInputError(const InputLocation& where, const std::string& problem,
                             const std::string& allowed);

}  // namespace softsub
