#include "scene/xml_checks.h"

#include <fmt/format.h>

#include <cctype>
#include <cstdint>
#include <string>

namespace softsub::scene {

namespace {

constexpr std::string_view kCharsAllowed =
    "UTF-8 text of XML characters: no NUL, no control character but tab, line feed and "
    "carriage return";
constexpr std::string_view kRefsAllowed =
    "&lt; &gt; &amp; &apos; &quot;, or &#N; / &#xN; of a character XML allows";
constexpr std::string_view kNoDtd = "no DOCTYPE or entity declarations: a .scene has no DTD";

bool isXmlChar(std::uint32_t c) {
  return c == 0x9 || c == 0xA || c == 0xD || (c >= 0x20 && c <= 0xD7FF) ||
         (c >= 0xE000 && c <= 0xFFFD) || (c >= 0x10000 && c <= 0x10FFFF);
}

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Pass 1: every byte sequence is UTF-8 for an XML character. Returns false with the
// problem filled in at the first bad one.
bool checkCharacters(std::string_view text, XmlTextCheck& out) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  // A UTF-16 file (what some Windows editors save) begins with its byte order mark, or
  // with '<' as two bytes: name the encoding rather than its first byte.
  if (text.size() >= 2 && ((byte(0) == 0xFF && byte(1) == 0xFE) || (byte(0) == 0xFE && byte(1) == 0xFF) ||
                           (byte(0) == '<' && byte(1) == 0) || (byte(0) == 0 && byte(1) == '<'))) {
    out.offset = 0;
    out.problem = "the file is UTF-16 text";
    out.allowed = "UTF-8 text: save the file as UTF-8 (every editor can)";
    return false;
  }
  std::size_t i = 0;
  while (i < text.size()) {
    const unsigned char b = byte(i);
    if (b < 0x80) {
      if (!isXmlChar(b)) {
        out.offset = i;
        out.problem = b == 0 ? std::string("a NUL character (byte 0)")
                             : fmt::format("a control character U+{:04X}", static_cast<unsigned>(b));
        out.allowed = kCharsAllowed;
        return false;
      }
      ++i;
      continue;
    }
    // Lead byte: length and the range of the first continuation byte (excludes overlong
    // forms, surrogates and code points above U+10FFFF).
    std::size_t length = 0;
    unsigned char lo = 0x80;
    unsigned char hi = 0xBF;
    std::uint32_t cp = 0;
    if (b >= 0xC2 && b <= 0xDF) {
      length = 2;
      cp = b & 0x1Fu;
    } else if (b >= 0xE0 && b <= 0xEF) {
      length = 3;
      cp = b & 0x0Fu;
      if (b == 0xE0) lo = 0xA0;
      if (b == 0xED) hi = 0x9F;
    } else if (b >= 0xF0 && b <= 0xF4) {
      length = 4;
      cp = b & 0x07u;
      if (b == 0xF0) lo = 0x90;
      if (b == 0xF4) hi = 0x8F;
    }
    bool ok = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; ok && k < length; ++k) {
      const unsigned char c = byte(i + k);
      if (c < (k == 1 ? lo : 0x80) || c > (k == 1 ? hi : 0xBF)) ok = false;
      cp = (cp << 6) | (c & 0x3Fu);
    }
    if (!ok) {
      out.offset = i;
      out.problem = fmt::format("invalid UTF-8 (byte 0x{:02X})", static_cast<unsigned>(b));
      out.allowed = kCharsAllowed;
      return false;
    }
    if (!isXmlChar(cp)) {
      out.offset = i;
      out.problem = fmt::format("the character U+{:04X}, which XML does not allow", cp);
      out.allowed = kCharsAllowed;
      return false;
    }
    i += length;
  }
  return true;
}

// A reference starting at text[at] == '&': empty when allowed, else the problem.
std::string checkReference(std::string_view text, std::size_t at) {
  constexpr std::size_t kLongest = 12;  // "&#x0010FFFF;" and the entity names fit
  const std::size_t semi = text.find(';', at + 1);
  if (semi == std::string_view::npos || semi - at > kLongest) {
    return "a '&' that starts no entity or character reference (write &amp;)";
  }
  const std::string_view name = text.substr(at + 1, semi - at - 1);
  const std::string_view whole = text.substr(at, semi - at + 1);
  if (name == "lt" || name == "gt" || name == "amp" || name == "apos" || name == "quot") return {};
  if (name.empty() || name[0] != '#') {
    return fmt::format("the entity reference '{}': only the five predefined entities exist", whole);
  }
  const bool hex = name.size() > 1 && name[1] == 'x';
  const std::string_view digits = name.substr(hex ? 2 : 1);
  std::uint32_t value = 0;
  bool ok = !digits.empty();
  for (const char c : digits) {
    std::uint32_t d = 0;
    if (c >= '0' && c <= '9') {
      d = static_cast<std::uint32_t>(c - '0');
    } else if (hex && c >= 'a' && c <= 'f') {
      d = static_cast<std::uint32_t>(c - 'a' + 10);
    } else if (hex && c >= 'A' && c <= 'F') {
      d = static_cast<std::uint32_t>(c - 'A' + 10);
    } else {
      ok = false;
      break;
    }
    value = value * (hex ? 16u : 10u) + d;
    if (value > 0x10FFFF) ok = false;
  }
  if (!ok) return fmt::format("'{}' is not a character reference", whole);
  if (value == 0) return fmt::format("a NUL character reference '{}'", whole);
  if (!isXmlChar(value)) {
    return fmt::format("the character reference '{}' to U+{:04X}, which XML does not allow", whole,
                       value);
  }
  return {};
}

bool isNameEnd(char c) { return isSpace(c) || c == '/' || c == '>'; }

}  // namespace

namespace {

// The encoding an XML declaration at the start names ("" when none): scene files are
// UTF-8, and a file that declares another encoding was refused over its first byte
// outside ASCII as "invalid UTF-8", without a word about the declaration, or read as
// UTF-8 whatever it declared (a review).
std::string declaredEncoding(std::string_view text, std::size_t& at) {
  std::size_t start = text.starts_with("\xEF\xBB\xBF") ? 3 : 0;
  if (text.substr(start, 5) != "<?xml") return {};
  const std::size_t end = text.find("?>", start);
  const std::string_view decl =
      text.substr(start, end == std::string_view::npos ? text.size() - start : end - start);
  const std::size_t key = decl.find("encoding");
  if (key == std::string_view::npos) return {};
  std::size_t i = key + 8;
  while (i < decl.size() &&
         (decl[i] == ' ' || decl[i] == '\t' || decl[i] == '\r' || decl[i] == '\n' || decl[i] == '='))
    ++i;
  if (i >= decl.size() || (decl[i] != '"' && decl[i] != '\'')) return {};
  const char quote = decl[i];
  const std::size_t close = decl.find(quote, i + 1);
  if (close == std::string_view::npos) return {};
  at = start + key;
  return std::string(decl.substr(i + 1, close - i - 1));
}

}  // namespace

XmlTextCheck checkXmlText(std::string_view text) {
  XmlTextCheck out;
  {
    std::size_t at = 0;
    std::string encoding = declaredEncoding(text, at);
    std::string lower = encoding;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (!encoding.empty() && lower != "utf-8" && lower != "utf8" && lower != "us-ascii" && lower != "ascii") {
      out.offset = at;
      out.problem =
          fmt::format("the file declares the encoding '{}'; scene files are read as UTF-8", encoding);
      out.allowed = fmt::format(
          "UTF-8 text, declared as such or not at all (convert it, e.g. iconv -f {} -t "
          "UTF-8 FILE, and change the declaration)",
          encoding);
      return out;
    }
  }
  if (!checkCharacters(text, out)) return out;

  const auto fail = [&](std::size_t at, std::string problem, std::string_view allowed) {
    out.offset = at;
    out.problem = std::move(problem);
    out.allowed = allowed;
    return out;
  };
  // Past the end marker of markup that starts at `start`; at the end of the text, with
  // the markup recorded as unfinished, when there is none.
  const auto skipTo = [&](std::size_t start, std::size_t from, std::string_view end,
                          std::string_view what) {
    const std::size_t e = text.find(end, from);
    if (e != std::string_view::npos) return e + end.size();
    out.unfinished = what;
    out.unfinishedOffset = start;
    return text.size();
  };

  std::vector<OpenElement>& open = out.openAtEnd;
  bool rootClosed = false;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '&') {
      if (std::string problem = checkReference(text, i); !problem.empty()) {
        return fail(i, std::move(problem), kRefsAllowed);
      }
      ++i;
      continue;
    }
    if (c != '<') {
      ++i;
      continue;
    }
    const std::string_view rest = text.substr(i);
    if (rest.starts_with("<!--")) {
      i = skipTo(i, i + 4, "-->", "a comment");
    } else if (rest.starts_with("<![CDATA[")) {
      if (rootClosed) {
        return fail(i, "a CDATA section after the root element",
                    "nothing but comments and white space after </Scene>");
      }
      i = skipTo(i, i + 9, "]]>", "a CDATA section");
    } else if (rest.starts_with("<!DOCTYPE")) {
      return fail(i, "a DOCTYPE declaration", kNoDtd);
    } else if (rest.starts_with("<!ENTITY")) {
      return fail(i, "an entity declaration", kNoDtd);
    } else if (rest.starts_with("<?")) {
      if (rootClosed) {
        return fail(i, "a processing instruction after the root element",
                    "nothing but comments and white space after </Scene>");
      }
      i = skipTo(i, i + 2, "?>", "a processing instruction");
    } else if (rest.starts_with("</")) {
      std::size_t j = i + 2;
      while (j < text.size() && !isNameEnd(text[j])) ++j;
      const std::string_view name = text.substr(i + 2, j - i - 2);
      if (!open.empty() && name != open.back().name && out.mismatchedEnd.name.empty() &&
          out.mismatchedOpen.name.empty()) {
        out.mismatchedEnd = {std::string(name), i};
        out.mismatchedOpen = open.back();
      }
      if (!open.empty()) open.pop_back();
      if (open.empty()) rootClosed = true;
      i = skipTo(i, i + 2, ">", "an end tag");
    } else if (rest.starts_with("<!")) {
      i += 2;  // not XML: the parser reports it
    } else {
      // A start tag: its name, then up to its '>' (quoted attribute values may hold '>'
      // and references).
      std::size_t j = i + 1;
      while (j < text.size() && !isNameEnd(text[j])) ++j;
      const std::string name(text.substr(i + 1, j - i - 1));
      char quote = 0;
      bool selfClosing = false;
      for (; j < text.size(); ++j) {
        const char d = text[j];
        if (quote != 0) {
          if (d == quote) quote = 0;
          if (d == '&') {
            if (std::string problem = checkReference(text, j); !problem.empty()) {
              return fail(j, std::move(problem), kRefsAllowed);
            }
          }
          continue;
        }
        if (d == '"' || d == '\'') quote = d;
        if (d == '>') {
          selfClosing = text[j - 1] == '/';
          break;
        }
      }
      if (j == text.size()) {
        out.unfinished = "<" + name + ">";
        out.unfinishedOffset = i;
      }
      if (!selfClosing) {
        if (open.size() == kMaxXmlDepth) {
          return fail(i, fmt::format("<{}> is nested {} elements deep", name, kMaxXmlDepth + 1),
                      fmt::format("elements nested at most {} deep", kMaxXmlDepth));
        }
        open.push_back({name, i});
      } else if (open.empty()) {
        rootClosed = true;
      }
      i = j < text.size() ? j + 1 : j;
    }
  }
  return out;
}

}  // namespace softsub::scene
