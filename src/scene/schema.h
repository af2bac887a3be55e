#pragma once
/// The schema of the .scene format: every tunable is declared once here, with its tag,
/// type, unit, default, allowed range and meaning. The reader, the writer and the docs
/// (schemaMarkdown, `softsub schema`) all walk these tables, so they cannot disagree.
///
/// Defaults are never written as literals here: a field's default is read from the
/// default-constructed description struct through the field's member pointer.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "scene/scene_desc.h"

namespace softsub::scene {

/// The type of a field's value as written in a scene file.
enum class Kind : std::uint8_t {
  Real,      ///< one finite number
  Int,       ///< one integer
  Bool,      ///< true, false, 1 or 0
  Vec3,      ///< three finite numbers
  Colour,    ///< three numbers in [0, 1]
  String,    ///< text, trimmed
  Enum,      ///< one of a fixed list of names
  RealList,  ///< any number of finite numbers
  PointList  ///< 3 numbers per point, one point after the other
};

/// A field value. Enums hold the index of their name in FieldInfo::choices.
using Value = std::variant<double, std::int64_t, bool, Vec3, std::string, std::vector<double>,
                           std::vector<Vec3>>;

/// An interval of allowed numbers; each end open or closed; infinite ends are no bound.
/// Finiteness is always required on top of it.
struct Range {
  double min = -std::numeric_limits<double>::infinity();  ///< lower bound
  double max = std::numeric_limits<double>::infinity();   ///< upper bound
  bool minOpen = false;                                    ///< true: min itself excluded
  bool maxOpen = false;                                    ///< true: max itself excluded

  /// True when v lies inside (v must be finite).
  [[nodiscard]] bool contains(double v) const;
  /// The rule in words: "> 0", ">= 0", "[0, 1]", "(0, 1000]", "any".
  [[nodiscard]] std::string describe() const;
  /// True when the range has no bound at all.
  [[nodiscard]] bool unbounded() const;
};

/// Common ranges.
inline constexpr Range kAnyNumber{};
inline constexpr Range kPositive{0, std::numeric_limits<double>::infinity(), true, false};
inline constexpr Range kNonNegative{0, std::numeric_limits<double>::infinity(), false, false};
inline constexpr Range kUnitInterval{0, 1, false, false};

/// Everything about a field except how to reach it in its struct.
struct FieldInfo {
  std::string_view tag;                       ///< element name in the scene file
  Kind kind = Kind::Real;                     ///< value type
  std::string_view unit;                      ///< unit in words ("units", "mass/s", "-")
  Range range;                                ///< allowed numbers (each number of a vector/list)
  std::string_view meaning;                   ///< one line for the docs
  std::string_view rule;                      ///< extra rule checked by the reader, in words
  std::span<const std::string_view> choices;  ///< Enum: the names, indexed by value
  bool required = false;                      ///< must be given (no default)
  /// The default in words, when the reader decides it from other fields ("1/20 of the
  /// largest extent"): the struct's default is then only a placeholder, which the docs
  /// do not show and the writer leaves out (reading the file back restores it).
  std::string_view defaultText;
};

/// A field of the description struct S: its info plus how to read and write it.
template <class S>
struct Field : FieldInfo {
  /// The field's value in an S.
  Value (*get)(const S&) = nullptr;
  /// Stores a value into an S; null for a derived field (NumberOfParticles), which the
  /// writer writes from get() and the reader only checks.
  void (*set)(S&, Value&&) = nullptr;

  /// The default: the value in a default-constructed S.
  [[nodiscard]] Value defaultValue() const { return get(S{}); }
  /// True when s holds the placeholder of a field whose default is in words
  /// (defaultText): the writer leaves such a field out.
  [[nodiscard]] bool holdsPlaceholder(const S& s) const {
    return !defaultText.empty() && get(s) == defaultValue();
  }
};

namespace detail {

template <class M>
struct MemberOf;
template <class C, class T>
struct MemberOf<T C::*> {
  using Class = C;
};

template <auto First, auto... Rest>
struct PathClass {
  using Type = typename MemberOf<decltype(First)>::Class;
};

/// s.*First.*Rest... : follows a chain of member pointers.
template <auto First, auto... Rest, class S>
constexpr auto& follow(S& s) {
  if constexpr (sizeof...(Rest) == 0) {
    return s.*First;
  } else {
    return follow<Rest...>(s.*First);
  }
}

template <class T>
Value toValue(const T& v) {
  if constexpr (std::is_enum_v<T>) {
    return static_cast<std::int64_t>(static_cast<std::underlying_type_t<T>>(v));
  } else if constexpr (std::is_same_v<T, int>) {
    return static_cast<std::int64_t>(v);
  } else {
    return Value(std::in_place_type<T>, v);
  }
}

template <class T>
void fromValue(Value&& v, T& out) {
  if constexpr (std::is_enum_v<T>) {
    out = static_cast<T>(std::get<std::int64_t>(v));
  } else if constexpr (std::is_same_v<T, int>) {
    out = static_cast<int>(std::get<std::int64_t>(v));
  } else {
    out = std::get<T>(std::move(v));
  }
}

}  // namespace detail

/// A field stored at s.*Path... (one member pointer, or a chain into a nested struct).
template <auto... Path>
constexpr Field<typename detail::PathClass<Path...>::Type> field(const FieldInfo& info) {
  using S = typename detail::PathClass<Path...>::Type;
  Field<S> f{info};
  f.get = [](const S& s) { return detail::toValue(detail::follow<Path...>(s)); };
  f.set = [](S& s, Value&& v) { detail::fromValue(std::move(v), detail::follow<Path...>(s)); };
  return f;
}

/// Names of Integrator values, as written in scene files.
inline constexpr std::string_view kIntegratorNames[] = {"explicit-euler", "symplectic-euler",
                                                        "velocity-verlet"};
/// Names of FillShape values, as written in scene files.
inline constexpr std::string_view kFillShapeNames[] = {"box", "sphere", "mesh"};
/// Names of ObjectShape values, as written in scene files.
inline constexpr std::string_view kObjectShapeNames[] = {"mesh", "sphere", "cone", "box",
                                                         "cylinder"};

/// How many numbers an object's Size has for this shape (0 for mesh: nothing to size).
std::size_t objectSizeCount(ObjectShape shape);
/// What the numbers of an object's Size are for this shape ("radius height"; "" for mesh).
std::string_view objectSizeWords(ObjectShape shape);

/// The fields of the element described by S. Specialised for SimulationDesc (Simulation),
/// CameraDesc, EnvironmentDesc, FluidDesc, FillDesc (the tags every fill shape has),
/// forces::Linear, forces::LennardJones, forces::LennardJonesForce, forces::Curve,
/// InteractionDesc (Damping, RelativeVelocity of FluidFluid, FluidObject and Pair),
/// PairDesc (A, B) and ObjectDesc (Object).
template <class S>
std::span<const Field<S>> fieldsOf();

template <>
std::span<const Field<SimulationDesc>> fieldsOf<SimulationDesc>();
template <>
std::span<const Field<CameraDesc>> fieldsOf<CameraDesc>();
template <>
std::span<const Field<EnvironmentDesc>> fieldsOf<EnvironmentDesc>();
template <>
std::span<const Field<FluidDesc>> fieldsOf<FluidDesc>();
template <>
std::span<const Field<FillDesc>> fieldsOf<FillDesc>();
template <>
std::span<const Field<forces::Linear>> fieldsOf<forces::Linear>();
template <>
std::span<const Field<forces::LennardJones>> fieldsOf<forces::LennardJones>();
template <>
std::span<const Field<forces::LennardJonesForce>> fieldsOf<forces::LennardJonesForce>();
template <>
std::span<const Field<forces::Curve>> fieldsOf<forces::Curve>();
template <>
std::span<const Field<InteractionDesc>> fieldsOf<InteractionDesc>();
template <>
std::span<const Field<PairDesc>> fieldsOf<PairDesc>();
template <>
std::span<const Field<ObjectDesc>> fieldsOf<ObjectDesc>();

/// The fields only a fill of this shape has (besides fieldsOf<FillDesc>()).
std::span<const Field<FillDesc>> fillShapeFields(FillShape shape);

/// Where an element may appear: the structure of a scene file.
struct ElementInfo {
  std::string_view name;     ///< element name
  std::string_view parent;   ///< parent element name ("" for the root)
  bool repeatable = false;   ///< may appear more than once in one parent
  std::string_view count;    ///< how many, in words ("optional", "any number", ...)
  std::string_view meaning;  ///< one line for the docs
};

/// Every element that is not a value field, with its parent (Scene, Fluid, Fill, ...).
std::span<const ElementInfo> elements();

/// The ElementInfo of name under parent, or null when name may not appear there.
const ElementInfo* findElement(std::string_view parent, std::string_view name);

/// The type name of a kind, for docs and messages ("real", "vec3", ...).
std::string_view kindName(Kind kind);

/// What the reader accepts for a field, in words (range, choices, extra rule).
std::string allowedText(const FieldInfo& info);

/// A value as scene-file text: shortest round-trip numbers, vectors space-separated,
/// enums by name; point lists one point per line (joined by "\n").
std::string formatValue(const FieldInfo& info, const Value& value);

/// Every table as Markdown: the element structure, then one table per element
/// (Tag | Type | Unit | Default | Allowed | Meaning). Printed by `softsub schema` and
/// pasted into docs/scene-format.md.
std::string schemaMarkdown();

}  // namespace softsub::scene
