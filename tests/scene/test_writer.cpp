// The writer: every field written, and read(write(d)) == d for hand-made and random scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>

#include <fmt/format.h>

#include "core/error.h"
#include "scene/fill.h"
#include "scene/reader.h"
#include "scene/schema.h"
#include "scene/value_text.h"
#include "scene/writer.h"

namespace softsub::scene {
namespace {

SceneDesc roundTrip(const SceneDesc& d) { return readSceneText(writeSceneText(d), "w.scene"); }

FluidDesc fluidWithBox(const std::string& name) {
  FluidDesc f;
  f.name = name;
  f.fills.push_back(FillDesc{});
  return f;
}

TEST(Writer, RoundTripsTheDefaultScene) {
  SceneDesc d;
  EXPECT_EQ(roundTrip(d), d);
  d.fluids.push_back(fluidWithBox("water"));
  EXPECT_EQ(roundTrip(d), d);
}

TEST(Writer, RoundTripsAHandMadeScene) {
  SceneDesc d;
  d.simulation = {30, 16, 400, {0.5, -9.81, 1e-7}, Integrator::ExplicitEuler};
  d.camera = {{-3, 2.25, 1e10}, 12.5, -370};
  d.environment = EnvironmentDesc{10, 5, 2.5, true, 0, 1, true};
  FluidDesc honey;
  honey.name = "honey-1_B";
  honey.params = {2, 0, 0.3, -1e-3, 1e6, 0, 0.25, 1.0 / 3};
  honey.initialSpeed = {0.1, 0.2, 0.3};
  honey.colour = {1, 0, 0.123456789};
  honey.particles = {{0, 0, 0}, {-1.5, 2, 1e-300}, {1.0 / 7, 2.0 / 3, -0.0}};
  FluidDesc oil;
  oil.name = "oil";
  FillDesc ball;
  ball.shape = FillShape::Sphere;
  ball.center = {1, 2, 3};
  ball.radius = 2.5;
  ball.spacing = 0.5;
  FillDesc slab;
  slab.min = {-1, 0, -1};
  slab.max = {1, 0.25, 1};
  slab.spacing = 0.125;
  slab.outsideObjects = true;
  oil.fills = {ball, slab};
  d.fluids = {honey, oil};
  d.interactions.fluidFluid = {forces::LennardJones{2, 0.9, -3, 30, 1.8}, 0.5, 0.25};
  d.interactions.pairs = {
      {"honey-1_B", "oil", {forces::Linear{3, 2, -1, 3}, 1, 0}},
      {"oil", "oil", {forces::LennardJonesForce{0.5, 0.8, 2}, 2, 3}},
      {"honey-1_B", "honey-1_B", {forces::Curve{{0, 10, 0.5, 1, 1.5, -0.25, 2, 0}}, 0, 0}}};
  const SceneDesc back = roundTrip(d);
  EXPECT_EQ(back, d);
  EXPECT_EQ(writeSceneText(back), writeSceneText(d));
}

ObjectDesc primitive(const std::string& name, ObjectShape shape, std::vector<double> size) {
  ObjectDesc o;
  o.name = name;
  o.shape = shape;
  o.size = std::move(size);
  return o;
}

TEST(Writer, RoundTripsObjectsFluidObjectAndPairsWithObjects) {
  SceneDesc d;
  d.fluids = {fluidWithBox("water")};
  ObjectDesc ball = primitive("ball", ObjectShape::Sphere, {0.5});
  ball.particleSize = 0.125;
  ball.uniformScale = 2;
  ball.initialPosition = {1, 2, 3};
  ball.initialRotation = {90, -45, 1.0 / 3};
  ball.initialLinearVelocity = {0, -1, 0.25};
  ball.initialAngularVelocity = {0, 360, 0};
  ball.normalAttenuation = 1;
  ball.tangentAttenuation = 0;
  ball.mass = 1e-3;
  ball.isDynamic = false;
  d.objects = {ball, primitive("cone #1 <a&b>", ObjectShape::Cone, {1, 2}),
               primitive("crate", ObjectShape::Box, {1, 2, 3}),
               primitive("object4", ObjectShape::Cylinder, {0.25, 4})};
  d.interactions.fluidObject = {forces::Curve{{0, 8, 1, 0}}, 0.5, 0};
  d.interactions.pairs = {{"water", "ball", {forces::Linear{3, 2, -1, 3}, 1, 0}},
                          {"cone #1 <a&b>", "water", {forces::LennardJonesForce{}, 0, 2}},
                          {"water", "water", {forces::LennardJones{}, 0, 0}}};
  const std::string text = writeSceneText(d);
  const SceneDesc back = roundTrip(d);
  EXPECT_EQ(back, d) << text;
  EXPECT_EQ(writeSceneText(back), text);
  EXPECT_NE(text.find("<Name>cone #1 &lt;a&amp;b&gt;</Name>"), std::string::npos) << text;
  EXPECT_NE(text.find("<Shape>cylinder</Shape>"), std::string::npos) << text;
  EXPECT_NE(text.find("<Size>1 2 3</Size>"), std::string::npos) << text;
  EXPECT_NE(text.find("<ParticleSize>0.125</ParticleSize>"), std::string::npos) << text;
  EXPECT_NE(text.find("<FluidObject>"), std::string::npos) << text;
  // The automatic particle size (0 in the description) is left out, and no empty Geometry.
  EXPECT_EQ(text.find("<ParticleSize>0</ParticleSize>"), std::string::npos) << text;
  EXPECT_EQ(text.find("<Geometry"), std::string::npos) << text;
}

TEST(Writer, FluidObjectDefaultsRoundTripAndAreTheSeeds) {
  SceneDesc d;
  const InteractionDesc def = InteractionsDesc{}.fluidObject;
  EXPECT_EQ(def.function, forces::PairFunction(forces::Linear{5, 1.5, 0, 5}));
  EXPECT_EQ(def.relativeVelocity, 2);
  const std::string text = writeSceneText(d);
  EXPECT_NE(text.find("<FluidObject>\n      <Linear>\n        <AtZero>5</AtZero>\n        "
                      "<Cutoff>1.5</Cutoff>"),
            std::string::npos)
      << text;
  EXPECT_EQ(roundTrip(d), d);
}

TEST(Writer, WritesEveryTagWithDefaultsAndNicelyIndented) {
  SceneDesc d;
  d.environment.emplace();
  FluidDesc f = fluidWithBox("w");
  f.particles = {{1, 2, 3}, {4, 5, 6}};
  FillDesc ball;
  ball.shape = FillShape::Sphere;
  ball.outsideObjects = true;  // written only when true
  f.fills.push_back(ball);
  d.fluids = {f, fluidWithBox("v"), fluidWithBox("u")};
  d.interactions.pairs = {{"w", "v", {forces::LennardJones{}, 0, 0}},
                          {"v", "u", {forces::LennardJonesForce{}, 0, 0}},
                          {"u", "u", {forces::Curve{{0, 1, 1, 0}}, 0, 0}}};
  const std::string text = writeSceneText(d);
  const auto expectTags = [&](auto table) {
    for (const auto& field : table) {
      const std::string open = fmt::format("<{}>", field.tag);  // "<" + tag trips GCC 12's -Wrestrict
      EXPECT_NE(text.find(open), std::string::npos) << field.tag;
    }
  };
  expectTags(fieldsOf<SimulationDesc>());
  expectTags(fieldsOf<CameraDesc>());
  expectTags(fieldsOf<EnvironmentDesc>());
  expectTags(fieldsOf<FluidDesc>());
  expectTags(fieldsOf<FillDesc>());
  expectTags(fillShapeFields(FillShape::Box));
  expectTags(fillShapeFields(FillShape::Sphere));
  expectTags(fieldsOf<forces::Linear>());
  expectTags(fieldsOf<forces::LennardJones>());
  expectTags(fieldsOf<forces::LennardJonesForce>());
  expectTags(fieldsOf<forces::Curve>());
  expectTags(fieldsOf<InteractionDesc>());
  expectTags(fieldsOf<PairDesc>());
  EXPECT_NE(text.find("<Scene version=\"1\">\n  <Simulation>\n    <FramesPerSecond>24</FramesPerSecond>"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("    <NumberOfParticles>2</NumberOfParticles>\n    <Particles>\n"
                      "      1 2 3\n      4 5 6\n    </Particles>"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("<Gravity>0 -9.81 0</Gravity>"), std::string::npos);
  EXPECT_NE(text.find("<Integrator>symplectic-euler</Integrator>"), std::string::npos);
  EXPECT_EQ(roundTrip(d), d);
}

TEST(Writer, NumbersAreShortestRoundTrip) {
  SceneDesc d;
  d.camera.eye = {0.1, 1e-7, 123456789.125};
  d.camera.verticalAngle = 1.0 / 3;
  const std::string text = writeSceneText(d);
  EXPECT_NE(text.find("<Eye>0.1 1e-07 123456789.125</Eye>"), std::string::npos) << text;
  EXPECT_NE(text.find("<VerticalAngle>0.3333333333333333</VerticalAngle>"), std::string::npos);
}

TEST(Writer, EnvironmentOnlyWhenPresent) {
  SceneDesc d;
  EXPECT_EQ(writeSceneText(d).find("<Environment>"), std::string::npos);
  d.environment.emplace();
  EXPECT_NE(writeSceneText(d).find("<Environment>"), std::string::npos);
}

// Random valid descriptions, driven by the schema tables so new fields are covered too.
class RandomScenes {
 public:
  explicit RandomScenes(std::uint64_t seed) : rng_(seed) {}

  SceneDesc scene() {
    SceneDesc d;
    randomize(fieldsOf<SimulationDesc>(), d.simulation);
    randomize(fieldsOf<CameraDesc>(), d.camera);
    if (coin()) randomize(fieldsOf<EnvironmentDesc>(), d.environment.emplace());
    const int fluids = uniformInt(0, 4);
    for (int i = 0; i < fluids; ++i) d.fluids.push_back(fluid(i));
    const int objects = uniformInt(0, 3);
    for (int i = 0; i < objects; ++i) d.objects.push_back(object(i));
    if (coin()) d.interactions.fluidFluid = interaction();
    if (coin()) d.interactions.fluidObject = interaction();
    std::set<std::pair<std::string, std::string>> used;
    std::vector<std::pair<std::string, bool>> names;  // name, is an object
    for (const auto& f : d.fluids) names.emplace_back(f.name, false);
    for (const auto& o : d.objects) names.emplace_back(o.name, true);
    for (int i = 0; i < 8 && !d.fluids.empty(); ++i) {
      PairDesc p;
      const auto& [a, aObject] = names[uniformIndex(names.size())];
      const auto& [b, bObject] = names[uniformIndex(names.size())];
      if (aObject && bObject) continue;  // objects collide by impulses, never by a Pair
      p.a = a;
      p.b = b;
      if (!used.insert(std::minmax(p.a, p.b)).second) continue;
      p.interaction = interaction();
      d.interactions.pairs.push_back(p);
    }
    return d;
  }

 private:
  bool coin() { return rng_() % 2 == 0; }
  int uniformInt(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }
  std::size_t uniformIndex(std::size_t n) { return static_cast<std::size_t>(rng_() % n); }
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }

  // A number inside the range: full-precision values, short decimals, the ends
  // themselves and tiny or huge magnitudes (up to single precision's, which is what the
  // reader takes), to exercise shortest round-trip printing.
  double real(const Range& r) {
    const double lo = std::isinf(r.min) ? (std::isinf(r.max) ? -1e3 : r.max - 1e3) : r.min;
    const double hi = std::isinf(r.max) ? lo + 1e3 : r.max;
    for (;;) {
      double v = 0;
      switch (rng_() % 5) {
        case 0: v = uniform(lo, hi); break;
        case 1: v = std::round(uniform(lo, hi) * 100) / 100; break;
        case 2: v = coin() ? lo : hi; break;
        case 3: v = lo + std::pow(10.0, uniform(-12, 2)); break;
        default: v = (coin() ? 1 : -1) * std::pow(10.0, uniform(-300, 38.6)); break;
      }
      if (std::isfinite(v) && std::fabs(v) <= kMaxReal && r.contains(v)) return v;
    }
  }

  Value value(const FieldInfo& f) {
    switch (f.kind) {
      case Kind::Real: return real(f.range);
      case Kind::Int: {
        const double lo = std::max(f.range.min, -1e6);
        const double hi = std::min(f.range.max, 1e6);
        return static_cast<std::int64_t>(uniformInt(static_cast<int>(lo), static_cast<int>(hi)));
      }
      case Kind::Bool: return coin();
      case Kind::Vec3:
      case Kind::Colour: return Vec3(real(f.range), real(f.range), real(f.range));
      case Kind::Enum: return static_cast<std::int64_t>(uniformIndex(f.choices.size()));
      case Kind::String:
      case Kind::RealList:
      case Kind::PointList: break;  // set by the callers, who know the rules
    }
    return {};
  }

  template <class S>
  void randomize(std::span<const Field<S>> table, S& s) {
    for (const Field<S>& f : table) {
      const bool generic = f.kind != Kind::String && f.kind != Kind::RealList &&
                           f.kind != Kind::PointList;
      if (f.set != nullptr && generic && coin()) f.set(s, value(f));  // else keep the default
    }
  }

  FluidDesc fluid(int index) {
    FluidDesc f;
    randomize(fieldsOf<FluidDesc>(), f);
    f.name = "fluid_" + std::to_string(index) + (coin() ? "-x" : "");
    if (f.params.minimumForce > f.params.maximumForce) {
      std::swap(f.params.minimumForce, f.params.maximumForce);
    }
    const int explicitCount = coin() ? uniformInt(1, 12) : 0;
    for (int i = 0; i < explicitCount; ++i) {
      f.particles.emplace_back(real(kAnyNumber), real(kAnyNumber), uniform(-5, 5));
    }
    const int fills = explicitCount == 0 ? uniformInt(1, 3) : uniformInt(0, 2);
    for (int i = 0; i < fills; ++i) f.fills.push_back(fill());
    return f;
  }

  // A primitive object (no mesh file): every field random, the name unique (sometimes
  // the reader's own default form, sometimes with spaces and XML characters), Size with the
  // shape's count, and the scale and particle size kept so the particle bound stays small.
  ObjectDesc object(int index) {
    ObjectDesc o;
    randomize(fieldsOf<ObjectDesc>(), o);
    switch (rng_() % 3) {
      case 0: o.name = "object" + std::to_string(index + 1); break;
      case 1: o.name = "body " + std::to_string(index) + " <a & b>"; break;
      default: o.name = "o" + std::to_string(index) + "_\xC3\xA9"; break;  // UTF-8 e-acute
    }
    o.geometry.clear();
    o.shape = static_cast<ObjectShape>(uniformInt(1, 4));  // a primitive
    o.size.clear();
    for (std::size_t i = 0; i < objectSizeCount(o.shape); ++i) o.size.push_back(uniform(0.05, 10));
    o.uniformScale = coin() ? 1.0 : uniform(0.1, 4);
    double largest = 0;
    for (const double v : o.size) largest = std::max(largest, v);
    o.particleSize = coin() ? 0.0 : largest * o.uniformScale / uniform(1, 30);
    return o;
  }

  FillDesc fill() {
    FillDesc f;
    f.shape = coin() ? FillShape::Box : FillShape::Sphere;
    f.spacing = uniform(0.05, 2);
    f.outsideObjects = coin();
    if (f.shape == FillShape::Box) {
      f.min = Vec3(uniform(-50, 50), uniform(-50, 50), uniform(-50, 50));
      for (int a = 0; a < 3; ++a) f.max[a] = f.min[a] + f.spacing * uniform(1.01, 8);
    } else {
      f.center = Vec3(uniform(-50, 50), uniform(-50, 50), uniform(-50, 50));
      f.radius = f.spacing * uniform(0.01, 6);
    }
    return f;
  }

  InteractionDesc interaction() {
    InteractionDesc d;
    randomize(fieldsOf<InteractionDesc>(), d);
    switch (rng_() % 4) {
      case 0: {
        forces::Linear l;
        randomize(fieldsOf<forces::Linear>(), l);
        if (l.min > l.max) std::swap(l.min, l.max);
        d.function = l;
        break;
      }
      case 1: {
        forces::LennardJones l;
        randomize(fieldsOf<forces::LennardJones>(), l);
        if (l.min > l.max) std::swap(l.min, l.max);
        d.function = l;
        break;
      }
      case 2: {
        forces::LennardJonesForce l;
        randomize(fieldsOf<forces::LennardJonesForce>(), l);
        d.function = l;
        break;
      }
      default: {
        forces::Curve c;
        double r = coin() ? 0 : uniform(0, 1);
        const int points = uniformInt(2, 8);
        for (int i = 0; i < points; ++i) {
          c.points.push_back(r);
          c.points.push_back(real(kAnyNumber));
          r += uniform(1e-6, 1);
        }
        d.function = c;
      }
    }
    return d;
  }

  std::mt19937_64 rng_;
};

TEST(Writer, RoundTripsRandomScenes) {
  RandomScenes random(20261121);
  for (int i = 0; i < 300; ++i) {
    const SceneDesc d = random.scene();
    const std::string text = writeSceneText(d);
    SceneDesc back;
    try {
      back = readSceneText(text, "random.scene");
    } catch (const InputError& e) {
      FAIL() << "scene " << i << ": " << e.what() << "\n" << text;
    }
    ASSERT_EQ(back, d) << "scene " << i << "\n" << text;
    ASSERT_EQ(writeSceneText(back), text) << "scene " << i;
  }
}

class WriterFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("softsub_writer_" + std::string(
                                    ::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(WriterFile, WritesReadsBackAndLeavesNoTemporaryFile) {
  SceneDesc d;
  d.fluids.push_back(fluidWithBox("w"));
  const std::string path = (dir_ / "a.scene").string();
  {
    std::ofstream old(path);
    old << "old contents";
  }
  writeSceneFile(d, path);
  EXPECT_EQ(readSceneFile(path), d);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir_)) ++files;
  EXPECT_EQ(files, 1U);
}

TEST_F(WriterFile, MissingFolderIsAnIoError) {
  EXPECT_THROW(writeSceneFile(SceneDesc{}, (dir_ / "no" / "such" / "a.scene").string()), IoError);
}

}  // namespace
}  // namespace softsub::scene
