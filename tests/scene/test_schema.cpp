// The schema tables: consistent with the structs, defaults valid, and the docs in step.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <variant>

#include "scene/schema.h"

namespace softsub::scene {
namespace {

// Visits every table with its element name.
template <class Visitor>
void forEachTable(Visitor&& visit) {
  visit("Simulation", fieldsOf<SimulationDesc>());
  visit("Camera", fieldsOf<CameraDesc>());
  visit("Environment", fieldsOf<EnvironmentDesc>());
  visit("Fluid", fieldsOf<FluidDesc>());
  visit("Fill", fieldsOf<FillDesc>());
  visit("Fill box", fillShapeFields(FillShape::Box));
  visit("Fill sphere", fillShapeFields(FillShape::Sphere));
  visit("Fill mesh", fillShapeFields(FillShape::Mesh));
  visit("Object", fieldsOf<ObjectDesc>());
  visit("Linear", fieldsOf<forces::Linear>());
  visit("LennardJones", fieldsOf<forces::LennardJones>());
  visit("LennardJonesForce", fieldsOf<forces::LennardJonesForce>());
  visit("Curve", fieldsOf<forces::Curve>());
  visit("Interaction", fieldsOf<InteractionDesc>());
  visit("Pair", fieldsOf<PairDesc>());
}

bool holdsKind(Kind kind, const Value& v) {
  switch (kind) {
    case Kind::Real: return std::holds_alternative<double>(v);
    case Kind::Int:
    case Kind::Enum: return std::holds_alternative<std::int64_t>(v);
    case Kind::Bool: return std::holds_alternative<bool>(v);
    case Kind::Vec3:
    case Kind::Colour: return std::holds_alternative<Vec3>(v);
    case Kind::String: return std::holds_alternative<std::string>(v);
    case Kind::RealList: return std::holds_alternative<std::vector<double>>(v);
    case Kind::PointList: return std::holds_alternative<std::vector<Vec3>>(v);
  }
  return false;
}

TEST(Schema, EveryFieldIsWellFormed) {
  forEachTable([](std::string_view element, auto table) {
    ASSERT_FALSE(table.empty()) << element;
    for (const auto& f : table) {
      SCOPED_TRACE(std::string(element) + "/" + std::string(f.tag));
      EXPECT_FALSE(f.tag.empty());
      EXPECT_FALSE(f.unit.empty());
      EXPECT_FALSE(f.meaning.empty());
      EXPECT_NE(f.get, nullptr);
      EXPECT_TRUE(holdsKind(f.kind, f.defaultValue()));
      EXPECT_EQ(f.kind == Kind::Enum, !f.choices.empty());
    }
  });
}

TEST(Schema, DefaultsSatisfyTheirOwnRanges) {
  forEachTable([](std::string_view element, auto table) {
    for (const auto& f : table) {
      // A default in words is decided by the reader; the struct holds only a placeholder.
      if (f.required || !f.defaultText.empty()) continue;
      SCOPED_TRACE(std::string(element) + "/" + std::string(f.tag));
      const Value v = f.defaultValue();
      if (const auto* d = std::get_if<double>(&v)) {
        EXPECT_TRUE(f.range.contains(*d));
      }
      if (const auto* i = std::get_if<std::int64_t>(&v)) {
        if (f.kind == Kind::Int) {
          EXPECT_TRUE(f.range.contains(static_cast<double>(*i)));
        } else {
          EXPECT_LT(static_cast<std::size_t>(*i), f.choices.size());
        }
      }
      if (const auto* p = std::get_if<Vec3>(&v)) {
        for (int a = 0; a < 3; ++a) EXPECT_TRUE(f.range.contains((*p)[a]));
      }
    }
  });
}

TEST(Schema, TagsAreUniqueWithinEachElement) {
  const auto unique = [](std::initializer_list<std::vector<std::string_view>> groups) {
    std::set<std::string_view> seen;
    for (const auto& g : groups) {
      for (const auto t : g) EXPECT_TRUE(seen.insert(t).second) << t;
    }
  };
  const auto tags = [](auto table) {
    std::vector<std::string_view> out;
    for (const auto& f : table) out.push_back(f.tag);
    return out;
  };
  std::vector<std::string_view> fns{"Linear", "LennardJones", "LennardJonesForce", "Curve"};
  unique({tags(fieldsOf<SimulationDesc>())});
  unique({tags(fieldsOf<CameraDesc>())});
  unique({tags(fieldsOf<EnvironmentDesc>())});
  unique({tags(fieldsOf<FluidDesc>()), {"Fill"}});
  unique({tags(fieldsOf<ObjectDesc>())});
  for (const FillShape s : {FillShape::Box, FillShape::Sphere, FillShape::Mesh}) {
    unique({tags(fieldsOf<FillDesc>()), tags(fillShapeFields(s))});
  }
  unique({tags(fieldsOf<InteractionDesc>()), fns});
  unique({tags(fieldsOf<PairDesc>()), tags(fieldsOf<InteractionDesc>()), fns});
}

TEST(Schema, DefaultsComeFromTheStructs) {
  // Spot checks that the tables reach the right members.
  const auto find = [](auto table, std::string_view tag) {
    for (const auto& f : table) {
      if (f.tag == tag) return f.defaultValue();
    }
    return Value{};
  };
  EXPECT_EQ(std::get<double>(find(fieldsOf<FluidDesc>(), "Viscosity")),
            fluid::FluidParams{}.viscosity);
  EXPECT_EQ(std::get<double>(find(fieldsOf<FluidDesc>(), "MaximumForce")),
            fluid::FluidParams{}.maximumForce);
  EXPECT_EQ(std::get<Vec3>(find(fieldsOf<SimulationDesc>(), "Gravity")), Vec3(0, -9.81, 0));
  EXPECT_EQ(std::get<std::int64_t>(find(fieldsOf<SimulationDesc>(), "Integrator")),
            static_cast<std::int64_t>(Integrator::SymplecticEuler));
  EXPECT_EQ(std::get<double>(find(fieldsOf<forces::LennardJonesForce>(), "Cutoff")),
            forces::LennardJonesForce{}.cutoff);
}

TEST(Schema, EnumNamesMatchTheEnums) {
  EXPECT_EQ(kIntegratorNames[static_cast<int>(Integrator::ExplicitEuler)], "explicit-euler");
  EXPECT_EQ(kIntegratorNames[static_cast<int>(Integrator::SymplecticEuler)], "symplectic-euler");
  EXPECT_EQ(kIntegratorNames[static_cast<int>(Integrator::VelocityVerlet)], "velocity-verlet");
  EXPECT_EQ(kFillShapeNames[static_cast<int>(FillShape::Box)], "box");
  EXPECT_EQ(kFillShapeNames[static_cast<int>(FillShape::Sphere)], "sphere");
  EXPECT_EQ(kFillShapeNames[static_cast<int>(FillShape::Mesh)], "mesh");
  EXPECT_EQ(std::size(kObjectShapeNames), 5U);
  EXPECT_EQ(kObjectShapeNames[static_cast<int>(ObjectShape::Mesh)], "mesh");
  EXPECT_EQ(kObjectShapeNames[static_cast<int>(ObjectShape::Sphere)], "sphere");
  EXPECT_EQ(kObjectShapeNames[static_cast<int>(ObjectShape::Cone)], "cone");
  EXPECT_EQ(kObjectShapeNames[static_cast<int>(ObjectShape::Box)], "box");
  EXPECT_EQ(kObjectShapeNames[static_cast<int>(ObjectShape::Cylinder)], "cylinder");
}

TEST(Schema, ObjectSizeCountsFollowTheShape) {
  EXPECT_EQ(objectSizeCount(ObjectShape::Mesh), 0U);
  EXPECT_EQ(objectSizeCount(ObjectShape::Sphere), 1U);
  EXPECT_EQ(objectSizeCount(ObjectShape::Cone), 2U);
  EXPECT_EQ(objectSizeCount(ObjectShape::Cylinder), 2U);
  EXPECT_EQ(objectSizeCount(ObjectShape::Box), 3U);
  EXPECT_EQ(objectSizeWords(ObjectShape::Box), "width height depth");
  EXPECT_EQ(objectSizeWords(ObjectShape::Cone), "radius height");
}

// Fields whose default the reader decides show it in words, and only those hold a
// placeholder the writer leaves out.
TEST(Schema, DefaultsInWordsAreShownAndArePlaceholders) {
  const std::string md = schemaMarkdown();
  EXPECT_NE(md.find("| `ParticleSize` | real | units | 1/20 of the largest extent (after UniformScale) | > 0 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| `Name` | string | - | `object<N>`, N its position among the objects (from 1) |"),
            std::string::npos);
  const ObjectDesc fresh;
  std::set<std::string_view> placeholders;
  for (const auto& f : fieldsOf<ObjectDesc>()) {
    if (f.holdsPlaceholder(fresh)) placeholders.insert(f.tag);
  }
  EXPECT_EQ(placeholders, (std::set<std::string_view>{"Name", "Geometry", "Shape", "Size", "ParticleSize"}));
  ObjectDesc sized;
  sized.particleSize = 0.25;
  sized.shape = ObjectShape::Box;
  for (const auto& f : fieldsOf<ObjectDesc>()) {
    if (f.tag == "ParticleSize" || f.tag == "Shape") {
      EXPECT_FALSE(f.holdsPlaceholder(sized)) << f.tag;
    }
  }
}

// <FluidObject>'s velocity terms default to InteractionsDesc{}.fluidObject, not to
// InteractionDesc{}: the docs table says so.
TEST(Schema, FluidObjectTableShowsItsOwnDefaults) {
  const std::string md = schemaMarkdown();
  const std::size_t at = md.find("### `<FluidObject>`: velocity terms");
  ASSERT_NE(at, std::string::npos);
  const std::size_t end = md.find("###", at + 3);
  const std::string table = md.substr(at, end - at);
  EXPECT_NE(table.find("| `RelativeVelocity` | real | mass/s | `2` |"), std::string::npos) << table;
  EXPECT_NE(table.find("| `Damping` | real | mass/s | `0` |"), std::string::npos) << table;
}

TEST(Schema, RangesDescribeThemselves) {
  EXPECT_EQ(kPositive.describe(), "> 0");
  EXPECT_EQ(kNonNegative.describe(), ">= 0");
  EXPECT_EQ(kUnitInterval.describe(), "[0, 1]");
  EXPECT_EQ((Range{0, 1000, true, false}.describe()), "(0, 1000]");
  EXPECT_EQ((Range{-std::numeric_limits<double>::infinity(), 2, false, true}.describe()), "< 2");
  EXPECT_EQ(kAnyNumber.describe(), "any");
  EXPECT_TRUE(kPositive.contains(1e-300));
  EXPECT_FALSE(kPositive.contains(0));
  EXPECT_TRUE(kUnitInterval.contains(1));
  EXPECT_FALSE((Range{0, 1000, true, false}.contains(0)));
}

TEST(Schema, MarkdownHasEveryTagAndElement) {
  const std::string md = schemaMarkdown();
  forEachTable([&](std::string_view element, auto table) {
    for (const auto& f : table) {
      EXPECT_NE(md.find("| `" + std::string(f.tag) + "` |"), std::string::npos)
          << element << "/" << f.tag;
    }
  });
  for (const ElementInfo& e : elements()) {
    EXPECT_NE(md.find("| `" + std::string(e.name) + "` |"), std::string::npos) << e.name;
  }
  EXPECT_NE(md.find("| Tag | Type | Unit | Default | Allowed | Meaning |"), std::string::npos);
  EXPECT_NE(md.find("| `Substeps` | int | - | `8` | integer [1, 10000] |"), std::string::npos);
}

// docs/scene-format.md must carry the generated tables verbatim, so they cannot drift.
TEST(Schema, DocsContainEveryLineOfTheMarkdown) {
  const std::string path = std::string(SOFTSUB_SOURCE_DIR) + "/docs/scene-format.md";
  std::ifstream in(path);
  ASSERT_TRUE(in) << "cannot open " << path;
  std::set<std::string> docLines;
  for (std::string line; std::getline(in, line);) docLines.insert(line);
  std::istringstream md(schemaMarkdown());
  int missing = 0;
  for (std::string line; std::getline(md, line);) {
    if (line.empty() || docLines.contains(line)) continue;
    ADD_FAILURE() << "docs/scene-format.md lacks the schema line:\n" << line;
    if (++missing > 20) break;
  }
  EXPECT_EQ(missing, 0) << "paste the output of schemaMarkdown() (`softsub schema`) into the docs";
}

}  // namespace
}  // namespace softsub::scene
