#include "cmd_fill.h"
#include "number_checks.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <system_error>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cache/atomic_file.h"
#include "cache/ply_format.h"
#include "core/error.h"
#include "core/snapshot.h"
#include "geometry/fill.h"
#include "geometry/mesh_loader.h"
#include "progress.h"
#include "scene/reader.h"
#include "scene/scene_desc.h"
#include "text_format.h"

namespace softsub::app {

CLI::App* addFillCommand(CLI::App& root, FillOptions& o) {
  CLI::App* cmd = root.add_subcommand(
      "fill", "Fill a mesh with particles (the seed's 'convert to particles'): a PLY point cloud or a <Fluid> block");
  cmd->add_option("MESH", o.mesh, "Mesh file (OBJ, PLY, STL, glTF, FBX)")->required()->check(nonEmptyPath(false));
  cmd->add_option("--spacing", o.spacing,
                  "Lattice step = particle diameter, scene units (a finite number > 0)")
      ->required();
  auto* out =
      cmd->add_option("--out", o.out, "Write the particles as a binary PLY point cloud to this .ply file")
          ->check(nonEmptyPath())
          ->check(outputFileWithExtension(".ply", "a PLY point cloud"));
  cmd->add_flag("--scene-snippet", o.sceneSnippet,
                "Print a <Fluid> block with the particles to paste into a .scene (the default without --out)")
      ->excludes(out);
  cmd->add_flag("--surface", o.surface, "Sample the surface only (thin shells, open meshes)");
  cmd->add_option("--name", o.name,
                  "Name of the fluid in the snippet or the PLY: letters, digits, _ and -, at most 100 characters, "
                  "as in a scene (default: filled)");
  cmd->add_option("--max-particles", o.maxParticles, "Refuse fills larger than this (default: 20,000,000)")
      ->transform(particleCap());
  cmd->add_flag("-q,--quiet", o.quiet,
                "No summary on stderr, even on a terminal (errors and warnings are still printed)");
  return cmd;
}

namespace {

// Text for an XML comment: no "--" inside, no '-' at the end (either makes the file
// malformed for strict parsers: xmllint, Python's ElementTree); such a '-' is written %2D.
std::string commentText(const std::string& text) {
  std::string out;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const bool unsafe = text[k] == '-' && (k + 1 == text.size() || text[k + 1] == '-');
    out += unsafe ? std::string("%2D") : std::string(1, text[k]);
  }
  return out;
}

std::string snippet(const FillOptions& o, const geometry::MeshFillResult& r) {
  // The fluid's own scales follow the spacing: particles touch at rest. The comment says
  // how it was made without the command's "--" (not allowed in an XML comment).
  // 1.5 S to 15 digits: 1.5 x 0.3 is 0.44999999999999996 in full.
  std::string s = fmt::format(
      "<!-- softsub fill of {} at spacing {}{}: {} particles -->\n"
      "<!-- Lengths follow the spacing; Amplitude, the force clamps and ParticleMass keep\n"
      "     their defaults, so a spacing below 1 makes a denser, stiffer fluid that may need\n"
      "     more Substeps: softsub info on the scene gives the stability estimate and the\n"
      "     count it asks for. -->\n"
      "<Fluid>\n"
      "  <Name>{}</Name>\n"
      "  <ParticleSize>{}</ParticleSize>\n"
      "  <FiniteDistance>{}</FiniteDistance>\n"
      "  <InteractionDistance>{:.15g}</InteractionDistance>\n"
      "  <NumberOfParticles>{}</NumberOfParticles>\n"
      "  <Particles>\n",
      commentText(o.mesh), o.spacing, o.surface ? ", surface only" : "", r.points.size(), o.name, o.spacing,
      o.spacing, 1.5 * o.spacing, r.points.size());
  // Each coordinate as the float the simulation keeps, in its shortest text: 0.05, not
  // the lattice's 0.04999999999999982 (the same float once read).
  for (const Vec3& p : r.points)
    s += fmt::format("    {} {} {}\n", static_cast<float>(p.x()), static_cast<float>(p.y()),
                     static_cast<float>(p.z()));
  s += "  </Particles>\n</Fluid>\n";
  return s;
}

}  // namespace

int fillCommand(const FillOptions& o) {
  // The name goes into a scene (the snippet, unescaped) or becomes a fluid's (the PLY): the
  // reader's rule for fluid names, checked before the mesh is read.
  scene::checkFluidName(o.name, {"command line", 0, "--name"});
  if (!(o.spacing > 0) || !std::isfinite(o.spacing))
    throw InputError({"command line", 0, "--spacing"}, fmt::format("{} is not a valid spacing", o.spacing),
                     "a finite number > 0");
  // A PLY mesh and the point cloud's --out may be one file (another spelling, a link).
  if (std::error_code ec; !o.out.empty() && std::filesystem::equivalent(o.mesh, o.out, ec) && !ec)
    throw InputError({"command line", 0, "--out"}, fmt::format("'{}' is the mesh being filled", o.out),
                     "another file: the point cloud would replace the mesh");
  geometry::MeshLoadReport report;
  const geometry::TriangleMesh mesh = geometry::loadMesh(o.mesh, &report);
  if (!o.surface)
    if (std::string open = geometry::openMeshWarning(geometry::countEdges(mesh)); !open.empty())
      report.warnings.push_back(std::move(open) + " (--surface)");
  geometry::MeshFillOptions fo;
  fo.spacing = o.spacing;
  fo.surfaceOnly = o.surface;
  fo.maxParticles = o.maxParticles;
  const geometry::MeshFillResult r = [&] {
    try {
      return geometry::fillMesh(mesh, fo);
    } catch (const InputError& e) {  // the fill knows the mesh, not its file: name it
      if (!e.where().file.empty()) throw;
      throw InputError({o.mesh, e.where().line, e.where().element}, e.problem(), e.allowed());
    }
  }();
  const bool talk = !o.quiet && stderrIsTerminal();
  for (const std::string& w : report.warnings)
    fmt::print(stderr, "warning: {}: {}\n", displayFile(o.mesh), w);
  for (const std::string& w : r.warnings) fmt::print(stderr, "warning: {}: {}\n", displayFile(o.mesh), w);
  if (r.points.empty())
    throw InputError({o.mesh, 0, "mesh"}, "the fill produced no particles",
                     "a closed mesh larger than the spacing (or --surface for thin shells)");

  if (!o.out.empty()) {
    FrameSnapshot frame;
    FluidSnapshot f;
    f.name = o.name;
    f.particleSize = static_cast<float>(o.spacing);
    // The colour the <Fluid> block the snippet makes would get (the scene's default):
    // the PLY's colours are a fluid's Colour x 255, never a white of nothing.
    const Vec3 colour = scene::FluidDesc{}.colour;
    f.colour = {static_cast<float>(colour.x()), static_cast<float>(colour.y()),
                static_cast<float>(colour.z())};
    for (std::size_t k = 0; k < r.points.size(); ++k) {
      f.ids.push_back(static_cast<std::uint32_t>(k));
      const Vec3& p = r.points[k];
      f.positions.insert(f.positions.end(),
                         {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
    }
    f.velocities.assign(f.positions.size(), 0.0f);
    frame.fluids.push_back(std::move(f));
    cache::writeFileAtomic(o.out, cache::encodePly(frame));
  } else {
    const std::string text = snippet(o, r);
    std::fwrite(text.data(), 1, text.size(), stdout);
  }
  if (talk)
    fmt::print(stderr, "filled {} from {} (spacing {}{}){}\n", countOf(r.points.size(), "particle"), o.mesh,
               o.spacing, o.surface ? ", surface" : "", o.out.empty() ? "" : fmt::format(" -> {}", o.out));
  return static_cast<int>(ExitCode::Ok);
}

}  // namespace softsub::app
