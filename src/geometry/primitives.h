#pragma once
/// Closed triangle meshes of the primitives a scene can name (box, sphere, cylinder,
/// cone), oriented counter-clockwise seen from outside, and the primitive that stands in
/// for a body's inertia (seed appendix "Inertia tensors").
#include "core/math.h"
#include "geometry/triangle_mesh.h"

namespace softsub::geometry {

/// An axis-aligned box [lo, hi], 12 triangles.
[[nodiscard]] TriangleMesh boxMesh(const Vec3& lo, const Vec3& hi);

/// A UV sphere of radius r around c with `rings` latitude bands (>= 2) and `segments`
/// longitude segments (>= 3); the poles are single vertices.
[[nodiscard]] TriangleMesh sphereMesh(const Vec3& c, double r, int rings, int segments);

/// A solid of revolution about the y axis from y0 (radius r0) to y1 (radius r1), capped;
/// a radius of 0 is a single apex vertex (a cone). `segments` >= 3.
[[nodiscard]] TriangleMesh frustumMesh(double r0, double y0, double r1, double y1, int segments);

}  // namespace softsub::geometry
