#include "core/error.h"

#include <string_view>

namespace softsub {

std::string formatInputError(const InputLocation& where, const std::string& problem,
                             const std::string& allowed) {
  std::string s;
  s.reserve(where.file.size() + where.element.size() + problem.size() + allowed.size() + 32);
  s.append(where.file.empty() ? std::string_view("<input>") : std::string_view(where.file));
  if (where.line > 0) s.append(":").append(std::to_string(where.line));
  s.append(": ");
  if (!where.element.empty()) s.append(where.element).append(": ");
  s.append(problem);
  if (!allowed.empty()) s.append(" (allowed: ").append(allowed).append(")");
  return s;
}

InputError::InputError(InputLocation where, std::string problem, std::string allowed)
    : std::runtime_error(formatInputError(where, problem, allowed)),
      where_(std::move(where)),
      problem_(std::move(problem)),
      allowed_(std::move(allowed)) {}

}  // namespace softsub
