#include "cache/message.h"

namespace softsub::cache::detail {

std::string excerpt(std::string_view text) {
  constexpr std::size_t kMost = 60;
  std::string out;
  for (std::size_t i = 0; i < text.size() && i < kMost; ++i) {
    const auto u = static_cast<unsigned char>(text[i]);
    out += (u < 0x20 || u == 0x7f) ? '?' : text[i];
  }
  if (text.size() > kMost) out += "...";
  return out;
}

}  // namespace softsub::cache::detail
