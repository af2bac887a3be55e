#pragma once
// Every validation rule of the scene reader, one row each: a scene that breaks the rule,
// the line (the line holding the marker <!--E-->), the element path and words of the
// message. Shared by the reader's tests (tests/scene) and the command-line tests
// (tests/app), which run each row through `softsub run` for the exit code.
#include <ostream>
#include <string>
#include <vector>

#include "scene_test_util.h"

namespace softsub::scene::rules {

using testing::lineOf;
using testing::readError;
using testing::sceneWith;
using testing::validFluid;

constexpr std::string_view kMark = "<!--E-->";

struct Row {
  std::string name;     // test name
  std::string text;     // the scene
  std::string element;  // expected element path, exactly
  std::string problem;  // expected in the problem
  std::string allowed;  // expected in the allowed rule ("" = not checked)
};

// Rows print as their names in test output.
inline void PrintTo(const Row& row, std::ostream* os) { *os << row.name; }

// A scene with the given body.
inline std::string S(std::string_view body) { return sceneWith(body); }

// A scene with one valid fluid 'w' that also holds inner.
inline std::string F(std::string_view inner) {
  return S("<Fluid>\n<Name>w</Name>\n<Fill><Shape>box</Shape><Max>2 2 2</Max></Fill>\n" +
           std::string(inner) + "\n</Fluid>");
}

// A scene with fluids 'w' and 'v' and the given <Interactions> content.
inline std::string I(std::string_view inner) {
  return S(validFluid("w") + validFluid("v") + "<Interactions>\n" + std::string(inner) +
           "\n</Interactions>");
}

// A FluidFluid holding only the function element fn.
inline std::string FF(std::string_view fn) { return I("<FluidFluid>\n" + std::string(fn) + "\n</FluidFluid>"); }

// A fluid with the given inner elements (no default source).
inline std::string bareFluid(std::string_view inner) { return S("<Fluid>\n" + std::string(inner) + "\n</Fluid>"); }

inline std::string fill(std::string_view inner) { return F("<Fill>\n" + std::string(inner) + "\n</Fill>"); }

// n valid fluids named f0, f1, ..., one per line.
inline std::string manyFluids(std::size_t n) {
  std::string out;
  // (append, not "f" + to_string(i): GCC 12 warns -Wrestrict inside operator+.)
  for (std::size_t i = 0; i < n; ++i) out += validFluid(std::string("f").append(std::to_string(i)));
  return out;
}

inline std::vector<Row> rows() {
  const std::string fillPath = "Fluid 'w'/Fill[2]";
  return {
      // --- XML and the root ----------------------------------------------------------
      {"MalformedXml", "<Scene version=\"1\">\n<Simulation>\n</Scene><!--E-->\n", "XML",
       "not well-formed", "well-formed XML"},
      {"EmptyDocument", "<!--E-->", "Scene", "no root element", "<Scene version=\"1\">"},
      {"UnquotedAttribute", "<!-- first line -->\n<Scene version=1><!--E-->\n</Scene>\n", "XML",
       "not well-formed: Error parsing element attribute", ""},
      {"RootNotScene", "<Scen version=\"1\"><!--E-->\n</Scen>\n", "Scen",
       "the root element is <Scen> (did you mean <Scene>?)", "<Scene version=\"1\">"},
      {"TwoRoots", "<Scene/>\n<Scene/><!--E-->\n", "Scene", "a second root element", "exactly one"},
      {"TextOutsideRoot", "<Scene/>\nhello<!--E-->\n", "Scene", "text outside the root", ""},
      {"UnsupportedVersion", "<Scene version=\"2\"><!--E-->\n</Scene>\n", "Scene",
       "unsupported format version '2'", "version=\"1\""},
      {"UnknownRootAttribute", "<Scene version=\"1\" units=\"m\"><!--E-->\n</Scene>\n", "Scene",
       "unknown attribute 'units'", "version"},
      {"UnknownChildAttribute", S("<Simulation fast=\"yes\"><!--E-->\n</Simulation>"), "Simulation",
       "unknown attribute 'fast'", "no attributes"},
      // --- structure -------------------------------------------------------------------
      {"UnknownTopElement", S("<Simulaton/><!--E-->"), "Simulaton",
       "unknown element <Simulaton> (did you mean <Simulation>?)",
       "in <Scene>: Simulation, Camera, Environment, Fluid, Interactions"},
      {"CaseSensitive", S("<Simulation>\n<substeps>4</substeps><!--E-->\n</Simulation>"),
       "Simulation/substeps", "element names are case-sensitive", "Substeps"},
      {"UnknownFluidTag", F("<Viscosty>2</Viscosty><!--E-->"), "Fluid 'w'/Viscosty",
       "unknown element <Viscosty> (did you mean <Viscosity>?)", "InteractionDistance, Amplitude"},
      {"DuplicateTag", S("<Simulation>\n<Substeps>4</Substeps>\n<Substeps>5</Substeps><!--E-->\n</Simulation>"),
       "Simulation/Substeps", "<Substeps> is given twice (first at line 3)", "one <Substeps>"},
      {"DuplicateElement", S("<Simulation/>\n<Simulation/><!--E-->"), "Simulation", "given twice",
       "one <Simulation> in each <Scene>"},
      {"ObjectRefused", S("<Object><!--E-->\n<Mass>2</Mass>\n</Object>"), "Object",
       "rigid objects are not supported yet (they arrive with rigid bodies, issue #3)", ""},
      {"FluidObjectRefused", I("<FluidObject><Linear/></FluidObject><!--E-->"),
       "Interactions/FluidObject", "rigid objects are not supported yet", "FluidFluid, Pair"},
      {"StrayText", S("<Simulation>\nhello<!--E-->\n<Substeps>4</Substeps>\n</Simulation>"),
       "Simulation", "unexpected text 'hello'", "child elements only"},
      {"ChildInsideValue", S("<Simulation>\n<Substeps><x/></Substeps><!--E-->\n</Simulation>"),
       "Simulation/Substeps/x", "unknown element <x>", "a value only"},
      // --- numbers and value kinds ---------------------------------------------------------
      {"NotANumber", S("<Simulation><FramesPerSecond>fast</FramesPerSecond><!--E--></Simulation>"),
       "Simulation/FramesPerSecond", "'fast' is not a number", "(0, 1000]"},
      {"TrailingGarbage", S("<Simulation><FramesPerSecond>24fps</FramesPerSecond><!--E--></Simulation>"),
       "Simulation/FramesPerSecond", "'24fps' is not a number", ""},
      {"CommaDecimal", S("<Camera><VerticalAngle>2,5</VerticalAngle><!--E--></Camera>"),
       "Camera/VerticalAngle", "'2,5' is not a number", "any finite number"},
      {"NotFiniteNan", S("<Camera><VerticalAngle>nan</VerticalAngle><!--E--></Camera>"),
       "Camera/VerticalAngle", "'nan' is not a finite number", ""},
      {"NotFiniteInf", S("<Camera><Eye>0 inf 0</Eye><!--E--></Camera>"), "Camera/Eye",
       "'inf' is not a finite number", "3 finite numbers"},
      {"NumberTooBig", S("<Camera><HorizontalAngle>1e999</HorizontalAngle><!--E--></Camera>"),
       "Camera/HorizontalAngle", "beyond the range of numbers", ""},
      // The model and the caches store floats: a real must fit single precision.
      {"PositionBeyondSinglePrecision", F("<Particles>0 0 1e39</Particles><!--E-->"), "Fluid 'w'/Particles",
       "'1e39' is too large for single precision", "|value| <= 3.4e38"},
      {"GravityBeyondSinglePrecision", S("<Simulation><Gravity>0 -3.5e38 0</Gravity><!--E--></Simulation>"),
       "Simulation/Gravity", "'-3.5e38' is too large for single precision", "|value| <= 3.4e38"},
      {"FunctionParameterBeyondSinglePrecision", FF("<Linear><AtZero>1e300</AtZero><!--E--></Linear>"),
       "Interactions/FluidFluid/Linear/AtZero", "'1e300' is too large for single precision",
       "|value| <= 3.4e38"},
      {"FpsZero", S("<Simulation><FramesPerSecond>0</FramesPerSecond><!--E--></Simulation>"),
       "Simulation/FramesPerSecond", "0 is out of range", "(0, 1000]"},
      {"FpsTooHigh", S("<Simulation><FramesPerSecond>1000.5</FramesPerSecond><!--E--></Simulation>"),
       "Simulation/FramesPerSecond", "1000.5 is out of range", "(0, 1000]"},
      {"SubstepsZero", S("<Simulation><Substeps>0</Substeps><!--E--></Simulation>"),
       "Simulation/Substeps", "0 is out of range", "integer [1, 10000]"},
      {"SubstepsNotInteger", S("<Simulation><Substeps>2.5</Substeps><!--E--></Simulation>"),
       "Simulation/Substeps", "'2.5' is not an integer", "integer [1, 10000]"},
      {"FramesNegative", S("<Simulation><Frames>-1</Frames><!--E--></Simulation>"),
       "Simulation/Frames", "-1 is out of range", "integer [0, 1000000]"},
      {"FramesHuge", S("<Simulation><Frames>99999999999999999999</Frames><!--E--></Simulation>"),
       "Simulation/Frames", "beyond the range of integers", ""},
      {"EmptyValue", S("<Simulation><Substeps></Substeps><!--E--></Simulation>"),
       "Simulation/Substeps", "the value is empty", ""},
      {"TwoValues", S("<Simulation><Substeps>1 2</Substeps><!--E--></Simulation>"),
       "Simulation/Substeps", "expected one value, got 2", ""},
      {"VectorTooShort", S("<Simulation><Gravity>0 -9.81</Gravity><!--E--></Simulation>"),
       "Simulation/Gravity", "expected 3 numbers, got 2", "3 finite numbers"},
      {"VectorTooLong", S("<Simulation><Gravity>0 -9.81 0 1</Gravity><!--E--></Simulation>"),
       "Simulation/Gravity", "expected 3 numbers, got 4", ""},
      {"VectorNotNumbers", S("<Camera><Eye>a b c</Eye><!--E--></Camera>"), "Camera/Eye",
       "'a' is not a number", ""},
      {"UnknownIntegrator", S("<Simulation><Integrator>rk4</Integrator><!--E--></Simulation>"),
       "Simulation/Integrator", "'rk4' is not one of the choices",
       "explicit-euler, symplectic-euler, velocity-verlet"},
      {"NotBoolean", S("<Environment><Reflective>yes</Reflective><!--E--></Environment>\n" + validFluid("w")),
       "Environment/Reflective", "'yes' is not a boolean", "true, false, 1, 0"},
      {"ColourOutOfRange", F("<Colour>0.5 1.5 0</Colour><!--E-->"), "Fluid 'w'/Colour",
       "1.5 is out of range", "3 numbers in [0, 1]"},
      // --- Environment -------------------------------------------------------------------
      {"WidthZero", S("<Environment><Width>0</Width><!--E--></Environment>"), "Environment/Width",
       "0 is out of range", "> 0"},
      {"HeightNegative", S("<Environment><Height>-1</Height><!--E--></Environment>"),
       "Environment/Height", "-1 is out of range", "> 0"},
      {"DepthZero", S("<Environment><Depth>0</Depth><!--E--></Environment>"), "Environment/Depth",
       "out of range", "> 0"},
      {"NormalAttenuationAboveOne",
       S("<Environment><NormalAttenuation>1.5</NormalAttenuation><!--E--></Environment>"),
       "Environment/NormalAttenuation", "1.5 is out of range", "[0, 1]"},
      {"TangentAttenuationNegative",
       S("<Environment><TangentAttenuation>-0.1</TangentAttenuation><!--E--></Environment>"),
       "Environment/TangentAttenuation", "-0.1 is out of range", "[0, 1]"},
      {"ClosedNotBoolean", S("<Environment><Closed>2</Closed><!--E--></Environment>"),
       "Environment/Closed", "'2' is not a boolean", ""},
      // --- Fluid -------------------------------------------------------------------------
      {"MissingName", S("<Fluid><!--E-->\n<Fill><Shape>box</Shape></Fill>\n</Fluid>"),
       "Fluid[1]", "missing required <Name>", "letters, digits, _ and -"},
      {"EmptyName", bareFluid("<Name> </Name><!--E-->\n<Fill><Shape>box</Shape></Fill>"),
       "Fluid[1]/Name", "the value is empty", ""},
      {"NameWithSpace", bareFluid("<Name>ho ney</Name><!--E-->\n<Fill><Shape>box</Shape></Fill>"),
       "Fluid[1]/Name", "'ho ney' is not a valid fluid name", "letters, digits, _ and -"},
      {"NameWithSlash", bareFluid("<Name>a/b</Name><!--E-->\n<Fill><Shape>box</Shape></Fill>"),
       "Fluid[1]/Name", "'a/b' is not a valid fluid name", ""},
      {"DuplicateFluidName",
       S(validFluid("w") + "<Fluid>\n<Name>w</Name><!--E-->\n<Fill><Shape>box</Shape></Fill>\n</Fluid>"),
       "Fluid 'w'/Name", "the fluid name 'w' is already used (line 2)", "a name no other fluid has"},
      {"InteractionDistanceZero", F("<InteractionDistance>0</InteractionDistance><!--E-->"),
       "Fluid 'w'/InteractionDistance", "0 is out of range", "> 0"},
      {"AmplitudeNegative", F("<Amplitude>-1</Amplitude><!--E-->"), "Fluid 'w'/Amplitude",
       "-1 is out of range", ">= 0"},
      {"FiniteDistanceZero", F("<FiniteDistance>0</FiniteDistance><!--E-->"),
       "Fluid 'w'/FiniteDistance", "0 is out of range", "> 0"},
      {"MinimumAboveMaximum",
       F("<MinimumForce>10</MinimumForce>\n<MaximumForce>5</MaximumForce><!--E-->"),
       "Fluid 'w'/MaximumForce", "MinimumForce (10) is greater than MaximumForce (5)",
       "MinimumForce <= MaximumForce"},
      {"MinimumAboveDefaultMaximum", F("<MinimumForce>500</MinimumForce><!--E-->"),
       "Fluid 'w'/MinimumForce", "MinimumForce (500) is greater than MaximumForce (400)", ""},
      {"ViscosityNegative", F("<Viscosity>-0.5</Viscosity><!--E-->"), "Fluid 'w'/Viscosity",
       "-0.5 is out of range", ">= 0"},
      {"ParticleSizeZero", F("<ParticleSize>0</ParticleSize><!--E-->"), "Fluid 'w'/ParticleSize",
       "0 is out of range", "> 0"},
      {"ParticleMassNegative", F("<ParticleMass>-2</ParticleMass><!--E-->"),
       "Fluid 'w'/ParticleMass", "-2 is out of range", "[1e-30, 1e+30]"},
      {"ParticleMassTinyInverseOverflows", F("<ParticleMass>1e-39</ParticleMass><!--E-->"),
       "Fluid 'w'/ParticleMass", "1e-39 is out of range", "[1e-30, 1e+30]"},
      {"InitialSpeedTwoNumbers", F("<InitialSpeed>1 2</InitialSpeed><!--E-->"),
       "Fluid 'w'/InitialSpeed", "expected 3 numbers, got 2", ""},
      {"CountMismatch",
       F("<NumberOfParticles>3</NumberOfParticles><!--E-->\n<Particles>0 0 0 1 1 1</Particles>"),
       "Fluid 'w'/NumberOfParticles", "NumberOfParticles is 3 but <Particles> holds 2 positions",
       "the number of positions in <Particles>"},
      {"CountWithoutParticles", F("<NumberOfParticles>2</NumberOfParticles><!--E-->"),
       "Fluid 'w'/NumberOfParticles", "NumberOfParticles is 2 but <Particles> holds 0", ""},
      {"CountNegative", F("<NumberOfParticles>-1</NumberOfParticles><!--E-->"),
       "Fluid 'w'/NumberOfParticles", "-1 is out of range", "integer >= 0"},
      {"PositionsNotTriples", F("<Particles>0 0 0<!--E-->\n1 1</Particles>"),
       "Fluid 'w'/Particles", "5 numbers do not make whole positions (3 numbers each)", ""},
      {"PositionNotFinite", F("<Particles>0 0 nan</Particles><!--E-->"), "Fluid 'w'/Particles",
       "'nan' is not a finite number", ""},
      // Refused at the first fluid past the cap, before anything after it is read (the
      // last fluid's own error is never reached).
      {"TooManyFluids",
       S(manyFluids(kMaxFluids) +
         "<Fluid><!--E-->\n<Name>one-more</Name>\n<Fill><Shape>box</Shape></Fill>\n</Fluid>\n"
         "<Fluid><Name>bad name</Name><Viscosity>-1</Viscosity></Fluid>"),
       "Fluid 'one-more'", "the scene has 1026 fluids, more than the cap of 1024", "at most 1024 fluids"},
      {"NoParticleSource", S("<Fluid><!--E-->\n<Name>w</Name>\n</Fluid>"), "Fluid 'w'",
       "the fluid has no particles", "explicit <Particles> or at least one <Fill>"},
      {"ZeroCountNoFill",
       S("<Fluid><!--E-->\n<Name>w</Name>\n<NumberOfParticles>0</NumberOfParticles>\n</Fluid>"),
       "Fluid 'w'", "the fluid has no particles", ""},
      // --- Fill --------------------------------------------------------------------------
      {"FillMissingShape", F("<Fill><!--E-->\n<Spacing>1</Spacing>\n</Fill>"), fillPath,
       "missing required <Shape>", "box, sphere, mesh"},
      {"FillUnknownShape", fill("<Shape>cube</Shape><!--E-->"), fillPath + "/Shape",
       "'cube' is not one of the choices", "box, sphere, mesh"},
      // Mesh fills. The rows need no mesh on disk (the reader refuses before loading, or
      // the file is missing); tests/scene/test_mesh_fill.cpp has the file-based cases.
      {"FillMeshWithoutGeometry",
       F("<Fill><!--E-->\n<Shape>mesh</Shape>\n<Spacing>0.5</Spacing>\n</Fill>"), fillPath,
       "missing required <Geometry>", "relative path"},
      {"FillMeshWithoutSpacing",
       F("<Fill><!--E-->\n<Shape>mesh</Shape>\n<Geometry>honeyGeo/blob.obj</Geometry>\n</Fill>"),
       fillPath, "missing required <Spacing>", "> 0"},
      {"FillMeshAbsolutePath",
       fill("<Shape>mesh</Shape>\n<Spacing>0.5</Spacing>\n<Geometry>/etc/blob.obj</Geometry><!--E-->"),
       fillPath + "/Geometry", "'/etc/blob.obj' is an absolute path",
       "a path inside the scene's folder, e.g. honeyGeo/blob.obj"},
      {"FillMeshDotDotEscape",
       fill("<Shape>mesh</Shape>\n<Spacing>0.5</Spacing>\n<Geometry>../blob.obj</Geometry><!--E-->"),
       fillPath + "/Geometry", "'../blob.obj' leaves the scene's folder",
       "a path inside the scene's folder"},
      {"FillMeshDotDotEscapeInside",
       fill("<Shape>mesh</Shape>\n<Spacing>0.5</Spacing>\n<Geometry>geo/../../x/blob.obj</Geometry><!--E-->"),
       fillPath + "/Geometry", "'geo/../../x/blob.obj' leaves the scene's folder",
       "a path inside the scene's folder"},
      {"FillMeshFolderItself",
       fill("<Shape>mesh</Shape>\n<Spacing>0.5</Spacing>\n<Geometry>geo/..</Geometry><!--E-->"),
       fillPath + "/Geometry", "names the scene's folder itself", "a path inside the scene's folder"},
      {"FillMeshMissingFile",
       fill("<Shape>mesh</Shape>\n<Spacing>0.5</Spacing>\n<Geometry>noSuchGeo/blob.obj</Geometry><!--E-->"),
       fillPath + "/Geometry", "cannot use the mesh 'noSuchGeo/blob.obj'", "a readable mesh file"},
      {"FillMeshSpacingZero",
       fill("<Shape>mesh</Shape>\n<Geometry>a.obj</Geometry>\n<Spacing>0</Spacing><!--E-->"),
       fillPath + "/Spacing", "0 is out of range", "> 0"},
      {"FillBoxWithSurface", fill("<Shape>box</Shape>\n<Surface>true</Surface><!--E-->"),
       fillPath + "/Surface", "<Surface> belongs to mesh fills, not to box fills",
       "Shape, Spacing, Min, Max"},
      {"FillMeshWithRadius",
       fill("<Shape>mesh</Shape>\n<Radius>2</Radius><!--E-->\n<Geometry>a.obj</Geometry>"),
       fillPath + "/Radius", "<Radius> belongs to sphere fills, not to mesh fills",
       "Shape, Spacing, Geometry, Surface"},
      {"FillBoxMinNotBelowMax",
       fill("<Shape>box</Shape>\n<Min>0 3 0</Min>\n<Max>2 3 2</Max><!--E-->"), fillPath + "/Max",
       "Min y (3) is not below Max y (3)", "Min < Max on every axis"},
      {"FillSpacingZero", fill("<Shape>box</Shape>\n<Spacing>0</Spacing><!--E-->"),
       fillPath + "/Spacing", "0 is out of range", "> 0"},
      {"FillBoxWithRadius", fill("<Shape>box</Shape>\n<Radius>2</Radius><!--E-->"),
       fillPath + "/Radius", "<Radius> belongs to sphere fills, not to box fills",
       "Shape, Spacing, Min, Max"},
      {"FillSphereWithMin", fill("<Shape>sphere</Shape>\n<Min>0 0 0</Min><!--E-->"),
       fillPath + "/Min", "<Min> belongs to box fills, not to sphere fills",
       "Shape, Spacing, Center, Radius"},
      {"FillSphereRadiusZero", fill("<Shape>sphere</Shape>\n<Radius>0</Radius><!--E-->"),
       fillPath + "/Radius", "0 is out of range", "> 0"},
      {"FillUnknownTag", fill("<Shape>box</Shape>\n<Step>1</Step><!--E-->"), fillPath + "/Step",
       "unknown element <Step>", "in <Fill>: Shape, Spacing, Min, Max"},
      {"FillMakesNothing",
       F("<Fill><!--E-->\n<Shape>box</Shape>\n<Max>0.5 2 2</Max>\n<Spacing>1</Spacing>\n</Fill>"),
       fillPath, "the fill makes no particles", "at least Spacing wide"},
      {"TooManyParticles",
       S("<Fluid><!--E-->\n<Name>big</Name>\n<Fill><Shape>box</Shape><Max>1000 1000 1000</Max></Fill>\n</Fluid>"),
       "Fluid 'big'", "the scene makes 1000000000 particles (explicit positions plus fills), "
                      "more than the cap of 20000000",
       "at most 20000000 particles"},
      // --- Interactions ------------------------------------------------------------------
      {"FluidFluidWithoutFunction", I("<FluidFluid><!--E-->\n<Damping>1</Damping>\n</FluidFluid>"),
       "Interactions/FluidFluid", "missing the function element",
       "exactly one of Linear, LennardJones, LennardJonesForce, Curve"},
      {"TwoFunctions", I("<FluidFluid>\n<Linear/>\n<Curve><Points>0 1 1 0</Points></Curve><!--E-->\n</FluidFluid>"),
       "Interactions/FluidFluid/Curve", "a second function <Curve> after <Linear>", "exactly one of"},
      {"DampingNegative", I("<FluidFluid><Linear/>\n<Damping>-1</Damping><!--E-->\n</FluidFluid>"),
       "Interactions/FluidFluid/Damping", "-1 is out of range", ">= 0"},
      {"RelativeVelocityNegative",
       I("<FluidFluid><Linear/>\n<RelativeVelocity>-1</RelativeVelocity><!--E-->\n</FluidFluid>"),
       "Interactions/FluidFluid/RelativeVelocity", "-1 is out of range", ">= 0"},
      {"LinearCutoffZero", FF("<Linear><Cutoff>0</Cutoff><!--E--></Linear>"),
       "Interactions/FluidFluid/Linear/Cutoff", "0 is out of range", "> 0"},
      {"LinearMinAboveMax", FF("<Linear>\n<Min>3</Min>\n<Max>1</Max><!--E-->\n</Linear>"),
       "Interactions/FluidFluid/Linear/Max", "Min (3) is greater than Max (1)", "Min <= Max"},
      {"LennardJonesAmplitudeNegative",
       FF("<LennardJones><Amplitude>-1</Amplitude><!--E--></LennardJones>"),
       "Interactions/FluidFluid/LennardJones/Amplitude", "-1 is out of range", ">= 0"},
      {"LennardJonesFiniteDistanceZero",
       FF("<LennardJones><FiniteDistance>0</FiniteDistance><!--E--></LennardJones>"),
       "Interactions/FluidFluid/LennardJones/FiniteDistance", "0 is out of range", "> 0"},
      {"LennardJonesMinAboveMax", FF("<LennardJones>\n<Min>20</Min><!--E-->\n</LennardJones>"),
       "Interactions/FluidFluid/LennardJones/Min", "Min (20) is greater than Max (10)", ""},
      {"LennardJonesCutoffZero", FF("<LennardJones><Cutoff>0</Cutoff><!--E--></LennardJones>"),
       "Interactions/FluidFluid/LennardJones/Cutoff", "0 is out of range", "> 0"},
      {"LennardJonesForceEpsilonNegative",
       FF("<LennardJonesForce><Epsilon>-1</Epsilon><!--E--></LennardJonesForce>"),
       "Interactions/FluidFluid/LennardJonesForce/Epsilon", "-1 is out of range", ">= 0"},
      {"LennardJonesForceSigmaZero",
       FF("<LennardJonesForce><Sigma>0</Sigma><!--E--></LennardJonesForce>"),
       "Interactions/FluidFluid/LennardJonesForce/Sigma", "0 is out of range", "> 0"},
      {"LennardJonesForceCutoffNegative",
       FF("<LennardJonesForce><Cutoff>-1</Cutoff><!--E--></LennardJonesForce>"),
       "Interactions/FluidFluid/LennardJonesForce/Cutoff", "-1 is out of range", "> 0"},
      {"CurveOddCount", FF("<Curve><Points>0 1 1 0 2</Points><!--E--></Curve>"),
       "Interactions/FluidFluid/Curve/Points", "5 numbers do not make at least 2 (r, f) points",
       "an even count, at least 4"},
      {"CurveTooFew", FF("<Curve><Points>0 1</Points><!--E--></Curve>"),
       "Interactions/FluidFluid/Curve/Points", "2 numbers do not make at least 2", ""},
      {"CurveNegativeR0", FF("<Curve><Points>-1 1 1 0</Points><!--E--></Curve>"),
       "Interactions/FluidFluid/Curve/Points", "the first r (-1) is negative", "r0 >= 0"},
      {"CurveNotIncreasing", FF("<Curve><Points>0 1 2 0.5 2 0</Points><!--E--></Curve>"),
       "Interactions/FluidFluid/Curve/Points", "r 2 does not increase after r 2 (point 3)",
       "r strictly increasing"},
      {"CurveMissingPoints", FF("<Curve/><!--E-->"), "Interactions/FluidFluid/Curve",
       "missing required <Points>", ""},
      {"CurvePointsNotNumbers", FF("<Curve><Points>0 1 x 0</Points><!--E--></Curve>"),
       "Interactions/FluidFluid/Curve/Points", "'x' is not a number", ""},
      {"PairMissingB", I("<Pair><!--E-->\n<A>w</A>\n<Linear/>\n</Pair>"), "Interactions/Pair[1]",
       "missing required <B>", "the Name of a fluid"},
      {"PairUnknownFluid", I("<Pair>\n<A>w</A>\n<B>oil</B><!--E-->\n<Linear/>\n</Pair>"),
       "Interactions/Pair 'w','oil'/B", "no fluid is named 'oil'", "the Name of a fluid: w, v"},
      {"PairDuplicateReversed",
       I("<Pair><A>w</A><B>v</B><Linear/></Pair>\n<Pair><!--E-->\n<A>v</A><B>w</B><Linear/></Pair>"),
       "Interactions/Pair 'v','w'", "the pair 'v','w' is given twice (first at line 5)",
       "in either order"},
      {"PairWithoutFunction", I("<Pair><!--E-->\n<A>w</A><B>v</B>\n</Pair>"),
       "Interactions/Pair 'w','v'", "missing the function element", "exactly one of"},
      {"PairUnknownTag", I("<Pair><A>w</A><B>v</B><Linear/>\n<C>x</C><!--E-->\n</Pair>"),
       "Interactions/Pair 'w','v'/C", "unknown element <C>",
       "A, B, Damping, RelativeVelocity, Linear, LennardJones, LennardJonesForce, Curve"},
      {"FunctionUnknownTag", FF("<Linear>\n<Slope>2</Slope><!--E-->\n</Linear>"),
       "Interactions/FluidFluid/Linear/Slope", "unknown element <Slope>", "AtZero, Cutoff, Min, Max"},
      {"InteractionsUnknownTag", I("<FluidFluids/><!--E-->"), "Interactions/FluidFluids",
       "unknown element <FluidFluids> (did you mean <FluidFluid>?)", "FluidFluid, Pair"},
      {"PairTwiceSameOrder",
       I("<Pair><A>w</A><B>w</B><Linear/></Pair>\n<Pair><A>w</A><!--E-->\n<B>w</B><Linear/></Pair>"),
       "Interactions/Pair 'w','w'", "given twice", ""},
  };
}

}  // namespace softsub::scene::rules
