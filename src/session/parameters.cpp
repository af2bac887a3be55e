#include "session/parameters.h"

#include <fmt/format.h>

#include "scene/schema.h"
#include "scene/value_text.h"

namespace softsub::session {

namespace {

/// A field an edit may set: a single value (not the name, the particle list or the
/// derived NumberOfParticles).
template <class S>
bool editable(const scene::Field<S>& f) {
  if (f.set == nullptr) return false;
  switch (f.kind) {
    case scene::Kind::Real:
    case scene::Kind::Int:
    case scene::Kind::Bool:
    case scene::Kind::Vec3:
    case scene::Kind::Colour:
    case scene::Kind::Enum: return true;
    case scene::Kind::String:
    case scene::Kind::RealList:
    case scene::Kind::PointList: return false;
  }
  return false;
}

template <class S>
std::vector<std::string_view> editableTags() {
  std::vector<std::string_view> tags;
  for (const scene::Field<S>& f : scene::fieldsOf<S>())
    if (editable(f)) tags.push_back(f.tag);
  return tags;
}

std::string joined(const std::vector<std::string_view>& names) {
  std::string s;
  for (std::string_view n : names) {
    if (!s.empty()) s += ", ";
    s += n;
  }
  return s;
}

InputLocation at(const EditSource& source, std::string_view element, std::string_view tag) {
  return {source.file, source.line, fmt::format("{}/{}", element, tag)};
}

/// The editable field `tag` of S, or InputError listing the editable tags.
template <class S>
const scene::Field<S>& findField(std::string_view element, std::string_view tag, const EditSource& source) {
  for (const scene::Field<S>& f : scene::fieldsOf<S>())
    if (f.tag == tag && editable(f)) return f;
  const std::vector<std::string_view> tags = editableTags<S>();
  throw InputError(at(source, element, tag),
                   fmt::format("{} is not an editable <{}> tag{}", scene::quote(tag), element,
                               scene::nearMiss(tag, tags)),
                   joined(tags));
}

/// Parses `text` as the field's value, or InputError with the field's rule.
template <class S>
scene::Value parseField(const scene::Field<S>& f, std::string_view element, std::string_view text,
                        const EditSource& source) {
  scene::Value v;
  const scene::ValueProblem problem = scene::parseValueText(f, text, v);
  if (!problem.text.empty())
    throw InputError(at(source, element, f.tag), problem.text,
                     problem.allowed.empty() ? scene::allowedText(f) : problem.allowed);
  return v;
}

/// The fluid named `name`, or InputError listing the scene's fluids.
template <class Fluids>
auto& fluidNamed(Fluids& fluids, std::string_view name, const EditSource& source) {
  for (auto& f : fluids)
    if (f.name == name) return f;
  std::vector<std::string_view> names;
  for (const auto& f : fluids) names.push_back(f.name);
  throw InputError({source.file, source.line, "Fluid"},
                   fmt::format("the scene has no fluid named {}", scene::quote(name)),
                   names.empty() ? std::string("none: the scene has no fluids") : joined(names));
}

}  // namespace

std::vector<std::string_view> editableFluidTags() { return editableTags<scene::FluidDesc>(); }

std::vector<std::string_view> editableSimulationTags() { return editableTags<scene::SimulationDesc>(); }

void setFluidParameter(scene::SceneDesc& desc, std::string_view fluid, std::string_view tag,
                       std::string_view valueText, const EditSource& source) {
  scene::FluidDesc& f = fluidNamed(desc.fluids, fluid, source);
  const auto& field = findField<scene::FluidDesc>("Fluid", tag, source);
  field.set(f, parseField(field, "Fluid", valueText, source));
}

void setSimulationParameter(scene::SceneDesc& desc, std::string_view tag, std::string_view valueText,
                            const EditSource& source) {
  const auto& field = findField<scene::SimulationDesc>("Simulation", tag, source);
  field.set(desc.simulation, parseField(field, "Simulation", valueText, source));
}

std::string fluidParameterText(const scene::SceneDesc& desc, std::string_view fluid, std::string_view tag) {
  const EditSource source;
  const scene::FluidDesc& f = fluidNamed(desc.fluids, fluid, source);
  const auto& field = findField<scene::FluidDesc>("Fluid", tag, source);
  return scene::formatValue(field, field.get(f));
}

std::string simulationParameterText(const scene::SceneDesc& desc, std::string_view tag) {
  const auto& field = findField<scene::SimulationDesc>("Simulation", tag, EditSource{});
  return scene::formatValue(field, field.get(desc.simulation));
}

void checkFluidParameter(std::string_view tag, std::string_view valueText, const EditSource& source) {
  (void)parseField(findField<scene::FluidDesc>("Fluid", tag, source), "Fluid", valueText, source);
}

void checkSimulationParameter(std::string_view tag, std::string_view valueText, const EditSource& source) {
  (void)parseField(findField<scene::SimulationDesc>("Simulation", tag, source), "Simulation", valueText,
                   source);
}

}  // namespace softsub::session
