#include "cache/manifest.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <system_error>

#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "cache/naming.h"
#include "core/error.h"

namespace softsub::cache {

namespace {

constexpr std::string_view kFirstLine = "softsub manifest 1";

std::string relativeText(const std::filesystem::path& dir, const std::filesystem::path& file) {
  return file.lexically_relative(dir).generic_string();
}

template <class T>
bool parseNumber(std::string_view text, T& out, int base = 10) {
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out, base);
  return ec == std::errc() && end == text.data() + text.size();
}

/// Frames of files named `<scene>.<digits><suffix>` in `folder`, ascending.
std::vector<std::int64_t> framesIn(const std::filesystem::path& folder, std::string_view sceneName,
                                   std::string_view suffix) {
  std::vector<std::int64_t> frames;
  std::error_code ec;
  std::filesystem::directory_iterator it(folder, ec);
  if (ec) return frames;
  const std::string prefix = std::string(sceneName) + ".";
  for (const auto& entry : it) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string_view digits =
        std::string_view(name).substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    std::int64_t frame = 0;
    if (digits.size() >= 4 && std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }) &&
        parseNumber(digits, frame) && frameTag(frame) == digits)
      frames.push_back(frame);
  }
  std::sort(frames.begin(), frames.end());
  return frames;
}

/// True when `name` is writeFileAtomic's temporary name `.<file>.tmp.<host>.<pid>.<n>`;
/// `host` and `pid` get the writer's.
bool isTemporaryName(std::string_view name, std::string_view& host, long& pid) {
  if (name.size() < 2 || name[0] != '.') return false;
  const auto last = name.rfind('.');
  if (last == std::string_view::npos || last == 0) return false;
  const auto pidDot = name.rfind('.', last - 1);
  if (pidDot == std::string_view::npos || pidDot == 0) return false;
  const auto hostDot = name.rfind('.', pidDot - 1);
  if (hostDot == std::string_view::npos || hostDot < 5 || name.substr(hostDot - 4, 4) != ".tmp") return false;
  host = name.substr(hostDot + 1, pidDot - hostDot - 1);
  std::uint64_t counter = 0;
  return !host.empty() && parseNumber(name.substr(pidDot + 1, last - pidDot - 1), pid) && pid > 0 &&
         parseNumber(name.substr(last + 1), counter);
}

}  // namespace

std::filesystem::path manifestPath(const std::filesystem::path& dir, std::string_view sceneName, std::int64_t frame) {
  return dir / "manifest" / fmt::format("{}.{}.manifest", sceneName, frameTag(frame));
}

std::filesystem::path checkpointPath(const std::filesystem::path& dir, std::string_view sceneName,
                                     std::int64_t frame) {
  return dir / "checkpoint" / fmt::format("{}.{}.state", sceneName, frameTag(frame));
}

std::string encodeManifest(const Manifest& m) {
  std::string s = fmt::format("{}\nframe {}\nsubsteps {}\nfingerprint {:016x}\n", kFirstLine, m.frame, m.substeps,
                              m.fingerprint);
  for (const ManifestEntry& e : m.files) s += fmt::format("file {} {}\n", e.bytes, e.path);
  if (m.checkpoint) s += fmt::format("checkpoint {} {}\n", m.checkpoint->bytes, m.checkpoint->path);
  s += "end\n";
  return s;
}

Manifest decodeManifest(std::string_view text, const std::string& file) {
  Manifest m;
  int line = 0;
  bool ended = false;
  bool haveFrame = false;
  const auto fail = [&](const std::string& problem) {
    throw InputError({file, line, "manifest"}, problem, "a manifest written by softsub run");
  };
  while (!text.empty()) {
    ++line;
    const auto nl = text.find('\n');
    if (nl == std::string_view::npos) fail("the last line has no end (the file is cut)");
    const std::string_view row = text.substr(0, nl);
    text.remove_prefix(nl + 1);
    if (ended) fail("text after 'end'");
    if (line == 1) {
      if (row != kFirstLine) fail("not a softsub manifest (first line)");
      continue;
    }
    const auto space = row.find(' ');
    const std::string_view key = row.substr(0, space);
    const std::string_view rest = space == std::string_view::npos ? std::string_view{} : row.substr(space + 1);
    if (key == "end" && rest.empty()) {
      ended = true;
    } else if (key == "frame") {
      if (!parseNumber(rest, m.frame) || m.frame < 0) fail("bad frame number");
      haveFrame = true;
    } else if (key == "substeps") {
      if (!parseNumber(rest, m.substeps) || m.substeps < 1) fail("bad substep count");
    } else if (key == "fingerprint") {
      if (rest.size() != 16 || !parseNumber(rest, m.fingerprint, 16)) fail("bad fingerprint");
    } else if (key == "file" || key == "checkpoint") {
      const auto gap = rest.find(' ');
      ManifestEntry e;
      if (gap == std::string_view::npos || !parseNumber(rest.substr(0, gap), e.bytes)) fail("bad file size");
      e.path = std::string(rest.substr(gap + 1));
      const std::filesystem::path p(e.path);
      if (e.path.empty() || p.is_absolute() ||
          std::any_of(p.begin(), p.end(), [](const std::filesystem::path& part) { return part == ".."; }))
        fail("a file outside the output folder");
      if (key == "file") {
        m.files.push_back(std::move(e));
      } else {
        if (m.checkpoint) fail("two checkpoints");
        m.checkpoint = std::move(e);
      }
    } else {
      fail(fmt::format("unknown line '{}'", key));
    }
  }
  if (!ended) fail("no 'end' line (the file is cut)");
  if (!haveFrame) fail("no frame line");
  return m;
}

std::optional<Manifest> readManifestIfValid(const std::filesystem::path& path) {
  if (std::error_code ec; !std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  try {
    return decodeManifest(readFileBytes(path), path.string());
  } catch (const std::exception&) {  // InputError, IoError
    return std::nullopt;
  }
}

ManifestEntry entryOf(const std::filesystem::path& dir, const std::filesystem::path& file) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec) throw IoError(fmt::format("cannot read '{}': {}", file.string(), ec.message()));
  return {relativeText(dir, file), static_cast<std::uint64_t>(size)};
}

std::string incompleteReason(const std::filesystem::path& dir, const Manifest& m, bool needCheckpoint) {
  const auto check = [&](const ManifestEntry& e) -> std::string {
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(dir / e.path, ec);
    if (ec) return fmt::format("'{}' is missing", e.path);
    if (size != e.bytes) return fmt::format("'{}' has {} bytes, not {}", e.path, size, e.bytes);
    return {};
  };
  for (const ManifestEntry& e : m.files)
    if (std::string why = check(e); !why.empty()) return why;
  if (needCheckpoint && !m.checkpoint) return "it has no checkpoint";
  if (m.checkpoint) {
    std::string why = check(*m.checkpoint);
    if (!why.empty() && needCheckpoint) return why;
  }
  return {};
}

std::vector<std::int64_t> manifestFrames(const std::filesystem::path& dir, std::string_view sceneName) {
  return framesIn(dir / "manifest", sceneName, ".manifest");
}

std::vector<std::string> manifestSceneNames(const std::filesystem::path& dir) {
  constexpr std::string_view kSuffix = ".manifest";
  std::vector<std::string> names;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir / "manifest", ec), end; !ec && it != end; it.increment(ec)) {
    const std::string file = it->path().filename().string();
    if (file.size() <= kSuffix.size() || !file.ends_with(kSuffix)) continue;
    const std::string stem = file.substr(0, file.size() - kSuffix.size());
    const auto dot = stem.rfind('.');
    if (dot == std::string::npos || dot == 0) continue;
    std::string name = stem.substr(0, dot);
    // Only names whose manifest is really a frame's (`<name>.<frame tag>.manifest`).
    if (std::find(names.begin(), names.end(), name) == names.end() && !manifestFrames(dir, name).empty())
      names.push_back(std::move(name));
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::int64_t> checkpointFrames(const std::filesystem::path& dir, std::string_view sceneName) {
  return framesIn(dir / "checkpoint", sceneName, ".state");
}

std::size_t removeStaleTemporaries(const std::filesystem::path& dir) {
  std::size_t removed = 0;
  const auto sweep = [&](const std::filesystem::path& folder, bool descend) {
    std::error_code ec;
    std::vector<std::filesystem::path> sub;
    for (std::filesystem::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
      const std::filesystem::path p = it->path();
      std::error_code typeError;
      if (it->is_directory(typeError)) {
        if (descend) sub.push_back(p);
        continue;
      }
      const std::string file = p.filename().string();
      std::string_view host;
      long pid = 0;
      if (!isTemporaryName(file, host, pid)) continue;
      // Another host's process cannot be asked (shared storage): left alone.
      if (host != hostTag()) continue;
      // kill(pid, 0) succeeds (or fails with EPERM) while that process lives; our own
      // process id on a leftover means an earlier process that had it (this one has not
      // written yet: the function runs before a run's first write).
      if (pid != static_cast<long>(::getpid()) && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM))
        continue;
      std::error_code removeError;
      if (std::filesystem::remove(p, removeError)) ++removed;
    }
    return sub;
  };
  for (const std::filesystem::path& folder : sweep(dir, true)) sweep(folder, false);
  return removed;
}

}  // namespace softsub::cache
