#pragma once
/// A simulation the viewer drives and edits while it runs: it owns an editable copy of
/// the scene description, the Model compiled from it and the Simulation stepping it, and
/// keeps the frames it has shown (the seed's record mode) to write them as caches on
/// request. No OpenGL, no window: the front end (src/app) draws snapshot() and calls these.
///
/// Not thread-safe: one thread calls everything.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cache/frame_writer.h"
#include "cache/obj_format.h"
#include "core/snapshot.h"
#include "geometry/triangle_mesh.h"
#include "scene/compile.h"
#include "scene/scene_desc.h"
#include "solver/model.h"
#include "solver/simulation.h"

namespace softsub::session {

/// What applyEdits did.
enum class EditResult : std::uint8_t {
  Continued,  ///< the new settings run on from the current frame and particle state
  Restarted   ///< the edit changed the particles themselves (sources, initial state):
              ///< back to frame 0 with the new description
};

/// What writeRecorded wrote.
struct RecordedWrite {
  std::size_t frames = 0;          ///< frames written
  std::int64_t firstFrame = 0;     ///< frame number of the first one
  std::int64_t lastFrame = -1;     ///< frame number of the last one (-1: none)
  std::filesystem::path folder;    ///< the output folder
};

/// Default cap on the memory kept by the recording: 2 GiB of particle data.
inline constexpr std::size_t kDefaultRecordingCap = std::size_t{2} << 30;

/// A live, editable simulation with an in-memory recording.
class LiveSession {
 public:
  /// Validates `desc` as a scene file would be (InputError otherwise), compiles it and
  /// starts at frame 0. `sceneName` names the recording's files (`<sceneName>.NNNN.sim`),
  /// written into `outDir` in `formats` (no format: nothing is recorded).
  LiveSession(scene::SceneDesc desc, std::string sceneName, std::filesystem::path outDir,
              cache::Formats formats = {});
  ~LiveSession();
  LiveSession(LiveSession&&) noexcept = default;
  LiveSession& operator=(LiveSession&&) noexcept = default;

  /// The description the running model was built from (every applied edit included).
  [[nodiscard]] const scene::SceneDesc& desc() const { return applied_; }
  /// The description to edit (setFluidParameter and friends, or directly); the edits
  /// take effect at applyEdits(). Starts equal to desc().
  [[nodiscard]] scene::SceneDesc& editableDesc() { return edited_; }
  /// True when editableDesc() differs from desc().
  [[nodiscard]] bool hasPendingEdits() const { return !(edited_ == applied_); }

  /// Applies editableDesc(). It is validated first exactly as a file would be (written
  /// as .scene text and read back, mesh paths resolving against its baseDir); on
  /// InputError the edits are dropped (editableDesc() is reset to desc()), the old
  /// model keeps running, and the error is rethrown for the front end to show. When the
  /// edit leaves the particles as they are (functions, viscosity, masses, sizes,
  /// colours, gravity, substeps, integrator, container, interactions, object masses and
  /// coefficients) the new model continues from the current frame and state; when it
  /// changes the particles (fluids added, removed or renamed, their Particles, Fills or
  /// InitialSpeed, objects' geometry, placement, initial motion or IsDynamic) or the
  /// simulation has blown up, it restarts from frame 0 (and the recording with it).
  EditResult applyEdits();

  /// Back to frame 0 of desc() (key R). Clears the recording and records frame 0.
  void restart();

  /// One frame (model().substeps substeps); records it when recording. Throws
  /// BlowUpError as Simulation::advanceFrame does; snapshot() then keeps the last good
  /// frame, blownUp() is true, and only restart() or applyEdits() go on.
  void advanceFrame();

  /// One substep (the seed's -drawPerFrame 0: draw every update); snapshot() shows it.
  /// The substep that completes a frame advances frame() and records it, as
  /// advanceFrame does; returns true then. BlowUpError as advanceFrame (checked at the
  /// end of each frame).
  bool advanceSubstep();

  /// Substeps done in the current, unfinished frame (0 between frames).
  [[nodiscard]] int substepInFrame() const { return substepInFrame_; }

  /// The frame number of snapshot().
  [[nodiscard]] std::int64_t frame() const { return snapshot_.frame; }
  /// The current frame, in stable-id order (kept up to date by every call above).
  [[nodiscard]] const FrameSnapshot& snapshot() const { return snapshot_; }
  /// The running model.
  [[nodiscard]] const solver::Model& model() const { return *model_; }
  /// The running simulation (read access: state, diagnostics).
  [[nodiscard]] const solver::Simulation& simulation() const { return *sim_; }
  /// Wall time per substep of the last advanceFrame, milliseconds (0 before the first).
  [[nodiscard]] double lastStepMilliseconds() const { return lastStepMs_; }
  /// True after advanceFrame threw BlowUpError, until restart() or applyEdits().
  [[nodiscard]] bool blownUp() const { return blownUp_; }

  /// Each object's geometry in its own axes (before UniformScale and the pose; the
  /// snapshot's ObjectSnapshot places it), in scene order: the mesh of model().bodies.bodies[i].
  [[nodiscard]] const std::vector<geometry::TriangleMesh>& objectMeshes() const { return meshes_; }

  // Recording (the seed's record mode).

  /// Recording on or off (on by default unless no format is written). Turning it on
  /// records from the next frame; frames already kept stay.
  void setRecording(bool on);
  /// True while frames are being kept.
  [[nodiscard]] bool recording() const { return recording_; }
  /// The seed's -stopRecordingAt: recording stops after frame `frame` (-1: no limit).
  void setStopRecordingAt(std::int64_t frame);
  /// Caps the memory the recording keeps (bytes of particle and object data). When the
  /// next frame would pass it, recording stops and recordingNote() says so.
  void setRecordingCap(std::size_t bytes) { cap_ = bytes; }
  /// Frames kept so far.
  [[nodiscard]] std::size_t recordedFrames() const { return recorded_.size(); }
  /// The kept frames, in frame order.
  [[nodiscard]] const std::vector<FrameSnapshot>& recorded() const { return recorded_; }
  /// Bytes the kept frames hold.
  [[nodiscard]] std::size_t recordedBytes() const { return recordedBytes_; }
  /// Why recording stopped by itself (memory cap, -stopRecordingAt), or "".
  [[nodiscard]] const std::string& recordingNote() const { return note_; }
  /// Writes every kept frame through cache::FrameWriter into the output folder (with
  /// the objects' meshes, as `softsub run` does; key S). The recording is kept: writing
  /// again rewrites the same files. IoError when a file cannot be written.
  RecordedWrite writeRecorded();

  /// Writes desc() as a .scene file (atomically) that reads back equal to it.
  void saveScene(const std::filesystem::path& path) const;

  /// The name the recording's files take.
  [[nodiscard]] const std::string& sceneName() const { return sceneName_; }
  /// Where writeRecorded writes.
  [[nodiscard]] const std::filesystem::path& outputDir() const { return outDir_; }

 private:
  void validate(const scene::SceneDesc& desc) const;
  void start(scene::Compiled compiled);  // frame 0 of compiled (applied_'s)
  void record();
  void refreshSnapshot();

  std::string sceneName_;
  std::filesystem::path outDir_;
  cache::Formats formats_;
  scene::SceneDesc applied_;
  scene::SceneDesc edited_;
  // The Simulation refers to the Model, which lives on the heap so that its address never
  // changes (moves included). The simulation is declared first so that an assignment
  // replaces it before the model it refers to; the destructor drops it first.
  std::unique_ptr<solver::Simulation> sim_;
  std::unique_ptr<solver::Model> model_;
  std::vector<geometry::TriangleMesh> meshes_;
  std::vector<cache::ObjectMesh> cacheMeshes_;
  FrameSnapshot snapshot_;
  double lastStepMs_ = 0;
  int substepInFrame_ = 0;
  bool blownUp_ = false;

  bool recording_ = true;        // keeping frames now
  bool wantRecording_ = true;    // the user's setting (restart resumes it)
  std::int64_t stopAt_ = -1;
  std::size_t cap_ = kDefaultRecordingCap;
  std::vector<FrameSnapshot> recorded_;
  std::size_t recordedBytes_ = 0;
  std::string note_;
};

}  // namespace softsub::session
