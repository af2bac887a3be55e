#include "core/error.h"

#include <string_view>

namespace softsub {

std::string displayFile(std::string_view file) {
  std::string s;
  for (const char c : file) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\t') {
      s += "\\t";
    } else if (c == '\n') {
      s += "\\n";
    } else if (c == '\r') {
      s += "\\r";
    } else if (u < 0x20 || u == 0x7f) {
      constexpr std::string_view kHex = "0123456789abcdef";
      s.append("\\x").append(1, kHex[u >> 4]).append(1, kHex[u & 0xf]);
    } else {
      s += c;
    }
  }
  return s;
}

std::string formatInputError(const InputLocation& where, const std::string& problem,
                             const std::string& allowed) {
  std::string s;
  s.reserve(where.file.size() + where.element.size() + problem.size() + allowed.size() + 32);
  s.append(where.file.empty() ? std::string("<input>") : displayFile(where.file));
  if (where.line > 0) s.append(":").append(std::to_string(where.line));
  s.append(": ");
  // The element and the problem may quote names and values from the input (an object
  // named "x&#10;y"): escaped like the file, so an error stays one readable line.
  if (!where.element.empty()) s.append(displayFile(where.element)).append(": ");
  s.append(displayFile(problem));
  if (!allowed.empty()) s.append(" (allowed: ").append(displayFile(allowed)).append(")");
  return s;
}

InputError::InputError(InputLocation where, std::string problem, std::string allowed)
    : std::runtime_error(formatInputError(where, problem, allowed)),
      where_(std::move(where)),
      problem_(std::move(problem)),
      allowed_(std::move(allowed)) {}

}  // namespace softsub
