#pragma once
/// Checks on the pictures `render`, `run --preview` and `view --script` write: decoding,
/// "not blank", whether a pixel shows a fluid's colour, and where a scene's particles
/// project through its camera. Expected positions come from the camera projection and
/// expected colours from the scene, never from hard-coded pixels.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "app_test_util.h"
#include "core/snapshot.h"
#include "render/camera.h"
#include "render/image.h"
#include "scene/compile.h"
#include "scene/reader.h"
#include "solver/simulation.h"

namespace softsub::apptest {

/// A PNG file, decoded.
inline render::Image readPng(const fs::path& p) { return render::decodePng(readFile(p), p.string()); }

/// Hue (degrees, [0, 360)), saturation and value ([0, 1]) of an RGB colour in [0, 1].
struct Hsv {
  double hue = 0, saturation = 0, value = 0;
};

inline Hsv hsvOf(double r, double g, double b) {
  const double hi = std::max({r, g, b}), lo = std::min({r, g, b}), span = hi - lo;
  Hsv out;
  out.value = hi;
  out.saturation = hi > 0 ? span / hi : 0;
  if (span <= 0) return out;
  if (hi == r) out.hue = 60 * std::fmod((g - b) / span + 6, 6.0);
  else if (hi == g) out.hue = 60 * ((b - r) / span + 2);
  else out.hue = 60 * ((r - g) / span + 4);
  return out;
}

inline Hsv hsvOf(const std::uint8_t* p) { return hsvOf(p[0] / 255.0, p[1] / 255.0, p[2] / 255.0); }
inline Hsv hsvOf(const std::array<float, 3>& c) { return hsvOf(c[0], c[1], c[2]); }

inline double hueDistance(double a, double b) {
  const double d = std::abs(a - b);
  return std::min(d, 360 - d);
}

/// Whether a pixel shows a surface of `colour` as the renderer shades it. Every term of
/// the sphere and mesh shading either scales the colour (diffuse, ambient, rim) or adds
/// white (specular), so the hue is kept and the saturation only drops: the pixel must
/// have the colour's hue (within 10 degrees), at least 45% of its saturation, and be
/// bright enough for its hue to mean something.
inline bool showsColour(const std::uint8_t* p, const std::array<float, 3>& colour) {
  const Hsv want = hsvOf(colour), got = hsvOf(p);
  if (got.value < 0.1 || got.saturation < 0.45 * want.saturation) return false;
  return hueDistance(got.hue, want.hue) <= 10;
}

/// Whether two colours are told apart by showsColour (their hues far enough apart).
inline bool distinguishable(const std::array<float, 3>& a, const std::array<float, 3>& b) {
  return hueDistance(hsvOf(a).hue, hsvOf(b).hue) > 25;
}

/// The share of the (2 half + 1)^2 pixels around (x, y) (clipped to the picture) that
/// show `colour`.
inline double shareShowing(const render::Image& im, double x, double y, int half,
                           const std::array<float, 3>& colour) {
  const int cx = static_cast<int>(x), cy = static_cast<int>(y);
  int n = 0, hit = 0;
  for (int j = std::max(cy - half, 0); j <= std::min(cy + half, im.height - 1); ++j)
    for (int i = std::max(cx - half, 0); i <= std::min(cx + half, im.width - 1); ++i, ++n)
      hit += showsColour(im.at(i, j), colour);
  return n ? static_cast<double>(hit) / n : 0;
}

/// The share of the whole picture that shows `colour`.
inline double shareShowing(const render::Image& im, const std::array<float, 3>& colour) {
  std::size_t hit = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) hit += showsColour(im.at(x, y), colour);
  return static_cast<double>(hit) / (static_cast<double>(im.width) * im.height);
}

/// The mean HSV of the (2 half + 1)^2 pixels around (x, y).
inline Hsv meanHsv(const render::Image& im, double x, double y, int half) {
  const int cx = static_cast<int>(x), cy = static_cast<int>(y);
  double sum[3] = {0, 0, 0};
  int n = 0;
  for (int j = std::max(cy - half, 0); j <= std::min(cy + half, im.height - 1); ++j)
    for (int i = std::max(cx - half, 0); i <= std::min(cx + half, im.width - 1); ++i, ++n)
      for (int k = 0; k < 3; ++k) sum[k] += im.at(i, j)[k] / 255.0;
  if (n == 0) return {};
  return hsvOf(sum[0] / n, sum[1] / n, sum[2] / n);
}

/// How many different RGB values the picture holds. A blank (one colour) picture has 1;
/// the renderer's background gradient alone has a few dozen.
inline std::size_t distinctColours(const render::Image& im) {
  std::set<std::uint32_t> seen;
  for (std::size_t i = 0; i + 2 < im.rgb.size(); i += 3)
    seen.insert(static_cast<std::uint32_t>(im.rgb[i]) << 16 | static_cast<std::uint32_t>(im.rgb[i + 1]) << 8 |
                im.rgb[i + 2]);
  return seen.size();
}

/// How many pixels differ between two pictures of the same size (all of them when the
/// sizes differ).
inline std::size_t differingPixels(const render::Image& a, const render::Image& b) {
  if (a.width != b.width || a.height != b.height)
    return static_cast<std::size_t>(std::max(a.width * a.height, b.width * b.height));
  std::size_t n = 0;
  for (std::size_t i = 0; i + 2 < a.rgb.size(); i += 3)
    n += a.rgb[i] != b.rgb[i] || a.rgb[i + 1] != b.rgb[i + 1] || a.rgb[i + 2] != b.rgb[i + 2];
  return n;
}

/// Standard deviation of the pixels' brightness (mean of the channels), 0..255.
inline double brightnessSpread(const render::Image& im) {
  double sum = 0, sum2 = 0;
  const double n = static_cast<double>(im.width) * im.height;
  for (std::size_t i = 0; i + 2 < im.rgb.size(); i += 3) {
    const double v = (im.rgb[i] + im.rgb[i + 1] + im.rgb[i + 2]) / 3.0;
    sum += v;
    sum2 += v * v;
  }
  return std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n)));
}

/// The renderer's camera for a scene's `<Camera>` (as the app maps it: eye, pitch =
/// VerticalAngle, yaw = HorizontalAngle, 45 degree vertical field of view).
inline render::Camera cameraOf(const scene::SceneDesc& desc) {
  render::Camera c;
  c.eye = desc.camera.eye;
  c.pitch = desc.camera.verticalAngle;
  c.yaw = desc.camera.horizontalAngle;
  c.fovY = 45;
  return c;
}

/// A scene's frame 0 as the simulation starts it (fluids with names, colours, sizes and
/// positions; objects at their initial pose).
inline FrameSnapshot initialFrame(const scene::SceneDesc& desc) {
  scene::Compiled c = scene::compile(desc);
  const solver::Simulation sim(c.model, std::move(c.state));
  return sim.snapshot();
}

/// The mean position of a fluid's particles.
inline Vec3 centroid(const FluidSnapshot& f) {
  Vec3 sum(0, 0, 0);
  for (std::size_t k = 0; k < f.count(); ++k)
    sum += Vec3(f.positions[3 * k], f.positions[3 * k + 1], f.positions[3 * k + 2]);
  return f.count() ? Vec3(sum / static_cast<double>(f.count())) : sum;
}

/// The largest radius, in pixels, that any particle of `frame` is drawn with.
inline double largestPixelRadius(const render::Camera& cam, const FrameSnapshot& frame, int height) {
  const double focal = 0.5 * height / std::tan(0.5 * cam.fovY * 3.14159265358979323846 / 180);
  double most = 0;
  for (const FluidSnapshot& f : frame.fluids)
    for (std::size_t k = 0; k < f.count(); ++k) {
      const Vec3 p(f.positions[3 * k], f.positions[3 * k + 1], f.positions[3 * k + 2]);
      const double d = (p - cam.eye).norm();
      if (d > 0) most = std::max(most, 0.5 * f.particleSize * focal / d);
    }
  return most;
}

/// The pixel (on a 4-pixel grid, 8 pixels in from the edges) farthest from where any
/// particle of `frame` projects, and that distance in pixels.
inline std::pair<std::array<double, 2>, double> emptiestPixel(const render::Camera& cam,
                                                              const FrameSnapshot& frame, int width,
                                                              int height) {
  std::vector<std::array<double, 2>> spots;
  for (const FluidSnapshot& f : frame.fluids)
    for (std::size_t k = 0; k < f.count(); ++k)
      if (auto px = render::projectToPixel(
              cam, Vec3(f.positions[3 * k], f.positions[3 * k + 1], f.positions[3 * k + 2]), width, height))
        spots.push_back(*px);
  std::array<double, 2> best{0, 0};
  double bestDistance = -1;
  for (int y = 8; y < height - 8; y += 4)
    for (int x = 8; x < width - 8; x += 4) {
      double nearest = 1e300;
      for (const auto& s : spots) nearest = std::min(nearest, std::hypot(s[0] - x, s[1] - y));
      if (nearest > bestDistance) {
        bestDistance = nearest;
        best = {static_cast<double>(x), static_cast<double>(y)};
      }
    }
  return {best, bestDistance};
}

/// Whether the segment from the camera's eye to `point` passes through a particle.
inline bool hiddenByParticles(const render::Camera& cam, const Vec3& point, const FrameSnapshot& frame) {
  const Vec3 d = point - cam.eye;
  const double len2 = d.squaredNorm();
  for (const FluidSnapshot& f : frame.fluids)
    for (std::size_t k = 0; k < f.count(); ++k) {
      const Vec3 c(f.positions[3 * k], f.positions[3 * k + 1], f.positions[3 * k + 2]);
      const double t = std::clamp((c - cam.eye).dot(d) / len2, 0.0, 1.0);
      if ((cam.eye + t * d - c).norm() < 0.5 * f.particleSize) return true;
    }
  return false;
}

/// Where an object's mesh vertex lies in the world at the pose of `o` (uniform scale,
/// then rotation, then translation).
inline Vec3 placed(const ObjectSnapshot& o, const Vec3& v) {
  const Eigen::Quaterniond q(o.rotation[0], o.rotation[1], o.rotation[2], o.rotation[3]);
  return Vec3(o.position[0], o.position[1], o.position[2]) + q.normalized() * (o.uniformScale * v);
}

}  // namespace softsub::apptest
