// softsub: the command line. Parses, dispatches to one command, and maps every error
// to its exit code (core/error.h, docs/cli.md) in this one place.
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <exception>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <tbb/global_control.h>

#include "cmd_bench.h"
#include "cmd_fill.h"
#include "cmd_info.h"
#include "cmd_mesh.h"
#include "cmd_render.h"
#include "cmd_run.h"
#include "cmd_schema.h"
#include "cmd_view.h"
#include "number_checks.h"
#include "core/error.h"
#include "seed_flags.h"

namespace {

using softsub::ExitCode;

int code(ExitCode c) { return static_cast<int>(c); }

void printError(const std::string& message) { fmt::print(stderr, "error: {}\n", message); }

int runApp(int argc, char** argv) {
  namespace app = softsub::app;
  CLI::App root{"softsub: soft and viscous substances from particles, simulated into frame caches",
                "softsub"};
  root.set_version_flag("--version", std::string("softsub ") + SOFTSUB_VERSION);
  root.require_subcommand(1);

  app::RunOptions runOptions;
  app::InfoOptions infoOptions;
  app::FillOptions fillOptions;
  app::RenderOptions renderOptions;
  app::ViewOptions viewOptions;
  app::MeshOptions meshOptions;
  app::BenchOptions benchOptions;
  CLI::App* run = app::addRunCommand(root, runOptions);
  CLI::App* info = app::addInfoCommand(root, infoOptions);
  CLI::App* fill = app::addFillCommand(root, fillOptions);
  CLI::App* schema = app::addSchemaCommand(root);
  CLI::App* render = app::addRenderCommand(root, renderOptions);
  CLI::App* view = app::addViewCommand(root, viewOptions);
  CLI::App* mesh = app::addMeshCommand(root, meshOptions);
  CLI::App* bench = app::addBenchCommand(root, benchOptions);
  // --threads belongs to the root and is accepted after any command too (fallthrough):
  // every command's parallel stages share one limit.
  int threads = 0;
  root.add_option("--threads", threads,
                  "Threads for the simulation, surfaces and pictures, 1 to 1024 (default 0: all cores); "
                  "results are bitwise the same for any count")
      ->transform(softsub::app::wholeNumberIn(0, 1024));
  for (CLI::App* sub : {run, info, fill, schema, render, view, mesh, bench}) sub->fallthrough();
  for (CLI::App* sub : bench->get_subcommands({})) sub->fallthrough();
  // After the subcommands: CLI11 copies the parent's footer into a subcommand when it is
  // added, and this one is for the root's help only.
  root.footer("Run 'softsub COMMAND --help' for a command's options. Seed flags (-f, -record, "
              "-updateNum, -stopRecordingAt, -drawPerFrame) imply 'run'.");

  const std::vector<std::string> given(argv, argv + argc);
  const std::vector<std::string> args = app::rewriteSeedFlags(given);
  std::vector<const char*> argvOut;
  for (const std::string& a : args) argvOut.push_back(a.c_str());
  try {
    root.parse(static_cast<int>(argvOut.size()), argvOut.data());
  } catch (const CLI::CallForHelp& e) {
    return root.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return root.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return root.exit(e);
  } catch (const CLI::ParseError& e) {
    // "A subcommand is required" for `softsub bogus` hides the cause: name the word.
    const auto subcommands = root.get_subcommands({});
    bool anyParsed = false;
    for (const CLI::App* sub : subcommands) anyParsed = anyParsed || sub->parsed();
    for (std::size_t k = 1; !anyParsed && k < args.size(); ++k) {
      if (args[k].starts_with("-")) continue;
      if (args[k - 1] == "--threads") continue;  // its value
      std::string names;
      for (const CLI::App* sub : subcommands) names += (names.empty() ? "" : ", ") + sub->get_name();
      printError(fmt::format("'{}' is not a command (allowed: {})", args[k], names));
      fmt::print(stderr, "Run 'softsub --help' for usage.\n");
      return code(ExitCode::BadInput);
    }
    // A command that needs a command of its own (bench lammps): name the word it got.
    for (const CLI::App* sub : subcommands) {
      if (!sub->parsed() || sub->get_subcommands({}).empty()) continue;
      bool inner = false;
      for (const CLI::App* s2 : sub->get_subcommands({})) inner = inner || s2->parsed();
      if (inner) continue;
      std::string names, word;
      for (const CLI::App* s2 : sub->get_subcommands({}))
        names += (names.empty() ? "" : ", ") + s2->get_name();
      const auto at = std::find(args.begin() + 1, args.end(), sub->get_name());
      for (auto k = at; k != args.end() && word.empty(); ++k)
        if (k != at && !k->starts_with("-")) word = *k;
      printError(word.empty()
                     ? fmt::format("'{}' needs a command (allowed: {})", sub->get_name(), names)
                     : fmt::format("'{}' is not a {} command (allowed: {})", word, sub->get_name(), names));
      fmt::print(stderr, "Run 'softsub {} --help' for usage.\n", sub->get_name());
      return code(ExitCode::BadInput);
    }
    std::string what = e.what();
    // The scene named without -f/--scene (the positional) is called by that name, not
    // by the option's (CLI11 names the option "--scene" either way).
    if (what.starts_with("--scene: ") && std::none_of(args.begin() + 1, args.end(), [](const std::string& a) {
          return a == "-f" || a == "--scene" || a.starts_with("--scene=") ||
                 (a.starts_with("-f") && a.size() > 2);
        }))
      what = (view->parsed() ? "INPUT" : "SCENE") + what.substr(7);
    // CLI11's "--frames: At Most 1 required but received 2" for an option given twice.
    if (const auto at = what.find(": At Most 1 required but received "); at != std::string::npos)
      what = fmt::format("{}: given {} times (allowed: once)", what.substr(0, at),
                         what.substr(at + std::string_view(": At Most 1 required but received ").size()));
    printError("command line: " + what);
    fmt::print(stderr, "Run 'softsub --help' or 'softsub COMMAND --help' for usage.\n");
    return code(ExitCode::BadInput);
  }

  std::optional<tbb::global_control> threadLimit;
  if (threads > 0) threadLimit.emplace(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  if (run->parsed()) return app::runCommand(runOptions);
  if (info->parsed()) return app::infoCommand(infoOptions);
  if (fill->parsed()) return app::fillCommand(fillOptions);
  if (schema->parsed()) return app::schemaCommand();
  if (render->parsed()) return app::renderCommand(renderOptions);
  if (view->parsed()) return app::viewCommand(viewOptions);
  if (mesh->parsed()) return app::meshCommand(meshOptions);
  benchOptions.threads = threads;
  if (bench->parsed()) return app::benchLammpsCommand(benchOptions);
  return code(ExitCode::BadInput);  // unreachable: a subcommand is required
}

}  // namespace

int main(int argc, char** argv) {
  // A file-size limit (ulimit -f) kills a process that writes past it unless SIGXFSZ is
  // ignored; ignored, the write fails with EFBIG and the run stops with an I/O error
  // (exit 3) like on a full disk, its earlier frames intact.
  std::signal(SIGXFSZ, SIG_IGN);
  try {
    return runApp(argc, argv);
  } catch (const softsub::InputError& e) {
    printError(e.what());
    return code(ExitCode::BadInput);
  } catch (const softsub::IoError& e) {
    printError(e.what());
    return code(ExitCode::IoFailure);
  } catch (const softsub::BlowUpError& e) {
    printError(e.what());  // names the frame, fluid, particle and a remedy
    return code(ExitCode::BlowUp);
  } catch (const std::bad_alloc&) {
    printError("out of memory");
    return code(ExitCode::Internal);
  } catch (const std::exception& e) {
    printError(std::string("internal error: ") + e.what());
    return code(ExitCode::Internal);
  }
}
