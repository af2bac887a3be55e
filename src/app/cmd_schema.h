#pragma once
/// `softsub schema`: the .scene format reference (every tag, unit, default, range).

namespace CLI {
class App;
}

namespace softsub::app {

/// Adds the `schema` subcommand and returns it.
CLI::App* addSchemaCommand(CLI::App& root);

/// Prints scene::schemaMarkdown() on stdout; returns the exit code.
int schemaCommand();

}  // namespace softsub::app
