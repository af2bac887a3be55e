#pragma once
/// The viewer's scripted input, for tests and demos: a text file of commands, one per
/// line, run by the front end as if typed (docs/cli.md, `softsub view --script`).
///
/// ```
/// # comments start with '#'; blank lines are ignored
/// set fluid honey Viscosity 8       # set fluid <Name> <Tag> <value...>
/// set simulation Gravity 0 -3 0     # set simulation <Tag> <value...>
/// key SPACE                         # key <R|S|N|M|SPACE|UP|DOWN|LEFT|RIGHT>
/// frames 24                         # advance 24 frames
/// wait 10                           # let 10 drawn frames pass
/// save tweaked.scene                # save <path.scene>
/// screenshot shot.png               # screenshot <path.png>
/// quit
/// ```
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene_desc.h"

namespace softsub::session {

/// What a script line asks for.
enum class ScriptCommandKind : std::uint8_t {
  SetFluid,       ///< args: fluid name, tag, value text
  SetSimulation,  ///< args: tag, value text
  Key,            ///< args: the key's name, upper case (R S N M SPACE UP DOWN LEFT RIGHT)
  Frames,         ///< args: how many frames to advance (>= 1)
  Wait,           ///< args: how many drawn frames to let pass (>= 0)
  Save,           ///< args: the .scene path
  Screenshot,     ///< args: the .png path
  Quit            ///< no args
};

/// One parsed script line.
struct ScriptCommand {
  ScriptCommandKind kind = ScriptCommandKind::Quit;
  std::vector<std::string> args;  ///< see ScriptCommandKind; values and paths as written (trimmed)
  int line = 0;                   ///< 1-based line in the script
  bool operator==(const ScriptCommand&) const = default;
};

/// The keys a script may press.
inline constexpr std::string_view kScriptKeys[] = {"R", "S", "N", "M", "SPACE", "UP", "DOWN", "LEFT", "RIGHT"};

/// The number a Frames or Wait command carries.
[[nodiscard]] std::int64_t scriptCount(const ScriptCommand& command);

/// Parses a script. Tags and values of `set` lines are checked against the scene schema
/// here (the fluid's name only when run). InputError `<fileName>:<line>: <command>:
/// <problem> (allowed: ...)` for a bad line, listing the commands (or keys, tags, values)
/// allowed.
[[nodiscard]] std::vector<ScriptCommand> parseScript(std::string_view text, const std::string& fileName);

/// Reads and parses a script file (IoError if unreadable).
[[nodiscard]] std::vector<ScriptCommand> readScriptFile(const std::filesystem::path& path);

/// Applies a SetFluid or SetSimulation command to `desc` (setFluidParameter /
/// setSimulationParameter, errors naming `fileName` and the command's line).
/// std::invalid_argument for any other command.
void applySetCommand(const ScriptCommand& command, scene::SceneDesc& desc, const std::string& fileName);

}  // namespace softsub::session
