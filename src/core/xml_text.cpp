#include "core/xml_text.h"

#include <cstdio>

#include "core/error.h"

namespace softsub {

void appendXmlEscaped(std::string& out, std::string_view s, std::string_view element) {
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      case '\r': out += "&#13;"; break;  // a raw CR would be read back as LF
      default:
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') {
          char code[8];
          std::snprintf(code, sizeof code, "%#04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
          throw InputError({"", 0, std::string(element)}, std::string("text contains control character ") + code,
                           "characters XML 1.0 can hold: no control characters but tab and line breaks");
        }
        out += c;
    }
  }
}

}  // namespace softsub
