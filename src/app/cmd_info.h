#pragma once
/// `softsub info FILE`: a summary of a .scene, .sim, .pdc or .ply file.
#include <string>

namespace CLI {
class App;
}

namespace softsub::app {

/// The options of `info`.
struct InfoOptions {
  std::string file;  ///< the file to describe; its extension picks the reader
};

/// Adds the `info` subcommand bound to `options` and returns it.
CLI::App* addInfoCommand(CLI::App& root, InfoOptions& options);

/// Prints the summary on stdout. Returns the exit code; throws InputError for an
/// unknown extension or an invalid file, IoError for an unreadable one.
int infoCommand(const InfoOptions& options);

/// Prints a summary of a .scene file (fluids, counts, bounds, parameters, interactions).
void printSceneInfo(const std::string& path);
/// Prints a summary of a .sim file (frame, time, per fluid count and bounds).
void printSimInfo(const std::string& path);
/// Prints a summary of a .pdc file (header, attributes, count, position bounds).
void printPdcInfo(const std::string& path);
/// Prints a summary of a .ply file (format, properties, per fluid counts, bounds).
void printPlyInfo(const std::string& path);

}  // namespace softsub::app
