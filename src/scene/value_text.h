#pragma once
/// Scene-file text to field values: strict, locale-independent number parsing
/// (std::from_chars, whole token, finite, in range) and the word-level helpers the
/// reader's messages use. No XML here; reader.cpp adds the file, line and element.
///
/// Every real must also fit single precision (|value| <= kMaxReal): the model and the
/// caches store floats, so a bigger number would turn into inf after validation.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "scene/schema.h"

namespace softsub::scene {

/// s without leading and trailing XML white space (space, tab, CR, LF).
std::string_view trimSpace(std::string_view s);

/// Whether a and b are the same ASCII text but for letter case.
bool equalIgnoringCase(std::string_view a, std::string_view b);

/// The largest magnitude of a real in a scene, "3.4e38" in messages: just below FLT_MAX
/// (3.4028e38), so every accepted real is a finite float.
inline constexpr double kMaxReal = 3.4e38;

/// A problem with a value's text, in words.
struct ValueProblem {
  std::string text;     ///< "'abc' is not a number"; empty: no problem
  std::string allowed;  ///< the rule broken when not the field's own; empty: allowedText(field)
  /// Where in the parsed text the token at fault starts (a long Particles list names
  /// its line); -1: the value as a whole.
  std::ptrdiff_t offset = -1;
};

/// The white-space separated tokens of s.
std::vector<std::string_view> splitTokens(std::string_view s);

/// Parses the text of a value element by the field's kind, range and choices into out.
/// Returns the problem (empty text on success).
ValueProblem parseValueText(const FieldInfo& field, std::string_view text, Value& out);

/// " (did you mean <X>?)" when name is a near miss (case or a couple of letters) of one
/// of the candidates, else "".
std::string nearMiss(std::string_view name, const std::vector<std::string_view>& candidates);

/// s in single quotes for a message, cut short when long.
std::string quote(std::string_view s);

}  // namespace softsub::scene
