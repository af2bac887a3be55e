#include "session/script.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <stdexcept>

#include "cache/atomic_file.h"
#include "core/error.h"
#include "session/parameters.h"

namespace softsub::session {

namespace {

constexpr const char* kCommands =
    "set fluid <Name> <Tag> <value>, set simulation <Tag> <value>, key <R|S|N|M|SPACE|UP|DOWN|LEFT|RIGHT>, "
    "frames <N>, wait <N>, save <path.scene>, screenshot <path.png>, quit";

constexpr std::int64_t kMostFrames = 1'000'000;

bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && isSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && isSpace(s.back())) s.remove_suffix(1);
  return s;
}

/// The line without its comment: '#' at the start or after white space.
std::string_view withoutComment(std::string_view line) {
  for (std::size_t i = 0; i < line.size(); ++i)
    if (line[i] == '#' && (i == 0 || isSpace(line[i - 1]))) return line.substr(0, i);
  return line;
}

/// Splits off the first word of `rest` (which keeps what follows, trimmed).
std::string_view nextWord(std::string_view& rest) {
  rest = trim(rest);
  std::size_t n = 0;
  while (n < rest.size() && !isSpace(rest[n])) ++n;
  const std::string_view word = rest.substr(0, n);
  rest = trim(rest.substr(n));
  return word;
}

std::string upper(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

bool endsWithIgnoringCase(std::string_view s, std::string_view suffix) {
  return s.size() > suffix.size() && upper(s.substr(s.size() - suffix.size())) == upper(suffix);
}

class LineParser {
 public:
  LineParser(const std::string& file, int line) : file_(file), line_(line) {}

  [[noreturn]] void fail(std::string_view element, std::string problem, std::string allowed) const {
    throw InputError({file_, line_, std::string(element)}, std::move(problem), std::move(allowed));
  }

  ScriptCommand parse(std::string_view text) const {
    ScriptCommand c;
    c.line = line_;
    std::string_view rest = text;
    const std::string_view word = nextWord(rest);
    if (word == "set") {
      const std::string_view what = nextWord(rest);
      if (what == "fluid") {
        const std::string_view name = nextWord(rest);
        const std::string_view tag = nextWord(rest);
        if (name.empty() || tag.empty() || rest.empty())
          fail("set fluid", "expected a fluid name, a tag and a value", "set fluid <Name> <Tag> <value>");
        checkFluidParameter(tag, rest, {file_, line_});
        c.kind = ScriptCommandKind::SetFluid;
        c.args = {std::string(name), std::string(tag), std::string(rest)};
      } else if (what == "simulation") {
        const std::string_view tag = nextWord(rest);
        if (tag.empty() || rest.empty())
          fail("set simulation", "expected a tag and a value", "set simulation <Tag> <value>");
        checkSimulationParameter(tag, rest, {file_, line_});
        c.kind = ScriptCommandKind::SetSimulation;
        c.args = {std::string(tag), std::string(rest)};
      } else {
        fail("set", fmt::format("cannot set '{}'", what), "set fluid <Name> <Tag> <value>, set simulation <Tag> <value>");
      }
    } else if (word == "key") {
      const std::string key = upper(nextWord(rest));
      std::string keys;
      for (std::string_view k : kScriptKeys) keys += (keys.empty() ? "" : ", ") + std::string(k);
      if (key.empty() || !rest.empty() ||
          std::find(std::begin(kScriptKeys), std::end(kScriptKeys), key) == std::end(kScriptKeys))
        fail("key", key.empty() ? std::string("expected a key") : fmt::format("unknown key '{}'", trim(text.substr(3))),
             keys);
      c.kind = ScriptCommandKind::Key;
      c.args = {key};
    } else if (word == "frames" || word == "wait") {
      const bool frames = word == "frames";
      const std::int64_t lowest = frames ? 1 : 0;
      const std::string_view n = nextWord(rest);
      std::int64_t value = 0;
      const auto [ptr, ec] = std::from_chars(n.data(), n.data() + n.size(), value);
      if (n.empty() || !rest.empty() || ec != std::errc{} || ptr != n.data() + n.size() || value < lowest ||
          value > kMostFrames)
        fail(word, n.empty() ? std::string("expected a number") : fmt::format("'{}' is not a count", trim(text.substr(word.size()))),
             fmt::format("an integer in [{}, {}]", lowest, kMostFrames));
      c.kind = frames ? ScriptCommandKind::Frames : ScriptCommandKind::Wait;
      c.args = {std::string(n)};
    } else if (word == "save" || word == "screenshot") {
      const bool save = word == "save";
      const std::string_view suffix = save ? ".scene" : ".png";
      if (!endsWithIgnoringCase(rest, suffix))
        fail(word, rest.empty() ? std::string("expected a file") : fmt::format("'{}' is not a {} file", rest, suffix),
             fmt::format("a path ending in {}", suffix));
      c.kind = save ? ScriptCommandKind::Save : ScriptCommandKind::Screenshot;
      c.args = {std::string(rest)};
    } else if (word == "quit") {
      if (!rest.empty()) fail("quit", "takes nothing after it", "quit");
      c.kind = ScriptCommandKind::Quit;
    } else {
      fail(word, fmt::format("unknown command '{}'", word), kCommands);
    }
    return c;
  }

 private:
  const std::string& file_;
  int line_;
};

}  // namespace

std::int64_t scriptCount(const ScriptCommand& command) {
  if ((command.kind != ScriptCommandKind::Frames && command.kind != ScriptCommandKind::Wait) ||
      command.args.size() != 1)
    throw std::invalid_argument("scriptCount: not a frames or wait command");
  std::int64_t n = 0;
  std::from_chars(command.args[0].data(), command.args[0].data() + command.args[0].size(), n);
  return n;
}

std::vector<ScriptCommand> parseScript(std::string_view text, const std::string& fileName) {
  std::vector<ScriptCommand> out;
  int line = 0;
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    const std::string_view raw = text.substr(0, end);
    text = end == std::string_view::npos ? std::string_view() : text.substr(end + 1);
    ++line;
    const std::string_view body = trim(withoutComment(raw));
    if (body.empty()) continue;
    out.push_back(LineParser(fileName, line).parse(body));
  }
  return out;
}

std::vector<ScriptCommand> readScriptFile(const std::filesystem::path& path) {
  return parseScript(cache::readFileBytes(path), path.string());
}

void applySetCommand(const ScriptCommand& command, scene::SceneDesc& desc, const std::string& fileName) {
  const EditSource source{fileName, command.line};
  if (command.kind == ScriptCommandKind::SetFluid && command.args.size() == 3) {
    setFluidParameter(desc, command.args[0], command.args[1], command.args[2], source);
  } else if (command.kind == ScriptCommandKind::SetSimulation && command.args.size() == 2) {
    setSimulationParameter(desc, command.args[0], command.args[1], source);
  } else {
    throw std::invalid_argument("applySetCommand: not a set command");
  }
}

}  // namespace softsub::session
