#include "scene/writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <variant>

#include "core/error.h"
#include "core/xml_text.h"
#include "scene/schema.h"

namespace softsub::scene {

namespace {

// Indented XML output, two spaces a level.
class XmlOut {
 public:
  void open(std::string_view tag, std::string_view attributes = {}) {
    line(fmt::format("<{}{}>", tag, attributes));
    ++depth_;
  }
  void close(std::string_view tag) {
    --depth_;
    line(fmt::format("</{}>", tag));
  }
  void line(std::string_view text) {
    text_.append(static_cast<std::size_t>(2 * depth_), ' ').append(text).append("\n");
  }

  // One field: a value on one line, or a multi-line value (point lists) one item a line.
  // A field still at the placeholder of a default in words (an object's ParticleSize 0,
  // meaning "1/20 of the largest extent") is left out: reading restores it.
  template <class S>
  void fields(std::span<const Field<S>> table, const S& s) {
    for (const Field<S>& f : table) {
      if (f.holdsPlaceholder(s)) continue;
      std::string value;
      appendXmlEscaped(value, formatValue(f, f.get(s)), f.tag);
      if (value.empty()) {
        line(fmt::format("<{}/>", f.tag));
      } else if (value.find('\n') == std::string::npos) {
        line(fmt::format("<{0}>{1}</{0}>", f.tag, value));
      } else {
        open(f.tag);
        std::size_t start = 0;
        while (start <= value.size()) {
          const std::size_t end = std::min(value.find('\n', start), value.size());
          line(std::string_view(value).substr(start, end - start));
          start = end + 1;
        }
        close(f.tag);
      }
    }
  }

  [[nodiscard]] std::string take() { return std::move(text_); }

 private:
  std::string text_;
  int depth_ = 0;
};

template <class F>
void writeFunction(XmlOut& out, std::string_view tag, const F& f) {
  out.open(tag);
  out.fields(fieldsOf<F>(), f);
  out.close(tag);
}

void writeInteraction(XmlOut& out, const InteractionDesc& d) {
  std::visit(
      [&](const auto& f) {
        writeFunction(out, forces::kindName(forces::PairFunction(f)), f);
      },
      d.function);
  out.fields(fieldsOf<InteractionDesc>(), d);
}

}  // namespace

std::string writeSceneText(const SceneDesc& scene) {
  XmlOut out;
  out.line("<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
  out.open("Scene", " version=\"1\"");
  out.open("Simulation");
  out.fields(fieldsOf<SimulationDesc>(), scene.simulation);
  out.close("Simulation");
  out.open("Camera");
  out.fields(fieldsOf<CameraDesc>(), scene.camera);
  out.close("Camera");
  if (scene.environment) {
    out.open("Environment");
    out.fields(fieldsOf<EnvironmentDesc>(), *scene.environment);
    out.close("Environment");
  }
  for (const FluidDesc& fluid : scene.fluids) {
    out.open("Fluid");
    out.fields(fieldsOf<FluidDesc>(), fluid);
    for (const FillDesc& fill : fluid.fills) {
      out.open("Fill");
      out.fields(fieldsOf<FillDesc>(), fill);
      out.fields(fillShapeFields(fill.shape), fill);
      out.close("Fill");
    }
    out.close("Fluid");
  }
  for (const ObjectDesc& object : scene.objects) {
    out.open("Object");
    out.fields(fieldsOf<ObjectDesc>(), object);
    out.close("Object");
  }
  out.open("Interactions");
  out.open("FluidFluid");
  writeInteraction(out, scene.interactions.fluidFluid);
  out.close("FluidFluid");
  out.open("FluidObject");
  writeInteraction(out, scene.interactions.fluidObject);
  out.close("FluidObject");
  for (const PairDesc& pair : scene.interactions.pairs) {
    out.open("Pair");
    out.fields(fieldsOf<PairDesc>(), pair);
    writeInteraction(out, pair.interaction);
    out.close("Pair");
  }
  out.close("Interactions");
  out.close("Scene");
  return out.take();
}

void writeSceneFile(const SceneDesc& scene, const std::string& path) {
  namespace fs = std::filesystem;
  const std::string text = writeSceneText(scene);
  std::random_device random;
  const fs::path target(path);
  const fs::path temp = fs::path(path).concat(fmt::format(".{:08x}.tmp", random()));
  const auto fail = [&](const std::string& why) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw IoError(fmt::format("cannot write scene file '{}': {}", path, why));
  };
  {
    std::ofstream file(temp, std::ios::binary | std::ios::trunc);
    if (!file) fail(std::strerror(errno));
    file.write(text.data(), static_cast<std::streamsize>(text.size()));
    file.flush();
    if (!file) fail("write failed");
  }
  std::error_code ec;
  fs::rename(temp, target, ec);
  if (ec) fail(ec.message());
}

}  // namespace softsub::scene
