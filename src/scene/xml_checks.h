#pragma once
/// Checks on the raw text of a .scene file that pugixml does not make (docs/robustness.md).
/// Debian's pugixml accepts a DOCTYPE and unknown entity references (kept as text), drops
/// `&#0;` silently, accepts control characters and invalid UTF-8, and reports a truncated
/// file only as "start-end tags mismatch". The reader runs checkXmlText before parsing,
/// so whatever reaches the parser is plain XML 1.0 without a DTD.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace softsub::scene {

/// Deepest element nesting a scene may have (the format itself needs 5:
/// Scene/Interactions/Pair/Curve/Points).
inline constexpr std::size_t kMaxXmlDepth = 32;

/// An element open at a point of the text: its name and the offset of its '<'.
struct OpenElement {
  std::string name;
  std::size_t offset = 0;
};

/// What checkXmlText found. problem empty: the text passed.
struct XmlTextCheck {
  std::string problem;                ///< "a DOCTYPE declaration", ...
  std::string allowed;                ///< the rule broken
  std::size_t offset = 0;             ///< byte offset of the problem
  std::vector<OpenElement> openAtEnd; ///< elements still open at the end of the text
  /// Markup the text ends inside ("<Shape>", "a comment", ...), "" when none, and where
  /// it starts: a file cut short.
  std::string unfinished;
  std::size_t unfinishedOffset = 0;
  /// The first end tag that does not close the innermost open element: its name and
  /// offset, and that element (name empty: none). The parser refuses the file there; the
  /// reader names both tags.
  OpenElement mismatchedEnd;
  OpenElement mismatchedOpen;
};

/// Scans text (without its byte order mark): UTF-8 that decodes to XML 1.0 characters
/// (no NUL, no control character but tab, LF and CR, no U+FFFE/U+FFFF), no DOCTYPE or
/// ENTITY declaration, only the five predefined entities and character references to
/// allowed characters (`&#0;` and `&#1;` are refused), elements nested at most
/// kMaxXmlDepth deep, and nothing but comments and white space after the root element.
/// Comments and CDATA sections are skipped for the markup rules (not for the character
/// rules). Stops at the first problem.
XmlTextCheck checkXmlText(std::string_view text);

}  // namespace softsub::scene
