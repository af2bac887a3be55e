// `softsub info FILE.scene`: what a scene holds, as the solver will see it.
#include <algorithm>
#include <variant>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cmd_info.h"
#include "core/aabb.h"
#include "core/error.h"
#include "scene/bodies.h"
#include "scene/compile.h"
#include "scene/schema.h"
#include "scene_source.h"
#include "solver/stability.h"
#include "text_format.h"

namespace softsub::app {

namespace {

/// "Tag value, Tag value, ..." for every field of `s` the schema declares (long point
/// lists and the fields in `skip` left out).
template <class S>
std::string describeFields(const S& s, std::initializer_list<std::string_view> skip = {}) {
  std::string out;
  for (const auto& f : scene::fieldsOf<S>()) {
    if (f.kind == scene::Kind::PointList) continue;
    if (std::find(skip.begin(), skip.end(), f.tag) != skip.end()) continue;
    // An empty list (an object's Size when a mesh or its Geometry gives the shape) is
    // not shown: "Size ," read as a value left out.
    const std::string value = scene::formatValue(f, f.get(s));
    if (value.empty()) continue;
    if (!out.empty()) out += ", ";
    out += fmt::format("{} {}", f.tag, value);
  }
  return out;
}

std::string describeInteraction(const scene::InteractionDesc& d) {
  const std::string function = std::visit(
      [](const auto& fn) { return fmt::format("{} ({})", forces::kindName(fn), describeFields(fn)); },
      d.function);
  return fmt::format("{}; {}", function, describeFields(d));
}

std::string vec(const Vec3& v) { return fmt::format("{:g} {:g} {:g}", v.x(), v.y(), v.z()); }

}  // namespace

void printSceneInfo(const std::string& path) {
  const LoadedScene loaded = loadScene(path, 0);
  const scene::SceneDesc& d = loaded.desc;
  const scene::Compiled compiled = scene::compile(d);
  // info is asked for: the reader's warnings always go to stderr.
  for (const std::string& w : loaded.warnings) fmt::print(stderr, "warning: {}\n", w);
  for (const std::string& w : compiled.warnings)
    fmt::print(stderr, "warning: {}: {}\n", displayFile(path), w);
  const auto& sim = d.simulation;
  fmt::print("scene {}: {}\n", loaded.name, path);
  fmt::print("simulation: {} frames at {:g} fps ({:g} s), {} substeps (dt {:.4g} s), {}, gravity {}\n",
             sim.frames, sim.framesPerSecond, sim.frames / sim.framesPerSecond, sim.substeps,
             compiled.model.dt(), scene::kIntegratorNames[static_cast<std::size_t>(sim.integrator)],
             vec(sim.gravity));
  // The viewer's stability hint (docs/architecture.md, "Stability estimate").
  if (const solver::StabilityReport st = solver::assessStability(compiled.model, &compiled.state);
      st.worst < st.pairs.size()) {
    const solver::PairStability& p = st.pairs[st.worst];
    // Marginal is where the default functions run at the default 8 substeps (every
    // example is): stable in the estimate's model, with less than its factor 2 in hand.
    const std::string need = st.minimumSubsteps > 0 ? fmt::format("{} substeps", st.minimumSubsteps)
                                                    : std::string("no count up to 10,000");
    const std::string verdict =
        st.verdict == solver::StabilityVerdict::Stable
            ? fmt::format("stable at {} substeps, with a factor 2 in the time step to spare ({} would do)",
                          st.substeps, need)
        : st.verdict == solver::StabilityVerdict::Marginal
            ? fmt::format(
                  "marginal at {} substeps: stable, with less than a factor 2 in the time step to spare "
                  "({} for that)",
                  st.substeps, need)
            : fmt::format("unstable at {} substeps: expect a blow-up ({} for a factor 2 to spare)",
                          st.substeps, need);
    fmt::print("stability (the estimate): {}; most demanding pair {} / {}\n", verdict, p.first, p.second);
  }
  if (d.environment) {
    const auto& e = *d.environment;
    fmt::print("environment: box x [{:g}, {:g}]  y [0, {:g}]  z [{:g}, {:g}], {} top; {}\n", -e.width / 2,
               e.width / 2, e.height, -e.depth / 2, e.depth / 2, e.closed ? "closed" : "open",
               describeFields(e));
  } else {
    fmt::print("environment: none (no walls, no floor)\n");
  }

  const ParticleStore& store = compiled.state.particles;
  std::vector<Aabb> boxes(d.fluids.size());
  for (std::size_t k = 0; k < store.size(); ++k)
    if (store.owner[k] < boxes.size()) boxes[store.owner[k]].add(store.px[k], store.py[k], store.pz[k]);
  const std::size_t bodyParticles = compiled.model.bodies.particleCount();
  fmt::print("fluids: {}, {} particles in all\n", d.fluids.size(),
             groupThousands(compiled.model.particleCount() - bodyParticles));
  for (std::size_t f = 0; f < d.fluids.size(); ++f) {
    const scene::FluidDesc& fluid = d.fluids[f];
    const std::size_t leftOut = compiled.leftOutInsideObjects.empty() ? 0 : compiled.leftOutInsideObjects[f];
    fmt::print(
        "  {}: {} particles ({} explicit, {} fills{}), bounds {}\n", fluid.name,
        groupThousands(compiled.model.fluids[f].count), fluid.particles.size(), fluid.fills.size(),
        leftOut > 0 ? fmt::format("; {} fill points inside objects left out", groupThousands(leftOut)) : "",
        describeBox(boxes[f]));
    fmt::print("    {}\n", describeFields(fluid, {"Name", "NumberOfParticles"}));
    // A <Pair> of the fluid with itself replaces its own function and viscosity: the
    // fields above that make them are then not what the run uses.
    if (std::any_of(d.interactions.pairs.begin(), d.interactions.pairs.end(),
                    [&](const scene::PairDesc& p) { return p.a == fluid.name && p.b == fluid.name; }))
      fmt::print(
          "    not used: InteractionDistance, Amplitude, FiniteDistance, MinimumForce, MaximumForce and "
          "Viscosity (pair {} / {} below replaces its own function and viscosity)\n",
          fluid.name, fluid.name);
  }

  if (!d.objects.empty()) {
    fmt::print("objects: {}, {} particles in all\n", d.objects.size(), groupThousands(bodyParticles));
    for (std::size_t o = 0; o < d.objects.size(); ++o) {
      const scene::ObjectDesc& obj = d.objects[o];
      const rigid::BodyInfo& body = compiled.model.bodies.bodies[o];
      fmt::print("  {}: {}, {} particles of diameter {:g}, {}, mass {:g}\n", obj.name,
                 obj.geometry.empty() ? std::string(scene::kObjectShapeNames[static_cast<std::size_t>(obj.shape)])
                                      : obj.geometry,
                 groupThousands(body.count), 2 * body.particleRadius, obj.isDynamic ? "dynamic" : "static", obj.mass);
      // Without <ParticleSize> the field holds 0, a value a scene may not hold: show the
      // diameter the body is filled with (1/20 of its largest extent) instead.
      scene::ObjectDesc shown = obj;
      shown.particleSize = 2 * body.particleRadius;
      fmt::print("    {}\n", describeFields(shown, {"Name", "Geometry", "Mass", "IsDynamic"}));
      // A primitive without Size stands in for the inertia at a size fitted to the mesh.
      if (obj.size.empty() && obj.shape != scene::ObjectShape::Mesh && o < compiled.objectMeshes.size()) {
        // As a scene writes Size: before UniformScale (which scales it), so that the line
        // can be pasted to reproduce the fit.
        const Aabb own = compiled.objectMeshes[o].bounds();
        fmt::print(
            "    Size {:g} (fitted to the mesh's bounding box, for the inertia; before UniformScale)\n",
            fmt::join(scene::inertiaPrimitiveSize(obj, own), " "));
      }
    }
  }

  fmt::print("interactions:\n");
  fmt::print("  fluid/fluid (different fluids): {}\n", describeInteraction(d.interactions.fluidFluid));
  if (!d.objects.empty())
    fmt::print("  fluid/object: {}\n", describeInteraction(d.interactions.fluidObject));
  for (const scene::PairDesc& p : d.interactions.pairs)
    fmt::print("  pair {} / {}: {}\n", p.a, p.b, describeInteraction(p.interaction));
  if (d.interactions.pairs.empty()) fmt::print("  no pair overrides\n");
}

}  // namespace softsub::app
