#pragma once
/// Scene-file text to field values: strict, locale-independent number parsing
/// (std::from_chars, whole token, finite, in range) and the word-level helpers the
/// reader's messages use. No XML here; reader.cpp adds the file, line and element.
#include <string>
#include <string_view>
#include <vector>

#include "scene/schema.h"

namespace softsub::scene {

/// s without leading and trailing XML white space (space, tab, CR, LF).
std::string_view trimSpace(std::string_view s);

/// The white-space separated tokens of s.
std::vector<std::string_view> splitTokens(std::string_view s);

/// Parses the text of a value element by the field's kind, range and choices into out.
/// Returns the problem in words ("'abc' is not a number"), or "" on success.
std::string parseValueText(const FieldInfo& field, std::string_view text, Value& out);

/// " (did you mean <X>?)" when name is a near miss (case or a couple of letters) of one
/// of the candidates, else "".
std::string nearMiss(std::string_view name, const std::vector<std::string_view>& candidates);

/// s in single quotes for a message, cut short when long.
std::string quote(std::string_view s);

}  // namespace softsub::scene
