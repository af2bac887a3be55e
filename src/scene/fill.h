#pragma once
/// Lattice fills: how many particles a <Fill> makes, and the particles themselves.
/// fillCount is exact and cheap (no point is generated), so a reader can refuse a
/// scene that is too big before anything is allocated.
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "scene/scene_desc.h"

namespace softsub::scene {

/// Largest sphere lattice radius (Radius / Spacing) counted exactly; beyond it the
/// count (over 2.8e11 points, far past any particle cap) is the volume estimate.
inline constexpr double kMaxExactSphereReach = 4096;

/// Number of points generateFill appends for fill, without generating them.
/// Box: product over axes of floor((Max - Min)/Spacing + 1e-9). Sphere: lattice points
/// within Radius (exact up to kMaxExactSphereReach). Saturates at UINT64_MAX, never
/// overflows. 0 for mesh fills (the reader bounds them with geometry::meshFillBound) and for invalid fills (Spacing <= 0,
/// non-finite numbers).
std::uint64_t fillCount(const FillDesc& fill);

/// Appends the fill's points to out. Box: Min + (k + 0.5) Spacing per axis; sphere:
/// Center + (i, j, k) Spacing with distance <= Radius (1 + 1e-12). Order: x fastest,
/// then y, then z. Throws std::invalid_argument for mesh fills: they need the mesh file,
/// which compile() loads (geometry::fillMesh).
void generateFill(const FillDesc& fill, std::vector<Vec3>& out);

}  // namespace softsub::scene
