#include "session/live_session.h"

#include <fmt/format.h>

#include <chrono>
#include <utility>

#include "core/error.h"
#include "scene/compile.h"
#include "scene/reader.h"
#include "scene/writer.h"
#include "session/object_meshes.h"

namespace softsub::session {

namespace {

/// True when a and b make the same particles with the same initial state: the same
/// fluids (names, explicit positions, fills, initial speed) and objects (geometry,
/// particle size, placement, initial motion, static or dynamic). Everything else only
/// changes how the particles move from here on.
bool sameParticles(const scene::SceneDesc& a, const scene::SceneDesc& b) {
  if (a.fluids.size() != b.fluids.size() || a.objects.size() != b.objects.size()) return false;
  for (std::size_t i = 0; i < a.fluids.size(); ++i) {
    const scene::FluidDesc& x = a.fluids[i];
    const scene::FluidDesc& y = b.fluids[i];
    if (x.name != y.name || x.particles != y.particles || x.fills != y.fills || x.initialSpeed != y.initialSpeed)
      return false;
  }
  for (std::size_t i = 0; i < a.objects.size(); ++i) {
    const scene::ObjectDesc& x = a.objects[i];
    const scene::ObjectDesc& y = b.objects[i];
    if (x.name != y.name || x.geometry != y.geometry || x.shape != y.shape || x.size != y.size ||
        x.particleSize != y.particleSize || x.uniformScale != y.uniformScale ||
        x.initialPosition != y.initialPosition || x.initialRotation != y.initialRotation ||
        x.initialLinearVelocity != y.initialLinearVelocity ||
        x.initialAngularVelocity != y.initialAngularVelocity || x.isDynamic != y.isDynamic)
      return false;
  }
  return true;
}

/// True when two models number their particles the same way: per fluid and per body
/// the same first id and count.
bool sameLayout(const solver::Model& a, const solver::Model& b) {
  if (a.fluids.size() != b.fluids.size() || a.bodies.bodies.size() != b.bodies.bodies.size()) return false;
  for (std::size_t f = 0; f < a.fluids.size(); ++f)
    if (a.fluids[f].firstId != b.fluids[f].firstId || a.fluids[f].count != b.fluids[f].count) return false;
  for (std::size_t i = 0; i < a.bodies.bodies.size(); ++i)
    if (a.bodies.bodies[i].firstId != b.bodies.bodies[i].firstId || a.bodies.bodies[i].count != b.bodies.bodies[i].count)
      return false;
  return a.particleCount() == b.particleCount();
}

/// Bytes a kept frame holds (its arrays and names).
std::size_t snapshotBytes(const FrameSnapshot& f) {
  std::size_t bytes = sizeof(FrameSnapshot);
  for (const FluidSnapshot& s : f.fluids)
    bytes += sizeof(FluidSnapshot) + s.name.size() + s.ids.size() * sizeof(std::uint32_t) +
             (s.positions.size() + s.velocities.size()) * sizeof(float);
  for (const ObjectSnapshot& o : f.objects) bytes += sizeof(ObjectSnapshot) + o.name.size() + o.filename.size();
  return bytes;
}

std::string bytesText(std::size_t bytes) {
  const double b = static_cast<double>(bytes);
  if (bytes >= (std::size_t{1} << 30)) return fmt::format("{:.1f} GiB", b / static_cast<double>(1 << 30));
  if (bytes >= (std::size_t{1} << 20)) return fmt::format("{:.1f} MiB", b / static_cast<double>(1 << 20));
  return fmt::format("{} bytes", bytes);
}

}  // namespace

LiveSession::LiveSession(scene::SceneDesc desc, std::string sceneName, std::filesystem::path outDir,
                         cache::Formats formats)
    : sceneName_(std::move(sceneName)), outDir_(std::move(outDir)), formats_(formats), applied_(std::move(desc)) {
  validate(applied_);
  edited_ = applied_;
  wantRecording_ = recording_ = formats_.sim || formats_.pdc || formats_.ply;
  start(scene::compile(applied_));
}

LiveSession::~LiveSession() {
  sim_.reset();  // before the model it refers to
}

void LiveSession::validate(const scene::SceneDesc& desc) const {
  // Exactly what a file would go through: the writer's text, read back by the reader,
  // as if it lay in the scene's folder (mesh paths resolve there).
  const std::filesystem::path base = desc.baseDir.empty() ? std::filesystem::path(".") : std::filesystem::path(desc.baseDir);
  const std::string text = scene::writeSceneText(desc);
  try {
    (void)scene::readSceneText(text, (base / (sceneName_ + ".scene")).string());
  } catch (const InputError& e) {
    // The text's line numbers point into a file nobody sees: name the edited scene.
    throw InputError({sceneName_ + ".scene (edited)", 0, e.where().element}, e.problem(), e.allowed());
  }
}

void LiveSession::start(scene::Compiled compiled) {
  std::vector<cache::ObjectMesh> cacheMeshes = objectMeshesForCache(compiled.model, compiled.objectMeshes, sceneName_);
  auto model = std::make_unique<solver::Model>(std::move(compiled.model));
  auto sim = std::make_unique<solver::Simulation>(*model, std::move(compiled.state));
  sim_ = std::move(sim);  // the old simulation goes before the old model
  model_ = std::move(model);
  meshes_ = std::move(compiled.objectMeshes);
  cacheMeshes_ = std::move(cacheMeshes);
  blownUp_ = false;
  lastStepMs_ = 0;
  substepInFrame_ = 0;
  recorded_.clear();
  recorded_.shrink_to_fit();
  recordedBytes_ = 0;
  note_.clear();
  recording_ = wantRecording_;
  refreshSnapshot();
  record();
}

void LiveSession::restart() { start(scene::compile(applied_)); }

EditResult LiveSession::applyEdits() {
  scene::Compiled compiled;
  try {
    validate(edited_);
    compiled = scene::compile(edited_);
  } catch (...) {
    edited_ = applied_;  // the old description and model keep running
    throw;
  }
  const bool restart = blownUp_ || !sameParticles(applied_, edited_) || !sameLayout(*model_, compiled.model);
  applied_ = edited_;
  if (restart) {
    start(std::move(compiled));
    return EditResult::Restarted;
  }
  std::vector<cache::ObjectMesh> cacheMeshes = objectMeshesForCache(compiled.model, compiled.objectMeshes, sceneName_);
  // Continue from the current particles. Only what the model decides per particle is
  // taken from the new compile: its material row (objects that now differ in their
  // interactions get rows of their own), found by stable id.
  sim_->levelVelocities();  // an edit between two substeps of a frame: whole-step velocities
  solver::State state = sim_->state();
  state.forcesValid = false;
  const ParticleStore& fresh = compiled.state.particles;
  std::vector<std::uint16_t> materialOfId(fresh.size());
  for (std::size_t i = 0; i < fresh.size(); ++i) materialOfId[fresh.id[i]] = fresh.material[i];
  ParticleStore& s = state.particles;
  for (std::size_t i = 0; i < s.size(); ++i) s.material[i] = materialOfId[s.id[i]];

  auto model = std::make_unique<solver::Model>(std::move(compiled.model));
  auto sim = std::make_unique<solver::Simulation>(*model, std::move(state));
  sim_ = std::move(sim);
  model_ = std::move(model);
  meshes_ = std::move(compiled.objectMeshes);
  cacheMeshes_ = std::move(cacheMeshes);
  refreshSnapshot();
  return EditResult::Continued;
}

void LiveSession::advanceFrame() {
  if (blownUp_)
    throw BlowUpError(fmt::format("the simulation blew up after frame {}: restart it or change the settings",
                                  snapshot_.frame));
  // Finish a frame begun substep by substep, else a whole one.
  while (substepInFrame_ != 0)
    if (advanceSubstep()) return;
  const auto start = std::chrono::steady_clock::now();
  try {
    sim_->advanceFrame();
  } catch (const BlowUpError&) {
    blownUp_ = true;
    throw;
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  lastStepMs_ = ms / sim_->substeps();
  refreshSnapshot();
  record();
}

bool LiveSession::advanceSubstep() {
  if (blownUp_)
    throw BlowUpError(fmt::format("the simulation blew up after frame {}: restart it or change the settings",
                                  snapshot_.frame));
  const auto start = std::chrono::steady_clock::now();
  const bool frameDone = substepInFrame_ + 1 >= sim_->substeps();
  try {
    sim_->step();  // checks every substep
    ++substepInFrame_;
    if (frameDone) {
      substepInFrame_ = 0;
      sim_->finishFrame();
    }
  } catch (const BlowUpError&) {
    blownUp_ = true;
    throw;
  }
  lastStepMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  refreshSnapshot();
  if (frameDone) record();
  return frameDone;
}

void LiveSession::refreshSnapshot() { sim_->snapshot(snapshot_); }

void LiveSession::setRecording(bool on) {
  wantRecording_ = on;
  recording_ = on;
  if (on) note_.clear();
}

void LiveSession::setStopRecordingAt(std::int64_t frame) { stopAt_ = frame; }

void LiveSession::record() {
  if (!recording_) return;
  if (stopAt_ >= 0 && snapshot_.frame > stopAt_) {
    recording_ = false;
    note_ = fmt::format("recording stopped after frame {} (stop-recording-at)", stopAt_);
    return;
  }
  const std::size_t bytes = snapshotBytes(snapshot_);
  if (recordedBytes_ + bytes > cap_) {
    recording_ = false;
    note_ = fmt::format("recording stopped at frame {}: keeping it would pass the {} memory cap "
                        "({} frames kept)",
                        snapshot_.frame, bytesText(cap_), recorded_.size());
    return;
  }
  recorded_.push_back(snapshot_);
  recordedBytes_ += bytes;
  if (stopAt_ >= 0 && snapshot_.frame >= stopAt_) {
    recording_ = false;
    note_ = fmt::format("recording stopped after frame {} (stop-recording-at)", stopAt_);
  }
}

RecordedWrite LiveSession::writeRecorded() {
  RecordedWrite w;
  w.folder = outDir_;
  if (recorded_.empty()) return w;
  cache::FrameWriter writer(outDir_, sceneName_, formats_);
  writer.setObjectMeshes(cacheMeshes_);
  for (const FrameSnapshot& f : recorded_) writer.onFrame(f);
  w.frames = recorded_.size();
  w.firstFrame = recorded_.front().frame;
  w.lastFrame = recorded_.back().frame;
  return w;
}

void LiveSession::saveScene(const std::filesystem::path& path) const {
  scene::writeSceneFile(applied_, path.string());
}

}  // namespace softsub::session
