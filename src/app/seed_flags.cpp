#include "seed_flags.h"

#include <algorithm>
#include <array>
#include <optional>
#include <string_view>
#include <utility>

namespace softsub::app {

namespace {

/// Seed flag -> softsub long option (each takes one value).
constexpr std::array<std::pair<std::string_view, std::string_view>, 4> kSeedToLong{{
    {"-record", "--record"},
    {"-updateNum", "--substeps"},
    {"-stopRecordingAt", "--stop-recording-at"},
    {"-drawPerFrame", "--draw-per-frame"},
}};

/// The long option for a seed flag `arg` (either `-flag` or `-flag=value`), and the
/// value when it came attached.
std::optional<std::pair<std::string_view, std::optional<std::string>>> matchSeed(std::string_view arg) {
  for (const auto& [seed, longName] : kSeedToLong) {
    if (arg == seed) return std::pair{longName, std::optional<std::string>{}};
    if (arg.size() > seed.size() && arg.starts_with(seed) && arg[seed.size()] == '=')
      return std::pair{longName, std::optional<std::string>{std::string(arg.substr(seed.size() + 1))}};
  }
  return std::nullopt;
}

bool isSubcommand(std::string_view arg) {
  return std::any_of(std::begin(kSubcommands), std::end(kSubcommands),
                     [&](const char* s) { return arg == s; });
}

}  // namespace

std::vector<std::string> rewriteSeedFlags(std::span<const std::string> args) {
  std::vector<std::string> out;
  if (args.empty()) return out;
  out.push_back(args[0]);
  bool sawSeedFlag = false;
  bool literal = false;  // after "--": positional arguments only
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (literal) {
      out.push_back(arg);
      continue;
    }
    if (arg == "--") {
      literal = true;
      out.push_back(arg);
      continue;
    }
    if (arg == "-f" || (arg.starts_with("-f") && !arg.starts_with("--"))) sawSeedFlag = true;
    if (arg.starts_with("-f=")) {  // CLI11 would take "=FILE" for the file name
      out.push_back("--scene=" + arg.substr(3));
      continue;
    }
    const auto seed = matchSeed(arg);
    if (!seed) {
      out.push_back(arg);
      continue;
    }
    sawSeedFlag = true;
    const auto& [longName, attached] = *seed;
    if (attached) {
      out.push_back(std::string(longName) + "=" + *attached);
    } else if (i + 1 < args.size()) {
      // Join the value so that a value such as "-1" is never taken for an option.
      out.push_back(std::string(longName) + "=" + args[++i]);
    } else {
      out.push_back(std::string(longName));  // CLI11 reports the missing value
    }
  }
  // The command comes after the root's own options (`softsub --threads 2 view -f x`):
  // "run" was put before them and the named command became a second scene.
  std::size_t k = 1;
  while (k < out.size()) {
    if (out[k] == "--threads" && k + 1 < out.size()) {
      k += 2;
    } else if (out[k].starts_with("--threads=")) {
      ++k;
    } else {
      break;
    }
  }
  const bool namesSubcommand = k < out.size() && isSubcommand(out[k]);
  if (sawSeedFlag && !namesSubcommand) out.insert(out.begin() + static_cast<std::ptrdiff_t>(k), "run");
  return out;
}

}  // namespace softsub::app
