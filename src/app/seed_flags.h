#pragma once
/// The seed's single-dash flags (-f, -record, -updateNum, -drawPerFrame,
/// -stopRecordingAt), mapped onto softsub's options before CLI11 parses the line.
#include <span>
#include <string>
#include <vector>

namespace softsub::app {

/// Names of softsub's subcommands (a first argument that is one of them is kept).
inline constexpr const char* kSubcommands[] = {"run", "info", "schema", "fill", "render", "view"};

/// Rewrites `args` (args[0] is the program) so that CLI11 can parse it:
/// `-record V` -> `--record=V`, `-updateNum V` -> `--substeps=V`,
/// `-stopRecordingAt V` -> `--stop-recording-at=V`, `-drawPerFrame V` ->
/// `--draw-per-frame=V` (also the `-flag=V` forms), and inserts `run` after the program
/// when no subcommand is named but a seed flag (or `-f`) is given. Nothing after `--`
/// is touched.
std::vector<std::string> rewriteSeedFlags(std::span<const std::string> args);

}  // namespace softsub::app
