#include "core/error.h"

namespace softsub {

std::string formatInputError(const InputLocation& where, const std::string& problem,
                             const std::string& allowed) {
  std::string s = where.file.empty() ? std::string("<input>") : where.file;
  if (where.line > 0) s += ":" + std::to_string(where.line);
  s += ": ";
  if (!where.element.empty()) s += where.element + ": ";
  s += problem;
  if (!allowed.empty()) s += " (allowed: " + allowed + ")";
  return s;
}

InputError::InputError(InputLocation where, std::string problem, std::string allowed)
    : std::runtime_error(formatInputError(where, problem, allowed)),
      where_(std::move(where)),
      problem_(std::move(problem)),
      allowed_(std::move(allowed)) {}

}  // namespace softsub
