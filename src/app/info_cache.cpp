// `softsub info` on cache files: .sim, .pdc and .ply.
#include <array>
#include <map>

#include <fmt/format.h>

#include "cache/pdc_format.h"
#include "cache/ply_format.h"
#include "cache/sim_format.h"
#include "cmd_info.h"
#include "core/aabb.h"
#include "text_format.h"

namespace softsub::app {

namespace {

std::string_view pdcTypeName(cache::PdcType t) {
  switch (t) {
    case cache::PdcType::Int: return "int";
    case cache::PdcType::IntArray: return "int array";
    case cache::PdcType::Double: return "double";
    case cache::PdcType::DoubleArray: return "double array";
    case cache::PdcType::Vector: return "vector";
    case cache::PdcType::VectorArray: return "vector array";
  }
  return "?";
}

std::string_view plyTypeName(cache::PlyScalar t) {
  constexpr std::array<std::string_view, 8> names{"int8",  "uint8",  "int16",   "uint16",
                                                  "int32", "uint32", "float32", "float64"};
  return names[static_cast<std::size_t>(t)];
}

}  // namespace

void printSimInfo(const std::string& path) {
  const cache::SimFile sim = cache::readSimFile(path);
  std::size_t total = 0;
  for (const FluidSnapshot& f : sim.frame.fluids) total += f.count();
  fmt::print("sim {}: frame {}, time {:g} s, {} fluids, {} particles, {} objects\n", path, sim.frame.frame,
             sim.frame.time, sim.frame.fluids.size(), groupThousands(total), sim.frame.objects.size());
  for (const FluidSnapshot& f : sim.frame.fluids) {
    Aabb box;
    for (std::size_t k = 0; k < f.count(); ++k)
      box.add(f.positions[3 * k], f.positions[3 * k + 1], f.positions[3 * k + 2]);
    fmt::print("  {}: {} particles, bounds {}\n", f.name, groupThousands(f.count()), describeBox(box));
  }
  for (const cache::SimObject& o : sim.frame.objects)
    fmt::print("  object {}: position {:g} {:g} {:g}, rotation {:g} {:g} {:g} {:g}, scale {:g}, file {}\n",
               o.name, o.position[0], o.position[1], o.position[2], o.rotation[0], o.rotation[1],
               o.rotation[2], o.rotation[3], o.uniformScale, o.filename);
}

void printPdcInfo(const std::string& path) {
  const cache::PdcFile pdc = cache::readPdcFile(path);
  fmt::print("pdc {}: version {}, byte order {}, {} particles, {} attributes\n", path, pdc.version,
             pdc.byteOrder, groupThousands(static_cast<std::uint64_t>(pdc.count)), pdc.attributes.size());
  for (const cache::PdcAttribute& a : pdc.attributes)
    fmt::print("  {}: {}, {} values\n", a.name, pdcTypeName(a.type), groupThousands(a.values.size()));
  if (const cache::PdcAttribute* p = pdc.find("position"); p && p->type == cache::PdcType::VectorArray) {
    Aabb box;
    for (std::size_t k = 0; k + 2 < p->values.size(); k += 3) box.add(p->values[k], p->values[k + 1], p->values[k + 2]);
    fmt::print("position bounds {}\n", describeBox(box));
  }
}

void printPlyInfo(const std::string& path) {
  const cache::PlyCloud ply = cache::readPlyFile(path);
  fmt::print("ply {}: {}, {} vertices, {} properties", path, ply.format, groupThousands(ply.vertexCount),
             ply.properties.size());
  if (ply.hasFrame) fmt::print(", frame {}, time {:g} s", ply.frame, ply.time);
  fmt::print("\n");
  for (const cache::PlyProperty& p : ply.properties) fmt::print("  {}: {}\n", p.name, plyTypeName(p.type));
  const cache::PlyProperty* x = ply.find("x");
  const cache::PlyProperty* y = ply.find("y");
  const cache::PlyProperty* z = ply.find("z");
  if (x && y && z) {
    Aabb box;
    for (std::size_t k = 0; k < ply.vertexCount; ++k) box.add(x->values[k], y->values[k], z->values[k]);
    fmt::print("position bounds {}\n", describeBox(box));
  }
  if (const cache::PlyProperty* fluid = ply.find("fluid")) {
    std::map<long long, std::size_t> counts;
    for (double v : fluid->values) ++counts[static_cast<long long>(v)];
    for (const auto& [index, n] : counts) {
      const bool named = index >= 0 && static_cast<std::size_t>(index) < ply.fluidNames.size();
      fmt::print("  fluid {} {}: {} particles\n", index, named ? ply.fluidNames[static_cast<std::size_t>(index)] : "",
                 groupThousands(n));
    }
  }
}

}  // namespace softsub::app
