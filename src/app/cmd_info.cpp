#include "cmd_info.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "core/error.h"
#include "number_checks.h"

namespace softsub::app {

CLI::App* addInfoCommand(CLI::App& root, InfoOptions& o) {
  CLI::App* info = root.add_subcommand(
      "info", "Summarise a .scene, .sim, .pdc, .ply, .manifest or .state file, or a run's output folder");
  info->add_option("FILE", o.file,
                   "A .scene, .sim, .pdc, .ply, .manifest or .state file (the extension says which), or an "
                   "output folder: which frames are complete and where --resume would continue")
      ->required()
      ->check(nonEmptyPath(false));
  return info;
}

int infoCommand(const InfoOptions& o) {
  std::error_code ec;
  if (std::filesystem::is_directory(o.file, ec)) {
    printRunFolderInfo(o.file);
    return static_cast<int>(ExitCode::Ok);
  }
  // A path that is not there: what is wrong is the path, whatever its extension (a
  // mistyped run folder was told "no file extension").
  if (!std::filesystem::exists(o.file, ec) && !ec)
    throw IoError(fmt::format("cannot read '{}': No such file or directory", displayFile(o.file)));
  std::string ext = std::filesystem::path(o.file).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".scene" || ext == ".xml") {  // `run` takes a scene under any name; .xml is common
    printSceneInfo(o.file);
  } else if (ext == ".sim") {
    printSimInfo(o.file);
  } else if (ext == ".pdc") {
    printPdcInfo(o.file);
  } else if (ext == ".ply") {
    printPlyInfo(o.file);
  } else if (ext == ".manifest") {
    printManifestInfo(o.file);
  } else if (ext == ".state") {
    printCheckpointInfo(o.file);
  } else {
    throw InputError({o.file, 0, {}},
                     ext.empty() ? std::string("no file extension")
                                 : "unknown file extension '" + ext + "'",
                     ".scene (or .xml), .sim, .pdc, .ply, .manifest, .state, or a folder");
  }
  return static_cast<int>(ExitCode::Ok);
}

}  // namespace softsub::app
