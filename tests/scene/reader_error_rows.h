#pragma once
// Every validation rule of the scene reader, one row each: a scene that breaks the rule,
// the line (the line holding the marker <!--E-->), the element path and words of the
// message. Shared by the reader's tests (tests/scene) and the command-line tests
// (tests/app), which run each row through `softsub run` for the exit code.
#include <ostream>
#include <string>
#include <vector>

#include "scene/xml_checks.h"
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

// A scene with fluid 'w' and one object holding inner (its own lines).
inline std::string O(std::string_view inner) {
  return S(validFluid("w") + "<Object>\n" + std::string(inner) + "\n</Object>");
}

// A scene with fluids 'w' and 'v', objects 'ball' and 'crate' (primitives) and the given
// <Interactions> content.
inline std::string IO(std::string_view inner) {
  return S(validFluid("w") + validFluid("v") +
           "<Object><Name>ball</Name><Shape>sphere</Shape><Size>1</Size></Object>\n"
           "<Object><Name>crate</Name><Shape>box</Shape><Size>1 2 3</Size></Object>\n"
           "<Interactions>\n" + std::string(inner) + "\n</Interactions>");
}

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
       "</Scene> does not close <Simulation> (opened at line 2)", "well-formed XML"},
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
      // --- what pugixml lets through (src/scene/xml_checks.cpp) ------------------------
      {"Doctype", "<!DOCTYPE Scene><!--E-->\n<Scene version=\"1\"/>\n", "XML", "a DOCTYPE declaration",
       "no DOCTYPE or entity declarations"},
      {"DoctypeWithEntities",
       "<?xml version=\"1.0\"?>\n<!DOCTYPE Scene [<!ENTITY big \"x\">]><!--E-->\n<Scene version=\"1\"/>\n",
       "XML", "a DOCTYPE declaration", "no DOCTYPE"},
      {"EntityDeclaration", "<!ENTITY big \"x\"><!--E-->\n<Scene version=\"1\"/>\n", "XML",
       "an entity declaration", "no DOCTYPE or entity declarations"},
      {"UnknownEntityReference", F("<Viscosity>&big;</Viscosity><!--E-->"), "XML",
       "the entity reference '&big;': only the five predefined entities exist", "&lt; &gt; &amp;"},
      {"BareAmpersand", F("<Viscosity>1 & 2</Viscosity><!--E-->"), "XML",
       "a '&' that starts no entity or character reference", "&amp;"},
      {"NulCharacterReference", F("<Viscosity>1&#0;</Viscosity><!--E-->"), "XML",
       "a NUL character reference '&#0;'", "of a character XML allows"},
      {"NulHexCharacterReference", F("<Viscosity>&#x0;1</Viscosity><!--E-->"), "XML",
       "a NUL character reference '&#x0;'", ""},
      {"ControlCharacterReference", F("<Viscosity>2&#1;</Viscosity><!--E-->"), "XML",
       "the character reference '&#1;' to U+0001, which XML does not allow", ""},
      {"CharacterReferenceBeyondUnicode", F("<Viscosity>&#x110000;</Viscosity><!--E-->"), "XML",
       "'&#x110000;' is not a character reference", ""},
      {"RawNul", F(std::string("<Viscosity>1") + '\0' + "</Viscosity><!--E-->"), "XML",
       "a NUL character (byte 0)", "no NUL"},
      {"RawControlCharacter", F("<Viscosity>1\x01</Viscosity><!--E-->"), "XML", "a control character U+0001",
       "no control character but tab"},
      {"InvalidUtf8", F("<Viscosity>1\xFF</Viscosity><!--E-->"), "XML", "invalid UTF-8 (byte 0xFF)",
       "UTF-8 text"},
      // Saved as UTF-16 (with and without a byte order mark): "invalid UTF-8 (byte 0xFF)".
      {"Utf16WithByteOrderMark", std::string("\xFF\xFE", 2) + "<!--E-->", "XML", "the file is UTF-16 text",
       "save the file as UTF-8"},
      {"Utf16BigEndianWithoutMark", std::string("\0<", 2) + "<!--E-->", "XML", "the file is UTF-16 text", ""},
      {"Utf16Surrogate", F("<Viscosity>1\xED\xA0\x80</Viscosity><!--E-->"), "XML",
       "invalid UTF-8 (byte 0xED)", ""},
      {"NonCharacterFFFF", F("<Viscosity>1\xEF\xBF\xBF</Viscosity><!--E-->"), "XML",
       "the character U+FFFF, which XML does not allow", ""},
      {"TooDeep",
       "<Scene version=\"1\">" +
           [] {
             std::string s;
             for (std::size_t i = 1; i < kMaxXmlDepth; ++i) s += "<a>";
             return s;
           }() +
           "\n<b><!--E-->\n</Scene>\n",
       "XML", "<b> is nested 33 elements deep", "elements nested at most 32 deep"},
      {"Truncated", "<Scene version=\"1\">\n<Fluid>\n<Name>w</Name>\n<Particles>0 0 0<!--E-->", "XML",
       "the file ends inside <Particles> (opened at line 4): it is truncated", "every element closed"},
      {"EndTagInAnotherCase",
       "<Scene version=\"1\">\n<Fluid><Name>w</Name>\n<Viscosity>1</viscosity><!--E-->\n"
       "<Particles>0 0 0</Particles></Fluid>\n</Scene>\n",
       "XML", "</viscosity> does not close <Viscosity> (opened at line 3): element names are case-sensitive",
       "each element closed by </name> with its own name"},
      {"MissingEndTag",
       "<Scene version=\"1\">\n<Fluid><Name>w</Name>\n<Particles>0 0 0</Particles>\n</Scene><!--E-->\n",
       "XML", "</Scene> does not close <Fluid> (opened at line 2): an element is not closed", ""},
      {"TruncatedInsideATag", "<Scene version=\"1\">\n<Fluid>\n<Name>w</Name>\n<Fill>\n<Shape a=\"<!--E-->",
       "XML", "the file ends inside <Shape> (opened at line 5)", ""},
      {"ProcessingInstructionAfterRoot", "<Scene version=\"1\"/>\n<?render fast?><!--E-->\n", "XML",
       "a processing instruction after the root element", "nothing but comments"},
      {"CdataAfterRoot", "<Scene version=\"1\"></Scene>\n<![CDATA[x]]><!--E-->\n", "XML",
       "a CDATA section after the root element", ""},
      // --- structure -------------------------------------------------------------------
      {"UnknownTopElement", S("<Simulaton/><!--E-->"), "Simulaton",
       "unknown element <Simulaton> (did you mean <Simulation>?)",
       "in <Scene>: Simulation, Camera, Environment, Fluid, Object, Interactions"},
      {"CaseSensitive", S("<Simulation>\n<substeps>4</substeps><!--E-->\n</Simulation>"),
       "Simulation/substeps", "element names are case-sensitive", "Substeps"},
      {"UnknownFluidTag", F("<Viscosty>2</Viscosty><!--E-->"), "Fluid 'w'/Viscosty",
       "unknown element <Viscosty> (did you mean <Viscosity>?)", "InteractionDistance, Amplitude"},
      {"DuplicateTag",
       S("<Simulation>\n<Substeps>4</Substeps>\n<Substeps>5</Substeps><!--E-->\n</Simulation>"),
       "Simulation/Substeps", "<Substeps> is given twice (first at line 3)", "one <Substeps>"},
      {"DuplicateElement", S("<Simulation/>\n<Simulation/><!--E-->"), "Simulation", "given twice",
       "one <Simulation> in each <Scene>"},
      {"StrayText", S("<Simulation>\nhello<!--E-->\n<Substeps>4</Substeps>\n</Simulation>"), "Simulation",
       "unexpected text 'hello'", "child elements only"},
      {"ChildInsideValue", S("<Simulation>\n<Substeps><x/></Substeps><!--E-->\n</Simulation>"),
       "Simulation/Substeps/x", "unknown element <x>", "a value only"},
      // --- numbers and value kinds ---------------------------------------------------------
      {"NotANumber", S("<Simulation><FramesPerSecond>fast</FramesPerSecond><!--E--></Simulation>"),
       "Simulation/FramesPerSecond", "'fast' is not a number", "[0.001, 1000]"},
      {"TrailingGarbage", S("<Simulation><FramesPerSecond>24fps</FramesPerSecond><!--E--></Simulation>"),
       "Simulation/FramesPerSecond", "'24fps' is not a number", ""},
      {"CommaDecimal", S("<Camera><VerticalAngle>2,5</VerticalAngle><!--E--></Camera>"),
       "Camera/VerticalAngle", "'2,5' holds a comma", "with a decimal point"},
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
       "Simulation/FramesPerSecond", "0 is out of range", "[0.001, 1000]"},
      // 1e-300 made the time step 1 / (fps * substeps) infinite: the run then "blew up".
      {"FpsTooSmallForAFiniteTimeStep",
       S("<Simulation><FramesPerSecond>1e-300</FramesPerSecond><!--E--></Simulation>"),
       "Simulation/FramesPerSecond", "1e-300 is out of range", "[0.001, 1000]"},
      {"FpsTooHigh", S("<Simulation><FramesPerSecond>1000.5</FramesPerSecond><!--E--></Simulation>"),
       "Simulation/FramesPerSecond", "1000.5 is out of range", "[0.001, 1000]"},
      {"SubstepsZero", S("<Simulation><Substeps>0</Substeps><!--E--></Simulation>"), "Simulation/Substeps",
       "0 is out of range", "integer [1, 10000]"},
      {"SubstepsNotInteger", S("<Simulation><Substeps>2.5</Substeps><!--E--></Simulation>"),
       "Simulation/Substeps", "'2.5' is not an integer", "integer [1, 10000]"},
      {"FramesNegative", S("<Simulation><Frames>-1</Frames><!--E--></Simulation>"), "Simulation/Frames",
       "-1 is out of range", "integer [0, 1000000]"},
      {"FramesHuge", S("<Simulation><Frames>99999999999999999999</Frames><!--E--></Simulation>"),
       "Simulation/Frames", "beyond the range of integers", ""},
      {"EmptyValue", S("<Simulation><Substeps></Substeps><!--E--></Simulation>"), "Simulation/Substeps",
       "the value is empty", ""},
      {"TwoValues", S("<Simulation><Substeps>1 2</Substeps><!--E--></Simulation>"), "Simulation/Substeps",
       "expected one value, got 2", ""},
      {"VectorTooShort", S("<Simulation><Gravity>0 -9.81</Gravity><!--E--></Simulation>"),
       "Simulation/Gravity", "expected 3 numbers, got 2", "3 finite numbers"},
      {"VectorTooLong", S("<Simulation><Gravity>0 -9.81 0 1</Gravity><!--E--></Simulation>"),
       "Simulation/Gravity", "expected 3 numbers, got 4", ""},
      {"VectorNotNumbers", S("<Camera><Eye>a b c</Eye><!--E--></Camera>"), "Camera/Eye",
       "'a' is not a number", ""},
      {"VectorWithCommas", S("<Simulation><Gravity>0,-9.81,0</Gravity><!--E--></Simulation>"),
       "Simulation/Gravity", "'0,-9.81,0' holds a comma",
       "numbers separated by spaces, with a decimal point"},
      // A bad number deep in a long list is named on its own line, not the list's first.
      {"BadNumberOnItsLine", F("<Particles>0 0 0\n1 0 0\n2 0 0\n3 0 nan</Particles><!--E-->"),
       "Fluid 'w'/Particles", "'nan' is not a finite number", "3 finite numbers per point"},
      {"UnknownIntegrator", S("<Simulation><Integrator>rk4</Integrator><!--E--></Simulation>"),
       "Simulation/Integrator", "'rk4' is not one of the choices",
       "explicit-euler, symplectic-euler, velocity-verlet"},
      {"NotBoolean", S("<Environment><Reflective>yes</Reflective><!--E--></Environment>\n" + validFluid("w")),
       "Environment/Reflective", "'yes' is not a boolean", "true, false, 1, 0"},
      {"ColourOutOfRange", F("<Colour>0.5 1.5 0</Colour><!--E-->"), "Fluid 'w'/Colour", "1.5 is out of range",
       "3 numbers in [0, 1]"},
      // --- Environment -------------------------------------------------------------------
      {"WidthZero", S("<Environment><Width>0</Width><!--E--></Environment>"), "Environment/Width",
       "0 is out of range", "> 0"},
      {"HeightNegative", S("<Environment><Height>-1</Height><!--E--></Environment>"), "Environment/Height",
       "-1 is out of range", "> 0"},
      {"DepthZero", S("<Environment><Depth>0</Depth><!--E--></Environment>"), "Environment/Depth",
       "out of range", "> 0"},
      {"NormalAttenuationAboveOne",
       S("<Environment><NormalAttenuation>1.5</NormalAttenuation><!--E--></Environment>"),
       "Environment/NormalAttenuation", "1.5 is out of range", "[0, 1]"},
      {"TangentAttenuationNegative",
       S("<Environment><TangentAttenuation>-0.1</TangentAttenuation><!--E--></Environment>"),
       "Environment/TangentAttenuation", "-0.1 is out of range", "[0, 1]"},
      {"ClosedNotBoolean", S("<Environment><Closed>2</Closed><!--E--></Environment>"), "Environment/Closed",
       "'2' is not a boolean", ""},
      // --- Fluid -------------------------------------------------------------------------
      {"MissingName", S("<Fluid><!--E-->\n<Fill><Shape>box</Shape></Fill>\n</Fluid>"), "Fluid[1]",
       "missing required <Name>", "letters, digits, _ and -"},
      {"EmptyName", bareFluid("<Name> </Name><!--E-->\n<Fill><Shape>box</Shape></Fill>"), "Fluid[1]/Name",
       "the value is empty", ""},
      {"NameWithSpace", bareFluid("<Name>ho ney</Name><!--E-->\n<Fill><Shape>box</Shape></Fill>"),
       "Fluid[1]/Name", "'ho ney' is not a valid fluid name", "letters, digits, _ and -"},
      // A name is part of file names, and the temporary name of an atomic write adds to it:
      // 235 characters passed the reader and failed at the first write ("File name too long").
      {"NameTooLongForFileNames",
       bareFluid("<Name>" + std::string(101, 'x') + "</Name><!--E-->\n<Fill><Shape>box</Shape></Fill>"),
       "Fluid[1]/Name", "the name is 101 bytes long: its output file names",
       "letters, digits, _ and -, at most 100 characters; unique"},
      {"NameWithSlash", bareFluid("<Name>a/b</Name><!--E-->\n<Fill><Shape>box</Shape></Fill>"),
       "Fluid[1]/Name", "'a/b' is not a valid fluid name", ""},
      {"DuplicateFluidName",
       S(validFluid("w") + "<Fluid>\n<Name>w</Name><!--E-->\n<Fill><Shape>box</Shape></Fill>\n</Fluid>"),
       "Fluid 'w'/Name", "the fluid name 'w' is already used (line 2)",
       "a name no other fluid or object has"},
      {"InteractionDistanceZero", F("<InteractionDistance>0</InteractionDistance><!--E-->"),
       "Fluid 'w'/InteractionDistance", "0 is out of range", "> 0"},
      {"AmplitudeNegative", F("<Amplitude>-1</Amplitude><!--E-->"), "Fluid 'w'/Amplitude",
       "-1 is out of range", ">= 0"},
      {"FiniteDistanceZero", F("<FiniteDistance>0</FiniteDistance><!--E-->"), "Fluid 'w'/FiniteDistance",
       "0 is out of range", "> 0"},
      {"MinimumAboveMaximum", F("<MinimumForce>10</MinimumForce>\n<MaximumForce>5</MaximumForce><!--E-->"),
       "Fluid 'w'/MaximumForce", "MinimumForce (10) is greater than MaximumForce (5)",
       "MinimumForce <= MaximumForce"},
      {"MinimumAboveDefaultMaximum", F("<MinimumForce>500</MinimumForce><!--E-->"), "Fluid 'w'/MinimumForce",
       "MinimumForce (500) is greater than MaximumForce (400)", ""},
      {"ViscosityNegative", F("<Viscosity>-0.5</Viscosity><!--E-->"), "Fluid 'w'/Viscosity",
       "-0.5 is out of range", ">= 0"},
      {"ParticleSizeZero", F("<ParticleSize>0</ParticleSize><!--E-->"), "Fluid 'w'/ParticleSize",
       "0 is out of range", "> 0"},
      {"ParticleMassNegative", F("<ParticleMass>-2</ParticleMass><!--E-->"), "Fluid 'w'/ParticleMass",
       "-2 is out of range", "[1e-30, 1e+30]"},
      {"ParticleMassTinyInverseOverflows", F("<ParticleMass>1e-39</ParticleMass><!--E-->"),
       "Fluid 'w'/ParticleMass", "1e-39 is out of range", "[1e-30, 1e+30]"},
      {"InitialSpeedTwoNumbers", F("<InitialSpeed>1 2</InitialSpeed><!--E-->"), "Fluid 'w'/InitialSpeed",
       "expected 3 numbers, got 2", ""},
      {"CountMismatch",
       F("<NumberOfParticles>3</NumberOfParticles><!--E-->\n<Particles>0 0 0 1 1 1</Particles>"),
       "Fluid 'w'/NumberOfParticles", "NumberOfParticles is 3 but <Particles> holds 2 positions",
       "the number of positions in <Particles>"},
      {"CountWithoutParticles", F("<NumberOfParticles>2</NumberOfParticles><!--E-->"),
       "Fluid 'w'/NumberOfParticles", "NumberOfParticles is 2 but <Particles> holds 0", ""},
      {"CountNegative", F("<NumberOfParticles>-1</NumberOfParticles><!--E-->"), "Fluid 'w'/NumberOfParticles",
       "-1 is out of range", "integer >= 0"},
      {"PositionsNotTriples", F("<Particles>0 0 0<!--E-->\n1 1</Particles>"), "Fluid 'w'/Particles",
       "5 numbers do not make whole positions (3 numbers each)", ""},
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
       S("<Fluid><!--E-->\n<Name>w</Name>\n<NumberOfParticles>0</NumberOfParticles>\n</Fluid>"), "Fluid 'w'",
       "the fluid has no particles", ""},
      // --- Fill --------------------------------------------------------------------------
      {"FillMissingShape", F("<Fill><!--E-->\n<Spacing>1</Spacing>\n</Fill>"), fillPath,
       "missing required <Shape>", "box, sphere, mesh"},
      {"FillUnknownShape", fill("<Shape>cube</Shape><!--E-->"), fillPath + "/Shape",
       "'cube' is not one of the choices", "box, sphere, mesh"},
      // Mesh fills. The rows need no mesh on disk (the reader refuses before loading, or
      // the file is missing); tests/scene/test_mesh_fill.cpp has the file-based cases.
      {"FillMeshWithoutGeometry", F("<Fill><!--E-->\n<Shape>mesh</Shape>\n<Spacing>0.5</Spacing>\n</Fill>"),
       fillPath, "missing required <Geometry>", "relative path"},
      {"FillMeshWithoutSpacing",
       F("<Fill><!--E-->\n<Shape>mesh</Shape>\n<Geometry>honeyGeo/blob.obj</Geometry>\n</Fill>"), fillPath,
       "missing required <Spacing>", "> 0"},
      {"FillMeshAbsolutePath",
       fill("<Shape>mesh</Shape>\n<Spacing>0.5</Spacing>\n<Geometry>/etc/blob.obj</Geometry><!--E-->"),
       fillPath + "/Geometry", "'/etc/blob.obj' is an absolute path",
       "a path inside the scene's folder, e.g. honeyGeo/blob.obj"},
      {"FillMeshDotDotEscape",
       fill("<Shape>mesh</Shape>\n<Spacing>0.5</Spacing>\n<Geometry>../blob.obj</Geometry><!--E-->"),
       fillPath + "/Geometry", "'../blob.obj' leaves the scene's folder", "a path inside the scene's folder"},
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
       "Shape, Spacing, OutsideObjects, Min, Max"},
      {"FillMeshWithRadius",
       fill("<Shape>mesh</Shape>\n<Radius>2</Radius><!--E-->\n<Geometry>a.obj</Geometry>"),
       fillPath + "/Radius", "<Radius> belongs to sphere fills, not to mesh fills",
       "Shape, Spacing, OutsideObjects, Geometry, Surface"},
      {"FillBoxMinNotBelowMax", fill("<Shape>box</Shape>\n<Min>0 3 0</Min>\n<Max>2 3 2</Max><!--E-->"),
       fillPath + "/Max", "Min y (3) is not below Max y (3)", "Min < Max on every axis"},
      {"FillSpacingZero", fill("<Shape>box</Shape>\n<Spacing>0</Spacing><!--E-->"), fillPath + "/Spacing",
       "0 is out of range", "> 0"},
      {"FillBoxWithRadius", fill("<Shape>box</Shape>\n<Radius>2</Radius><!--E-->"), fillPath + "/Radius",
       "<Radius> belongs to sphere fills, not to box fills", "Shape, Spacing, OutsideObjects, Min, Max"},
      {"FillSphereWithMin", fill("<Shape>sphere</Shape>\n<Min>0 0 0</Min><!--E-->"), fillPath + "/Min",
       "<Min> belongs to box fills, not to sphere fills", "Shape, Spacing, OutsideObjects, Center, Radius"},
      {"FillSphereRadiusZero", fill("<Shape>sphere</Shape>\n<Radius>0</Radius><!--E-->"),
       fillPath + "/Radius", "0 is out of range", "> 0"},
      {"FillUnknownTag", fill("<Shape>box</Shape>\n<Step>1</Step><!--E-->"), fillPath + "/Step",
       "unknown element <Step>", "in <Fill>: Shape, Spacing, OutsideObjects, Min, Max"},
      {"FillMakesNothing",
       F("<Fill><!--E-->\n<Shape>box</Shape>\n<Max>0.5 2 2</Max>\n<Spacing>1</Spacing>\n</Fill>"), fillPath,
       "the fill makes no particles", "at least Spacing wide"},
      {"TooManyParticles",
       S("<Fluid><!--E-->\n<Name>big</Name>\n<Fill><Shape>box</Shape><Max>1000 1000 "
         "1000</Max></Fill>\n</Fluid>"),
       "Fluid 'big'",
       "the scene makes 1000000000 particles (explicit positions plus fills), "
       "more than the cap of 20000000",
       "at most 20000000 particles"},
      // --- Object ------------------------------------------------------------------------
      {"ObjectUnknownTag", O("<Shape>sphere</Shape><Size>1</Size>\n<Radius>1</Radius><!--E-->"),
       "Object[1]/Radius", "unknown element <Radius>",
       "in <Object>: Name, Geometry, Shape, Size, ParticleSize, UniformScale, InitialPosition"},
      {"ObjectPositionMisspelt", O("<Shape>sphere</Shape><Size>1</Size>\n<Position>1 2 3</Position><!--E-->"),
       "Object[1]/Position", "unknown element <Position>", "InitialPosition"},
      {"ObjectNeitherGeometryNorShape", S("<Object><!--E-->\n<Mass>2</Mass>\n</Object>"), "Object[1]",
       "the object has neither <Geometry> nor <Shape>",
       "<Geometry> (a mesh file), or <Shape> sphere, cone, box or cylinder with <Size>"},
      {"ObjectMeshShapeWithoutGeometry", O("<Name>o</Name>\n<Shape>mesh</Shape><!--E-->"), "Object 'o'/Shape",
       "Shape mesh needs a <Geometry> mesh file", "<Geometry> (a mesh file)"},
      {"ObjectUnknownShape", O("<Shape>cube</Shape><!--E-->\n<Size>1 1 1</Size>"), "Object[1]/Shape",
       "'cube' is not one of the choices", "mesh, sphere, cone, box, cylinder"},
      {"ObjectPrimitiveWithoutSize", S("<Object><!--E-->\n<Name>o</Name>\n<Shape>box</Shape>\n</Object>"),
       "Object 'o'", "missing required <Size> for Shape box", "3 numbers > 0 for a box: width height depth"},
      {"ObjectSphereSizeTwoNumbers", O("<Name>o</Name>\n<Shape>sphere</Shape>\n<Size>1 2</Size><!--E-->"),
       "Object 'o'/Size", "Size has 2 numbers but a sphere takes 1 (radius)",
       "1 number > 0 for a sphere: radius"},
      {"ObjectConeSizeThreeNumbers", O("<Name>o</Name>\n<Size>1 2 3</Size><!--E-->\n<Shape>cone</Shape>"),
       "Object 'o'/Size", "Size has 3 numbers but a cone takes 2 (radius height)",
       "2 numbers > 0 for a cone: radius height"},
      {"ObjectCylinderSizeOneNumber", O("<Name>o</Name>\n<Shape>cylinder</Shape>\n<Size>1</Size><!--E-->"),
       "Object 'o'/Size", "Size has 1 number but a cylinder takes 2 (radius height)", ""},
      {"ObjectBoxSizeEmpty", O("<Name>o</Name>\n<Shape>box</Shape>\n<Size></Size><!--E-->"),
       "Object 'o'/Size", "Size has 0 numbers but a box takes 3 (width height depth)",
       "3 numbers > 0 for a box"},
      {"ObjectSizeZero", O("<Name>o</Name>\n<Shape>cylinder</Shape>\n<Size>1 0</Size><!--E-->"),
       "Object 'o'/Size", "0 is out of range", "numbers > 0"},
      {"ObjectSizeNotANumber", O("<Name>o</Name>\n<Shape>sphere</Shape>\n<Size>big</Size><!--E-->"),
       "Object 'o'/Size", "'big' is not a number", ""},
      // Refused before the mesh is looked for: no file needed.
      {"ObjectSizeWithMeshGeometry", O("<Name>o</Name>\n<Geometry>a.obj</Geometry>\n<Size>1</Size><!--E-->"),
       "Object 'o'/Size", "a mesh object takes its size from its mesh: there is nothing to size",
       "Size only with Shape sphere, cone, box or cylinder"},
      {"ObjectGeometryAbsolute", O("<Name>o</Name>\n<Geometry>/etc/a.obj</Geometry><!--E-->"),
       "Object 'o'/Geometry", "'/etc/a.obj' is an absolute path",
       "a path inside the scene's folder, e.g. honeyGeo/blob.obj"},
      {"ObjectGeometryLeavesTheFolder", O("<Name>o</Name>\n<Geometry>geo/../../a.obj</Geometry><!--E-->"),
       "Object 'o'/Geometry", "'geo/../../a.obj' leaves the scene's folder", "a path inside"},
      {"ObjectGeometryMissingFile",
       O("<Name>o</Name>\n<Shape>sphere</Shape>\n<Geometry>noSuchGeo/a.obj</Geometry><!--E-->"),
       "Object 'o'/Geometry", "cannot use the mesh 'noSuchGeo/a.obj'", "a readable mesh file"},
      {"ObjectGeometryEmpty", O("<Name>o</Name>\n<Geometry> </Geometry><!--E-->"), "Object 'o'/Geometry",
       "the value is empty", ""},
      {"ObjectNameTooLongForFileNames",
       O("<Name>" + std::string(101, 'o') + "</Name><!--E-->\n<Shape>sphere</Shape><Size>1</Size>"),
       "Object[1]/Name", "the name is 101 bytes long: its output file names",
       "a non-empty name of at most 100 bytes (UTF-8) without '/', '\\' or control characters"},
      {"ObjectNameWithSlash", O("<Name>a/b</Name><!--E-->\n<Shape>sphere</Shape><Size>1</Size>"),
       "Object[1]/Name", "'a/b' is not a valid object name: it becomes part of file names",
       "a non-empty name of at most 100 bytes (UTF-8) without '/', '\\' or control characters"},
      {"ObjectNameWithBackslash", O("<Name>a\\b</Name><!--E-->\n<Shape>sphere</Shape><Size>1</Size>"),
       "Object[1]/Name", "is not a valid object name", "without '/', '\\' or control characters"},
      {"ObjectNameWithControlCharacter",
       O("<Name>a&#x7F;b</Name><!--E-->\n<Shape>sphere</Shape><Size>1</Size>"), "Object[1]/Name",
       "is not a valid object name", "control characters"},
      {"ObjectNameDotDot", O("<Name>..</Name><!--E-->\n<Shape>sphere</Shape><Size>1</Size>"),
       "Object[1]/Name", "'..' is not a valid object name: it names a folder", "other than '.' and '..'"},
      {"ObjectNameDot", O("<Name>.</Name><!--E-->\n<Shape>sphere</Shape><Size>1</Size>"), "Object[1]/Name",
       "'.' is not a valid object name: it names a folder", "other than '.' and '..'"},
      {"ObjectNameEmpty", O("<Name> </Name><!--E-->\n<Shape>sphere</Shape><Size>1</Size>"), "Object[1]/Name",
       "the value is empty", ""},
      {"ObjectNameTakenByAFluid", O("<Name>w</Name><!--E-->\n<Shape>sphere</Shape><Size>1</Size>"),
       "Object 'w'/Name", "the object name 'w' is already used by a fluid (line 2)",
       "a name no other fluid or object has"},
      {"FluidNameTakenByAnObject",
       S("<Object><Name>w</Name><Shape>sphere</Shape><Size>1</Size></Object>\n"
         "<Fluid>\n<Name>w</Name><!--E-->\n<Fill><Shape>box</Shape></Fill>\n</Fluid>"),
       "Fluid 'w'/Name", "the fluid name 'w' is already used by an object (line 2)",
       "a name no other fluid or object has"},
      {"DuplicateObjectName",
       S("<Object><Name>o</Name><Shape>sphere</Shape><Size>1</Size></Object>\n"
         "<Object><Shape>sphere</Shape><Size>1</Size>\n<Name>o</Name><!--E-->\n</Object>"),
       "Object 'o'/Name", "the object name 'o' is already used (line 2)", ""},
      {"DefaultObjectNameTaken",
       S("<Object><Name>object2</Name><Shape>sphere</Shape><Size>1</Size></Object>\n"
         "<Object><!--E-->\n<Shape>sphere</Shape><Size>1</Size>\n</Object>"),
       "Object[2]", "the default object name 'object2' is already used (line 2)",
       "give this object its own <Name>"},
      {"ObjectMassZero", O("<Name>o</Name><Shape>sphere</Shape><Size>1</Size>\n<Mass>0</Mass><!--E-->"),
       "Object 'o'/Mass", "0 is out of range", "[1e-30, 1e+30]"},
      {"ObjectMassTiny", O("<Name>o</Name><Shape>sphere</Shape><Size>1</Size>\n<Mass>1e-200</Mass><!--E-->"),
       "Object 'o'/Mass", "1e-200 is out of range", "[1e-30, 1e+30]"},
      {"ObjectUniformScaleNegative",
       O("<Name>o</Name><Shape>sphere</Shape><Size>1</Size>\n<UniformScale>-1</UniformScale><!--E-->"),
       "Object 'o'/UniformScale", "-1 is out of range", "> 0"},
      {"ObjectParticleSizeZero",
       O("<Name>o</Name><Shape>sphere</Shape><Size>1</Size>\n<ParticleSize>0</ParticleSize><!--E-->"),
       "Object 'o'/ParticleSize", "0 is out of range", "> 0"},
      {"ObjectNormalAttenuationAboveOne",
       O("<Name>o</Name><Shape>sphere</Shape><Size>1</Size>\n<NormalAttenuation>1.1</"
         "NormalAttenuation><!--E-->"),
       "Object 'o'/NormalAttenuation", "1.1 is out of range", "[0, 1]"},
      {"ObjectTangentAttenuationNegative",
       O("<Name>o</Name><Shape>sphere</Shape><Size>1</Size>\n<TangentAttenuation>-0.5</"
         "TangentAttenuation><!--E-->"),
       "Object 'o'/TangentAttenuation", "-0.5 is out of range", "[0, 1]"},
      {"ObjectIsDynamicNotBoolean",
       O("<Name>o</Name><Shape>sphere</Shape><Size>1</Size>\n<IsDynamic>no</IsDynamic><!--E-->"),
       "Object 'o'/IsDynamic", "'no' is not a boolean", "true, false, 1, 0"},
      {"ObjectRotationTwoNumbers",
       O("<Name>o</Name><Shape>sphere</Shape><Size>1</Size>\n<InitialRotation>90 "
         "0</InitialRotation><!--E-->"),
       "Object 'o'/InitialRotation", "expected 3 numbers, got 2", "3 finite numbers"},
      {"ObjectAngularVelocityNotFinite",
       O("<Name>o</Name><Shape>sphere</Shape><Size>1</Size>\n<InitialAngularVelocity>0 inf "
         "0</InitialAngularVelocity><!--E-->"),
       "Object 'o'/InitialAngularVelocity", "'inf' is not a finite number", ""},
      {"ObjectScaledBeyondSinglePrecision",
       O("<Name>o</Name><Shape>sphere</Shape><Size>1e38</Size>\n<UniformScale>1e10</UniformScale><!--E-->"),
       "Object 'o'/UniformScale", "too large for single precision", "at most 3.4e38 units across"},
      {"ObjectTooManyParticles",
       S(validFluid("w") + "<Object><!--E-->\n<Name>o</Name>\n<Shape>sphere</Shape>\n<Size>1000</Size>\n"
                           "<ParticleSize>0.5</ParticleSize>\n</Object>"),
       "Object 'o'",
       "may make 64000000008 particles (objects filled at their ParticleSize), more "
       "than the cap of 20000000",
       "at most 20000000 particles in all"},
      // --- Interactions ------------------------------------------------------------------
      {"FluidFluidWithoutFunction", I("<FluidFluid><!--E-->\n<Damping>1</Damping>\n</FluidFluid>"),
       "Interactions/FluidFluid", "missing the function element",
       "exactly one of Linear, LennardJones, LennardJonesForce, Curve"},
      {"TwoFunctions",
       I("<FluidFluid>\n<Linear/>\n<Curve><Points>0 1 1 0</Points></Curve><!--E-->\n</FluidFluid>"),
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
      {"LennardJonesAmplitudeNegative", FF("<LennardJones><Amplitude>-1</Amplitude><!--E--></LennardJones>"),
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
      {"LennardJonesForceSigmaZero", FF("<LennardJonesForce><Sigma>0</Sigma><!--E--></LennardJonesForce>"),
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
       "Interactions/Pair 'w','oil'/B", "no fluid or object is named 'oil'",
       "the Name of a fluid or an object: fluids w, v"},
      {"PairDuplicateReversed",
       I("<Pair><A>w</A><B>v</B><Linear/></Pair>\n<Pair><!--E-->\n<A>v</A><B>w</B><Linear/></Pair>"),
       "Interactions/Pair 'v','w'", "the pair 'v','w' is given twice (first at line 5)", "in either order"},
      {"FluidObjectWithoutFunction",
       I("<FluidObject><!--E-->\n<RelativeVelocity>1</RelativeVelocity>\n</FluidObject>"),
       "Interactions/FluidObject", "missing the function element",
       "exactly one of Linear, LennardJones, LennardJonesForce, Curve"},
      {"FluidObjectTwoFunctions", I("<FluidObject>\n<Linear/>\n<LennardJones/><!--E-->\n</FluidObject>"),
       "Interactions/FluidObject/LennardJones", "a second function <LennardJones> after <Linear>",
       "exactly one of"},
      {"FluidObjectRelativeVelocityNegative",
       I("<FluidObject><Linear/>\n<RelativeVelocity>-2</RelativeVelocity><!--E-->\n</FluidObject>"),
       "Interactions/FluidObject/RelativeVelocity", "-2 is out of range", ">= 0"},
      {"FluidObjectGivenTwice",
       I("<FluidObject><Linear/></FluidObject>\n<FluidObject><Linear/></FluidObject><!--E-->"),
       "Interactions/FluidObject", "<FluidObject> is given twice (first at line 5)",
       "one <FluidObject> in each <Interactions>"},
      {"FluidObjectLinearMinAboveMax",
       I("<FluidObject>\n<Linear><Min>2</Min><Max>1</Max></Linear><!--E-->\n</FluidObject>"),
       "Interactions/FluidObject/Linear/Max", "Min (2) is greater than Max (1)", "Min <= Max"},
      {"PairTwoObjects", IO("<Pair><!--E-->\n<A>ball</A>\n<B>crate</B>\n<Linear/>\n</Pair>"),
       "Interactions/Pair 'ball','crate'",
       "'ball' and 'crate' are both objects: objects collide by impulses (NormalAttenuation, "
       "TangentAttenuation), not by a function",
       "a Pair of two fluids, or of a fluid and an object"},
      {"PairSameObjectTwice", IO("<Pair><!--E-->\n<A>ball</A><B>ball</B><Linear/>\n</Pair>"),
       "Interactions/Pair 'ball','ball'", "'ball' and 'ball' are both objects", ""},
      {"PairUnknownNameWithObjects", IO("<Pair>\n<A>ball</A>\n<B>oil</B><!--E-->\n<Linear/>\n</Pair>"),
       "Interactions/Pair 'ball','oil'/B", "no fluid or object is named 'oil'",
       "the Name of a fluid or an object: fluids w, v; objects ball, crate"},
      {"PairUnknownNameNothingInTheScene",
       S("<Interactions>\n<Pair>\n<A>x</A><!--E-->\n<B>y</B><Linear/>\n</Pair>\n</Interactions>"),
       "Interactions/Pair 'x','y'/A", "no fluid or object is named 'x'",
       "the Name of a fluid or an object (the scene has none)"},
      {"PairFluidObjectTwiceReversed",
       IO("<Pair><A>w</A><B>ball</B><Linear/></Pair>\n<Pair><!--E-->\n<A>ball</A><B>w</B><Linear/></Pair>"),
       "Interactions/Pair 'ball','w'", "the pair 'ball','w' is given twice (first at line 7)",
       "in either order"},
      {"PairWithoutFunction", I("<Pair><!--E-->\n<A>w</A><B>v</B>\n</Pair>"), "Interactions/Pair 'w','v'",
       "missing the function element", "exactly one of"},
      {"PairUnknownTag", I("<Pair><A>w</A><B>v</B><Linear/>\n<C>x</C><!--E-->\n</Pair>"),
       "Interactions/Pair 'w','v'/C", "unknown element <C>",
       "A, B, Damping, RelativeVelocity, Linear, LennardJones, LennardJonesForce, Curve"},
      {"FunctionUnknownTag", FF("<Linear>\n<Slope>2</Slope><!--E-->\n</Linear>"),
       "Interactions/FluidFluid/Linear/Slope", "unknown element <Slope>", "AtZero, Cutoff, Min, Max"},
      {"InteractionsUnknownTag", I("<FluidFluids/><!--E-->"), "Interactions/FluidFluids",
       "unknown element <FluidFluids> (did you mean <FluidFluid>?)", "FluidFluid, FluidObject, Pair"},
      {"PairTwiceSameOrder",
       I("<Pair><A>w</A><B>w</B><Linear/></Pair>\n<Pair><A>w</A><!--E-->\n<B>w</B><Linear/></Pair>"),
       "Interactions/Pair 'w','w'", "given twice", ""},
  };
}

}  // namespace softsub::scene::rules
