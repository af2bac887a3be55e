#pragma once
/// `softsub info FILE`: a summary of a .scene, .sim, .pdc, .ply, .manifest or .state
/// file, or of a run's output folder.
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
/// Prints a frame's manifest: frame, substeps, run fingerprint, files, and whether the
/// frame is complete (every listed file there at its size).
void printManifestInfo(const std::string& path);
/// Prints a checkpoint's header: frame, particles, bodies, run fingerprint.
void printCheckpointInfo(const std::string& path);
/// Prints, per scene name with manifests in the folder, which frames are complete, the
/// checkpoints, and where `run --resume` would continue.
void printRunFolderInfo(const std::string& dir);

}  // namespace softsub::app
