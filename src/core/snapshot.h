#pragma once
/// A frame as observers see it: plain arrays in stable-id order, detached from the
/// solver's internal (cell-sorted) layout. Writers, the viewer and tests read these.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace softsub {

/// One fluid at one frame. Arrays are indexed by particle k = 0..count-1 in stable-id
/// order; positions and velocities are interleaved x y z.
struct FluidSnapshot {
  std::string name;                      ///< the fluid's unique name from the scene
  std::array<float, 3> colour{1, 1, 1};  ///< display colour, each channel in [0,1]
  float particleSize = 1;                ///< particle diameter, scene units
  std::vector<std::uint32_t> ids;        ///< stable particle ids, increasing
  std::vector<float> positions;          ///< 3 * count, scene units
  std::vector<float> velocities;         ///< 3 * count, scene units per second

  /// Number of particles.
  [[nodiscard]] std::size_t count() const { return ids.size(); }
};

/// One rigid body at one frame: the transform that places its geometry file (uniform
/// scale, then rotation, then translation of the geometry's origin), as the `.sim` file
/// and packages like Maya want it.
struct ObjectSnapshot {
  std::string name;                            ///< the body's unique name from the scene
  double uniformScale = 1;                     ///< the scene's UniformScale
  std::array<double, 3> position{0, 0, 0};     ///< where the geometry's origin is, world
  std::array<double, 4> rotation{1, 0, 0, 0};  ///< unit quaternion w x y z
  std::string filename;                        ///< geometry file, relative to the frame files
  std::array<double, 3> velocity{0, 0, 0};     ///< of the centre of mass (not in `.sim`)
  std::array<double, 3> angularVelocity{0, 0, 0};  ///< radians/s, world axes (not in `.sim`)
  std::array<double, 3> centerOfMass{0, 0, 0};     ///< world (not in `.sim`)
};

/// Everything recorded for one frame.
struct FrameSnapshot {
  std::int64_t frame = 0;            ///< frame number; frame 0 is the initial state
  double time = 0;                   ///< seconds since the start, frame / fps
  double framesPerSecond = 24;       ///< the scene's frame rate (for PDC ticks)
  std::vector<FluidSnapshot> fluids; ///< in scene order
  std::vector<ObjectSnapshot> objects;  ///< rigid bodies, in scene order
};

}  // namespace softsub

namespace softsub {

/// Something that receives each recorded frame (cache writers, the viewer, tests).
/// One virtual call per frame, never per particle.
class FrameObserver {
 public:
  virtual ~FrameObserver() = default;
  /// Called once per recorded frame, in frame order, starting with frame 0.
  virtual void onFrame(const FrameSnapshot& frame) = 0;
};

}  // namespace softsub
