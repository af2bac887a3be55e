#pragma once
/// Helpers shared by the cache decoders' error messages (internal to the module).
#include <string>
#include <string_view>

namespace softsub::cache::detail {

/// Input text as quoted in an error message: at most 60 characters (then "..."), every
/// control character shown as '?', so that garbage input cannot garble a terminal.
[[nodiscard]] std::string excerpt(std::string_view text);

}  // namespace softsub::cache::detail
