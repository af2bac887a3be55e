#pragma once
/// Escaping text for the XML files softsub writes (.scene, .sim).
#include <string>
#include <string_view>

namespace softsub {

/// Appends `s` to `out` as XML character data (& < > " ' and CR escaped). Characters
/// XML 1.0 cannot carry at all (control characters other than tab and line feed)
/// throw InputError naming `element`, rather than producing a file no reader accepts.
void appendXmlEscaped(std::string& out, std::string_view s, std::string_view element);

}  // namespace softsub
