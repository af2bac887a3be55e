// Headless rendering through EGL (Mesa's software rasteriser in CI): the picture has the
// asked size, is not blank, each fluid's colour appears where its particles project, the
// floor is at the bottom, meshes are drawn at their pose and a reflective floor mirrors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <span>
#include <vector>

#include "render/camera.h"
#include "render/offscreen.h"
#include "render/renderer.h"

namespace softsub::render {
namespace {

/// One context for the whole suite: making one costs ~50 ms with llvmpipe.
class Headless : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context_ = std::make_unique<OffscreenContext>();
    renderer_ = std::make_unique<Renderer>();
  }
  static void TearDownTestSuite() {
    renderer_.reset();
    context_.reset();
  }
  Image render(const RenderScene& scene, const FrameSnapshot& frame, const Camera& camera, int w, int h,
               std::span<const RenderSurface> surfaces = {}) {
    renderer_->setScene(scene);
    Framebuffer fb(w, h);
    fb.bind();
    renderer_->draw(frame, camera, w, h, {}, surfaces);
    Image im = fb.read();
    // SOFTSUB_TEST_PICTURES=DIR keeps each picture for a person to look at.
    if (const char* dir = std::getenv("SOFTSUB_TEST_PICTURES")) {
      const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
      std::ofstream(std::string(dir) + "/" + info->name() + "-" + std::to_string(++shots_) + ".png",
                    std::ios::binary)
          << encodePng(im);
    }
    return im;
  }
  int shots_ = 0;
  static std::unique_ptr<OffscreenContext> context_;
  static std::unique_ptr<Renderer> renderer_;
};
std::unique_ptr<OffscreenContext> Headless::context_;
std::unique_ptr<Renderer> Headless::renderer_;

/// A cube of n^3 particles of `size` spacing centred at c.
FluidSnapshot blob(const std::string& name, std::array<float, 3> colour, Vec3 c, int n, float size) {
  FluidSnapshot f;
  f.name = name;
  f.colour = colour;
  f.particleSize = size;
  std::uint32_t id = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        f.ids.push_back(id++);
        f.positions.push_back(static_cast<float>(c.x() + (i - 0.5 * (n - 1)) * size));
        f.positions.push_back(static_cast<float>(c.y() + (j - 0.5 * (n - 1)) * size));
        f.positions.push_back(static_cast<float>(c.z() + (k - 0.5 * (n - 1)) * size));
        f.velocities.insert(f.velocities.end(), {0, 0, 0});
      }
  return f;
}

RenderScene boxScene(bool reflective) {
  RenderScene s;
  s.container = RenderContainer{{-10, 0, -10}, {10, 20, 10}, false};
  s.reflective = reflective;
  return s;
}

Camera frontCamera() {
  Camera c;
  c.eye = {0, 8, 30};
  c.pitch = -12;
  return c;
}

bool reddish(const std::uint8_t* p) { return p[0] > 90 && p[0] > 2 * p[1] && p[0] > 2 * p[2]; }
bool greenish(const std::uint8_t* p) { return p[1] > 90 && p[1] > 2 * p[0] && p[1] > 2 * p[2]; }
bool greyish(const std::uint8_t* p) {
  return std::abs(p[0] - p[1]) < 20 && std::abs(p[1] - p[2]) < 20 && p[0] > 70;
}

/// The mean colour of the 7x7 pixels around where `p` projects (gaps between spheres and
/// shading make single pixels a poor witness).
struct Rgb {
  std::uint8_t v[3];
  operator const std::uint8_t*() const { return v; }
};
Rgb pixelAt(const Image& im, const Camera& c, const Vec3& p) {
  const auto px = projectToPixel(c, p, im.width, im.height);
  EXPECT_TRUE(px);
  const int cx = static_cast<int>((*px)[0]), cy = static_cast<int>((*px)[1]);
  int sum[3] = {0, 0, 0}, n = 0;
  for (int y = std::max(cy - 3, 0); y <= std::min(cy + 3, im.height - 1); ++y)
    for (int x = std::max(cx - 3, 0); x <= std::min(cx + 3, im.width - 1); ++x, ++n)
      for (int k = 0; k < 3; ++k) sum[k] += im.at(x, y)[k];
  Rgb out{};
  for (int k = 0; k < 3; ++k) out.v[k] = static_cast<std::uint8_t>(n ? sum[k] / n : 0);
  return out;
}

/// A red blob at (-5, 3, 0) and a green one at (5, 3, 0).
FrameSnapshot redAndGreen() {
  FrameSnapshot frame;
  frame.fluids.push_back(blob("red", {0.9f, 0.1f, 0.1f}, {-5, 3, 0}, 4, 1));
  frame.fluids.push_back(blob("green", {0.1f, 0.85f, 0.15f}, {5, 3, 0}, 4, 1));
  return frame;
}

TEST_F(Headless, FluidsAppearInTheirColourWhereTheyProject) {
  const FrameSnapshot frame = redAndGreen();
  const Camera cam = frontCamera();
  const Image im = render(boxScene(false), frame, cam, 320, 240);
  ASSERT_EQ(im.width, 320);
  ASSERT_EQ(im.height, 240);
  ASSERT_EQ(im.rgb.size(), 320u * 240u * 3u);
  EXPECT_TRUE(reddish(pixelAt(im, cam, {-5, 3, 0})));
  EXPECT_TRUE(greenish(pixelAt(im, cam, {5, 3, 0})));
  // Empty space above the blobs is neither.
  EXPECT_FALSE(reddish(pixelAt(im, cam, {0, 12, 0})));
  EXPECT_FALSE(greenish(pixelAt(im, cam, {0, 12, 0})));
  // Not blank: many distinct values.
  std::size_t red = 0, green = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      red += reddish(im.at(x, y));
      green += greenish(im.at(x, y));
    }
  EXPECT_GT(red, 200u);
  EXPECT_GT(green, 200u);
}

TEST_F(Headless, TheFloorIsAtTheBottom) {
  FrameSnapshot frame;  // no particles at all: the picture is the container and floor
  const Camera cam = frontCamera();
  const Image im = render(boxScene(false), frame, cam, 320, 240);
  // The floor's front middle projects into the lower half and is drawn grey there.
  const auto floorFront = projectToPixel(cam, {0, 0, 8}, 320, 240);
  ASSERT_TRUE(floorFront);
  EXPECT_GT((*floorFront)[1], 240 / 2);
  EXPECT_TRUE(greyish(pixelAt(im, cam, {0, 0, 8})));
  EXPECT_TRUE(greyish(pixelAt(im, cam, {-6, 0, -6})));
  // The top rows show the background, darker than the floor.
  const std::uint8_t* sky = im.at(160, 2);  // one pixel: the background is smooth
  EXPECT_LT(sky[0] + sky[1] + sky[2], pixelAt(im, cam, {0, 0, 8})[0] * 3);
}

TEST_F(Headless, ParticleSizeScalesTheDrawnArea) {
  auto area = [&](float size) {
    FrameSnapshot frame;
    frame.fluids.push_back(blob("red", {0.9f, 0.1f, 0.1f}, {0, 5, 0}, 1, size));
    const Image im = render(boxScene(false), frame, frontCamera(), 400, 300);
    std::size_t n = 0;
    for (int y = 0; y < im.height; ++y)
      for (int x = 0; x < im.width; ++x) n += reddish(im.at(x, y));
    return static_cast<double>(n);
  };
  const double one = area(1), two = area(2);
  ASSERT_GT(one, 20);
  EXPECT_NEAR(two / one, 4.0, 0.6);  // area goes as the diameter squared
}

TEST_F(Headless, MeshesAreDrawnAtTheirPose) {
  RenderScene scene = boxScene(false);
  RenderMesh cube;
  cube.name = "crate";
  cube.colour = {0.2f, 0.3f, 0.95f};
  for (int k = 0; k < 8; ++k)
    cube.vertices.push_back({(k & 1) ? 1.f : -1.f, (k & 2) ? 1.f : -1.f, (k & 4) ? 1.f : -1.f});
  const std::array<std::array<std::uint32_t, 3>, 12> tris{{{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                                            {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                                            {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}}};
  cube.triangles.assign(tris.begin(), tris.end());
  scene.meshes.push_back(cube);
  FrameSnapshot frame;
  ObjectSnapshot o;
  o.name = "crate";
  o.position = {4, 6, 0};
  o.uniformScale = 2;
  o.rotation = {std::cos(0.3), 0, std::sin(0.3), 0};
  frame.objects.push_back(o);
  const Camera cam = frontCamera();
  const Image im = render(scene, frame, cam, 320, 240);
  const Rgb p = pixelAt(im, cam, {4, 6, 0});
  EXPECT_GT(p[2], 2 * p[0]) << int(p[0]) << " " << int(p[1]) << " " << int(p[2]);
  // Where the unmoved cube would be (the origin, at scale 1) there is no blue.
  const Rgb q = pixelAt(im, cam, {-4, 6, 0});
  EXPECT_FALSE(q[2] > 2 * q[0]);
}

TEST_F(Headless, AReflectiveFloorMirrorsTheFluid) {
  FrameSnapshot frame;
  frame.fluids.push_back(blob("red", {0.9f, 0.1f, 0.1f}, {0, 2.5, 0}, 4, 1));
  const Camera cam = frontCamera();
  const Image plain = render(boxScene(false), frame, cam, 320, 240);
  const Image mirror = render(boxScene(true), frame, cam, 320, 240);
  // Just below the floor's image of the blob: grey without reflection, red-tinted with it.
  const Rgb a = pixelAt(plain, cam, {0, -2.5, 0});
  const Rgb b = pixelAt(mirror, cam, {0, -2.5, 0});
  EXPECT_TRUE(greyish(a));
  EXPECT_GT(b[0] - b[1], 40) << int(b[0]) << " " << int(b[1]) << " " << int(b[2]);
  // Nothing is mirrored outside the floor: below its front edge there is no red.
  const auto edge = projectToPixel(cam, {0, 0, 10}, 320, 240);
  ASSERT_TRUE(edge);
  std::size_t leaked = 0;
  for (int y = static_cast<int>((*edge)[1]) + 2; y < mirror.height; ++y)
    for (int x = 0; x < mirror.width; ++x) leaked += mirror.at(x, y)[0] > mirror.at(x, y)[1] + 30;
  EXPECT_EQ(leaked, 0u);
  // The blob itself looks the same in both.
  EXPECT_TRUE(reddish(pixelAt(mirror, cam, {0, 2.5, 0})));
}


/// A closed cube of half-edge h around c, with outward normals at its corners.
RenderSurface cubeSurface(std::size_t fluid, Vec3 c, float h) {
  RenderSurface s;
  s.fluid = fluid;
  for (int k = 0; k < 8; ++k) {
    const float sx = (k & 1) ? 1.f : -1.f, sy = (k & 2) ? 1.f : -1.f, sz = (k & 4) ? 1.f : -1.f;
    s.vertices.push_back({static_cast<float>(c.x()) + sx * h, static_cast<float>(c.y()) + sy * h,
                          static_cast<float>(c.z()) + sz * h});
    const float n = 1.0f / std::sqrt(3.0f);
    s.normals.push_back({sx * n, sy * n, sz * n});
  }
  s.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return s;
}

TEST_F(Headless, ASurfaceReplacesItsFluidsParticles) {
  const FrameSnapshot frame = redAndGreen();
  const Camera cam = frontCamera();
  std::vector<RenderSurface> surfaces{cubeSurface(0, {0, 10, 0}, 1.5f)};
  // Malformed ones are skipped, not drawn and not fatal: a fluid that does not exist, a
  // missing normal, an index out of range.
  surfaces.push_back(cubeSurface(7, {0, 3, 0}, 1.5f));
  surfaces.push_back(cubeSurface(1, {0, 3, 0}, 1.5f));
  surfaces.back().normals.pop_back();
  surfaces.push_back(cubeSurface(1, {0, 3, 0}, 1.5f));
  surfaces.back().triangles[0][0] = 99;
  const Image im = render(boxScene(false), frame, cam, 320, 240, surfaces);
  EXPECT_TRUE(reddish(pixelAt(im, cam, {0, 10, 0}))) << "the red fluid's surface, in its colour";
  EXPECT_FALSE(reddish(pixelAt(im, cam, {-5, 3, 0}))) << "the red particles are replaced by the surface";
  EXPECT_TRUE(greenish(pixelAt(im, cam, {5, 3, 0}))) << "a fluid without a surface keeps its particles";
  const Rgb middle = pixelAt(im, cam, {0, 3, 0});
  EXPECT_FALSE(reddish(middle) || greenish(middle)) << "no malformed surface is drawn";
}

}  // namespace
}  // namespace softsub::render
