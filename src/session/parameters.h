#pragma once
/// Editing a scene description by scene-file tag, as the viewer's panels and scripts do:
/// `set fluid honey Viscosity 4`. Values are parsed and range-checked by the schema's own
/// declaration of the tag (scene/schema.h), so an edit accepts exactly what a .scene file
/// would. Rules between fields (MinimumForce <= MaximumForce) are checked when the edits
/// are applied (LiveSession::applyEdits validates the whole description).
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "scene/scene_desc.h"

namespace softsub::session {

/// Where an edit comes from, for messages ("live edit", or a script's file and line).
/// The element is filled in by the setters ("Fluid/Viscosity").
struct EditSource {
  std::string file = "live edit";  ///< names the source in messages
  int line = 0;                    ///< 1-based line, 0 = none
};

/// The `<Fluid>` tags setFluidParameter accepts, in schema order: every number, vector and
/// colour of a fluid (InteractionDistance, Amplitude, FiniteDistance, MinimumForce,
/// MaximumForce, Viscosity, ParticleSize, ParticleMass, InitialSpeed, Colour).
[[nodiscard]] std::vector<std::string_view> editableFluidTags();

/// The `<Simulation>` tags setSimulationParameter accepts (FramesPerSecond, Substeps,
/// Frames, Gravity, Integrator).
[[nodiscard]] std::vector<std::string_view> editableSimulationTags();

/// Sets `tag` of the fluid named `fluid` from scene-file text ("4", "0.9 0.6 0.1").
/// Numbers are parsed locale-independently and checked against the tag's range.
/// InputError (element "Fluid/<tag>") naming the allowed values for a bad value, the
/// editable tags for an unknown tag, the scene's fluids for an unknown fluid. `desc` is
/// unchanged on error.
void setFluidParameter(scene::SceneDesc& desc, std::string_view fluid, std::string_view tag,
                       std::string_view valueText, const EditSource& source = {});

/// Sets `tag` of `<Simulation>` from scene-file text ("16", "0 -9.81 0",
/// "velocity-verlet"); same checks and errors as setFluidParameter.
void setSimulationParameter(scene::SceneDesc& desc, std::string_view tag, std::string_view valueText,
                            const EditSource& source = {});

/// The current value of a fluid's tag as scene-file text (for panels and messages).
/// InputError as setFluidParameter for an unknown fluid or tag.
[[nodiscard]] std::string fluidParameterText(const scene::SceneDesc& desc, std::string_view fluid,
                                             std::string_view tag);

/// The current value of a `<Simulation>` tag as scene-file text.
[[nodiscard]] std::string simulationParameterText(const scene::SceneDesc& desc, std::string_view tag);

/// Checks that `valueText` is a valid value of the fluid tag `tag` without a scene
/// (scripts check their lines when read). InputError as setFluidParameter.
void checkFluidParameter(std::string_view tag, std::string_view valueText, const EditSource& source = {});

/// Checks that `valueText` is a valid value of the `<Simulation>` tag `tag`.
void checkSimulationParameter(std::string_view tag, std::string_view valueText, const EditSource& source = {});

}  // namespace softsub::session
