#include "cmd_schema.h"

#include <cstdio>

#include <CLI/CLI.hpp>

#include "core/error.h"
#include "scene/schema.h"

namespace softsub::app {

CLI::App* addSchemaCommand(CLI::App& root) {
  return root.add_subcommand("schema",
                             "Print the .scene format reference as Markdown (every tag, unit, default, range)");
}

int schemaCommand() {
  const std::string text = scene::schemaMarkdown();
  std::fwrite(text.data(), 1, text.size(), stdout);
  return static_cast<int>(ExitCode::Ok);
}

}  // namespace softsub::app
