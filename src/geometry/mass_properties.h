#pragma once
/// Mass properties: inertia tensors of primitives and the exact volume, centre of mass
/// and inertia tensor of a closed triangle mesh of uniform density.
///
/// Conventions for every function here: the tensor is about the body's centre of mass,
/// in the body's own axes, for the given mass (kg-like units times scene units squared).
/// The scene's up is +y, so axisymmetric primitives (cone, cylinder) have their axis
/// along y.
#include <string>

#include "core/math.h"
#include "geometry/triangle_mesh.h"

namespace softsub::geometry {

/// Solid sphere of mass m and radius r: 2/5 m r² on every axis.
[[nodiscard]] Mat3 sphereInertia(double m, double r);

/// Solid cone of mass m, base radius r and height h, axis along y, about its centre of
/// mass (on the axis, h/4 above the base centre):
///   I_yy = 3/10 m r²,  I_xx = I_zz = 3/20 m r² + 3/80 m h².
/// The seed's appendix lists diag(3/5 m h² + 3/20 m r², same, 3/10 m r²): that is the
/// tensor about the apex with the axis along z. Moving it to the centre of mass
/// (3/4 h from the apex) subtracts m (3h/4)² = 9/16 m h² from the perpendicular terms,
/// which gives the 3/80 m h² used here.
[[nodiscard]] Mat3 coneInertia(double m, double r, double h);

/// Solid cuboid of mass m with width w (along x), height h (along y), depth d (along z):
/// diag(1/12 m (h² + d²), 1/12 m (w² + d²), 1/12 m (w² + h²)), as in the seed.
[[nodiscard]] Mat3 cuboidInertia(double m, double w, double h, double d);

/// Solid cylinder of mass m, radius r and height h, axis along y, about its centre:
/// I_yy = 1/2 m r², I_xx = I_zz = 1/12 m (3 r² + h²). (The seed's table has the axis
/// along z; only the axis differs.)
[[nodiscard]] Mat3 cylinderInertia(double m, double r, double h);

/// What meshMassProperties computes.
struct MassProperties {
  double volume = 0;            ///< enclosed volume, scene units³ (always positive)
  Vec3 centerOfMass{0, 0, 0};   ///< in the mesh's coordinates
  Mat3 inertia = Mat3::Zero();  ///< about the centre of mass, mesh axes, for the given mass
};

/// Exact volume, centre of mass and inertia tensor of a closed triangle mesh filled with
/// uniform density so that its total mass is `mass` (> 0). Orientation does not matter:
/// an inside-out mesh gives the same result. Throws InputError (element "mesh", file
/// `source`) when the mesh is not closed (an edge without its opposite) or encloses no
/// volume (empty or flat); std::invalid_argument when mass is not positive and finite.
[[nodiscard]] MassProperties meshMassProperties(const TriangleMesh& mesh, double mass,
                                                const std::string& source = {});

}  // namespace softsub::geometry
