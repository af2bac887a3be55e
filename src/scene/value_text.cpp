#include "scene/value_text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <utility>

namespace softsub::scene {

namespace {

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

static_assert(kMaxReal <= FLT_MAX, "every accepted real must convert to a finite float");

// A problem with a value, thrown inside this file only and returned as a ValueProblem.
struct Problem {
  std::string text;
  std::string allowed;  // empty: the field's own rule
  std::string_view at;  // the token at fault, a view into the parsed text; empty: the value
};

// from_chars does not take a leading '+'; people write one.
std::string_view withoutPlus(std::string_view t) {
  if (t.size() > 1 && t[0] == '+' && t[1] != '+' && t[1] != '-') t.remove_prefix(1);
  return t;
}

// Parses one finite number; returns the problem, or "" when fine.
std::string parseReal(std::string_view token, double& out) {
  const std::string_view t = withoutPlus(token);
  const char* end = t.data() + t.size();
  const auto [ptr, ec] = std::from_chars(t.data(), end, out);
  if (ec == std::errc::result_out_of_range) {
    return fmt::format("{} is beyond the range of numbers", quote(token));
  }
  if (ec != std::errc{} || ptr != end) return fmt::format("{} is not a number", quote(token));
  if (!std::isfinite(out)) return fmt::format("{} is not a finite number", quote(token));
  return {};
}

// Parses one integer; returns the problem, or "" when fine.
std::string parseInt(std::string_view token, std::int64_t& out) {
  const std::string_view t = withoutPlus(token);
  const char* end = t.data() + t.size();
  const auto [ptr, ec] = std::from_chars(t.data(), end, out);
  if (ec == std::errc::result_out_of_range) {
    return fmt::format("{} is beyond the range of integers", quote(token));
  }
  if (ec != std::errc{} || ptr != end) {
    double d = 0;
    if (parseReal(token, d).empty()) return fmt::format("{} is not an integer", quote(token));
    return fmt::format("{} is not a number", quote(token));
  }
  return {};
}

class ValueParser {
 public:
  ValueParser(const FieldInfo& f, std::string_view text)
      : f_(f), text_(trimSpace(text)), tokens_(splitTokens(text)) {}

  [[nodiscard]] Value parse() const {
    // Numbers written with commas ("0,-9.81,0", "1,5") are a common slip from other
    // tools: said as such rather than as a count or "not a number".
    if (f_.kind != Kind::String && f_.kind != Kind::Enum)
      for (const std::string_view t : tokens_)
        if (t.find(',') != std::string_view::npos)
          bad(fmt::format("{} holds a comma", quote(t)),
              "numbers separated by spaces, with a decimal point (e.g. 0 -9.81 0, 1.5)", t);
    switch (f_.kind) {
      case Kind::Real: return number(single());
      case Kind::Int: return integer(single());
      case Kind::Bool: return boolean(single());
      case Kind::Vec3:
      case Kind::Colour:
        if (tokens_.size() != 3) bad(fmt::format("expected 3 numbers, got {}", tokens_.size()));
        return point(0);
      case Kind::String:
        if (text_.empty()) bad("the value is empty");
        return std::string(text_);
      case Kind::Enum: return choice(single());
      case Kind::RealList: {
        std::vector<double> list;
        list.reserve(tokens_.size());
        for (const auto t : tokens_) list.push_back(number(t));
        return list;
      }
      case Kind::PointList: {
        if (tokens_.size() % 3 != 0) {
          bad(fmt::format("{} numbers do not make whole positions (3 numbers each)", tokens_.size()));
        }
        std::vector<Vec3> points;
        points.reserve(tokens_.size() / 3);
        for (std::size_t i = 0; i < tokens_.size(); i += 3) points.push_back(point(i));
        return points;
      }
    }
    bad("unsupported value kind");
  }

 private:
  [[noreturn]] static void bad(std::string problem, std::string allowed = {}, std::string_view at = {}) {
    throw Problem{std::move(problem), std::move(allowed), at};
  }

  [[nodiscard]] std::string_view single() const {
    if (tokens_.empty()) bad("the value is empty");
    if (tokens_.size() > 1) {
      bad(fmt::format("expected one value, got {}: {}", tokens_.size(), quote(text_)));
    }
    return tokens_[0];
  }

  [[nodiscard]] double number(std::string_view token) const {
    double v = 0;
    if (auto problem = parseReal(token, v); !problem.empty()) bad(std::move(problem), {}, token);
    if (!f_.range.contains(v)) bad(fmt::format("{} is out of range", token), {}, token);
    // After the range: a bounded field names its own range; the others this limit.
    if (std::fabs(v) > kMaxReal)
      bad(fmt::format("{} is too large for single precision", quote(token)), "|value| <= 3.4e38", token);
    return v;
  }

  // Tokens first .. first + 2 as a point, checked left to right (so the first bad
  // number is the one reported; constructor arguments have no evaluation order).
  [[nodiscard]] Vec3 point(std::size_t first) const {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = number(tokens_[first + static_cast<std::size_t>(a)]);
    return p;
  }

  [[nodiscard]] std::int64_t integer(std::string_view token) const {
    std::int64_t v = 0;
    if (auto problem = parseInt(token, v); !problem.empty()) bad(std::move(problem));
    if (!f_.range.contains(static_cast<double>(v))) bad(fmt::format("{} is out of range", v));
    return v;
  }

  [[nodiscard]] static bool boolean(std::string_view token) {
    if (token == "true" || token == "1") return true;
    if (token == "false" || token == "0") return false;
    bad(fmt::format("{} is not a boolean", quote(token)));
  }

  [[nodiscard]] std::int64_t choice(std::string_view token) const {
    for (std::size_t i = 0; i < f_.choices.size(); ++i) {
      if (f_.choices[i] == token) return static_cast<std::int64_t>(i);
    }
    bad(fmt::format("{} is not one of the choices", quote(token)));
  }

  const FieldInfo& f_;
  std::string_view text_;
  std::vector<std::string_view> tokens_;
};

std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0U : 1U)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

bool equalIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

std::string_view trimSpace(std::string_view s) {
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> splitTokens(std::string_view s) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && isSpace(s[i])) ++i;
    const std::size_t start = i;
    while (i < s.size() && !isSpace(s[i])) ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
  return out;
}

ValueProblem parseValueText(const FieldInfo& field, std::string_view text, Value& out) {
  try {
    out = ValueParser(field, text).parse();
    return {};
  } catch (const Problem& p) {
    return {p.text, p.allowed, p.at.empty() ? -1 : p.at.data() - text.data()};
  }
}

std::string nearMiss(std::string_view name, const std::vector<std::string_view>& candidates) {
  // The seed report's names for what this format names otherwise (a review: a scene
  // written after the report got only the list of allowed names).
  constexpr std::pair<std::string_view, std::string_view> kReportNames[] = {
      {"MinimumForce", "Min"},
      {"MaximumForce", "Max"},
      {"InteractionDistance", "Cutoff"},
      {"Filename", "Geometry"},
  };
  for (const auto& [report, ours] : kReportNames)
    if (name == report && std::find(candidates.begin(), candidates.end(), ours) != candidates.end())
      return fmt::format(" (did you mean <{}>? the seed report's <{}> is <{}> here: scene-format.md)", ours,
                         report, ours);
  for (const auto c : candidates) {
    if (equalIgnoringCase(name, c)) {
      return fmt::format(" (did you mean <{}>? element names are case-sensitive)", c);
    }
  }
  std::string_view best;
  std::size_t bestDistance = 3;  // at most 2 edits
  for (const auto c : candidates) {
    const std::size_t d = editDistance(name, c);
    if (d < bestDistance && d < c.size()) {
      best = c;
      bestDistance = d;
    }
  }
  return best.empty() ? std::string() : fmt::format(" (did you mean <{}>?)", best);
}

std::string quote(std::string_view s) {
  constexpr std::size_t kMax = 40;
  if (s.size() > kMax) return fmt::format("'{}...'", s.substr(0, kMax));
  return fmt::format("'{}'", s);
}

}  // namespace softsub::scene
