#pragma once
/// Whole-file input and output for the caches: atomic writes (a file is complete or
/// absent, never half-written) and whole-file reads, all reporting IoError.
#include <filesystem>
#include <string>
#include <string_view>

namespace softsub::cache {

/// Writes `bytes` to `path` atomically: to a unique temporary file in the same folder,
/// flushed and closed, then renamed over `path`. On failure the temporary file is
/// removed, `path` is left as it was, and IoError names the path and the reason.
void writeFileAtomic(const std::filesystem::path& path, std::string_view bytes);

/// This machine's name as temporary file names carry it (letters, digits, '-' and '_').
[[nodiscard]] std::string hostTag();

/// A temporary name for `path` in the same folder, unique to this process and call:
/// `.<name>.tmp.<host>.<pid>.<n>`, the name writeFileAtomic writes under, which the next
/// run on this host recognises and removes when its process is gone
/// (removeStaleTemporaries). For files a
/// library writes itself (OpenVDB): write there, then rename over `path`.
[[nodiscard]] std::filesystem::path temporaryPathFor(const std::filesystem::path& path);

/// Creates `dir` and its missing parents; IoError if that fails or `dir` is not a folder.
void ensureDirectory(const std::filesystem::path& dir);

/// Reads the whole file at `path`; IoError if it cannot be opened or read.
[[nodiscard]] std::string readFileBytes(const std::filesystem::path& path);

}  // namespace softsub::cache
