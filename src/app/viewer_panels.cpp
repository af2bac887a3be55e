// The viewer's Dear ImGui panels: statistics and controls, every fluid parameter, the
// interaction functions plotted live (formula and sampled table), Curve control points
// dragged with the mouse, the stability hint, and the help overlay.
#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include <fmt/format.h>
#include <imgui.h>

#include "core/error.h"
#include "fluid/fluid_params.h"
#include "forces/function.h"
#include "forces/interaction_table.h"
#include "render_playback.h"
#include "session/live_session.h"
#include "viewer.h"

namespace softsub::app {

namespace {

const ImVec4 kGood{0.45f, 0.85f, 0.45f, 1};
const ImVec4 kWarn{0.95f, 0.75f, 0.25f, 1};
const ImVec4 kBad{1.0f, 0.35f, 0.3f, 1};

ImVec4 verdictColour(solver::StabilityVerdict v) {
  switch (v) {
    case solver::StabilityVerdict::Stable: return kGood;
    case solver::StabilityVerdict::Marginal: return kWarn;
    case solver::StabilityVerdict::Unstable: return kBad;
  }
  return kBad;
}

bool dragDouble(const char* label, double& v, double speed, double lo, double hi, const char* format = "%.4g") {
  return ImGui::DragScalar(label, ImGuiDataType_Double, &v, static_cast<float>(speed), &lo, &hi, format,
                           ImGuiSliderFlags_AlwaysClamp);
}

/// A few points that follow `f`: what a function becomes when it is turned into a Curve.
forces::Curve curveFrom(const forces::PairFunction& f) {
  forces::Curve c;
  const double end = forces::cutoff(f);
  const int n = 6;
  for (int i = 0; i < n; ++i) {
    const double r = end * (0.15 + 0.85 * i / (n - 1)) * (i == n - 1 ? 0.999 : 1.0);
    c.points.push_back(r);
    c.points.push_back(forces::evaluate(f, r));
  }
  return c;
}

/// Plots F(r) from the formula (line) and the sampled table the solver uses (dots) from
/// 0 to past the cutoff. A Curve's control points can be dragged when `editable`; returns
/// true when one moved.
bool plotFunction(const char* id, forces::PairFunction& f, bool editable) {
  ImGui::PushID(id);
  const float width = std::max(ImGui::GetContentRegionAvail().x, 120.0f);
  const float height = 140;
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const ImVec2 p1{p0.x + width, p0.y + height};
  ImGui::InvisibleButton("plot", ImVec2(width, height));
  const bool hovered = ImGui::IsItemHovered();
  const bool active = ImGui::IsItemActive();
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->AddRectFilled(p0, p1, IM_COL32(24, 26, 30, 255));

  const double cut = std::max(forces::cutoff(f), 1e-6);
  const double rMax = cut * 1.15;
  constexpr int kSamples = 240;
  std::vector<double> values(kSamples + 1);
  double lo = 0, hi = 0;
  double attract = 0;
  for (int i = 0; i <= kSamples; ++i) {
    const double r = rMax * std::max(i, 1) / kSamples;
    values[i] = forces::evaluate(f, r);
    attract = std::min(attract, values[i]);
  }
  for (double v : values) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  // The true 12-6 force is unbounded near 0, and a clamped repulsion often dwarfs the
  // attraction: "zoom" shows the curve up to a multiple of its attraction.
  ImGuiStorage* storage = ImGui::GetStateStorage();
  const ImGuiID zoomKey = ImGui::GetID("zoom");
  bool zoom = storage->GetBool(zoomKey, std::holds_alternative<forces::LennardJonesForce>(f));
  if (zoom && attract < 0) hi = std::min(hi, -8 * attract);
  if (const auto* c = std::get_if<forces::Curve>(&f))
    for (std::size_t k = 1; k < c->points.size(); k += 2) {
      lo = std::min(lo, c->points[k]);
      hi = std::max(hi, c->points[k]);
    }
  if (hi - lo < 1e-12) hi = lo + 1;
  const double pad = 0.08 * (hi - lo);
  lo -= pad;
  hi += pad;
  auto toScreen = [&](double r, double v) {
    const double y = std::clamp((v - lo) / (hi - lo), -0.05, 1.05);
    return ImVec2(p0.x + static_cast<float>(r / rMax) * width, p1.y - static_cast<float>(y) * height);
  };
  auto fromScreen = [&](ImVec2 s) {
    return std::pair{std::clamp((s.x - p0.x) / width, 0.0f, 1.0f) * rMax,
                     lo + (p1.y - s.y) / height * (hi - lo)};
  };

  dl->PushClipRect(p0, p1, true);
  // Zero line and cutoff.
  dl->AddLine(toScreen(0, 0), toScreen(rMax, 0), IM_COL32(110, 110, 120, 255));
  dl->AddLine(toScreen(cut, lo), toScreen(cut, hi), IM_COL32(90, 90, 140, 255));
  // The sampled table, as the solver sees it.
  const forces::SampledFunction table = forces::sample(f);
  const std::size_t pieces = table.intervals();
  const std::size_t every = std::max<std::size_t>(1, pieces / 60);
  for (std::size_t k = 0; k < pieces; k += every) {
    const double r = static_cast<double>(k) / table.invDr;
    dl->AddCircleFilled(toScreen(r, table.pieces[2 * k]), 2.2f, IM_COL32(255, 160, 60, 255));
  }
  // The formula.
  for (int i = 1; i <= kSamples; ++i)
    dl->AddLine(toScreen(rMax * std::max(i - 1, 1) / kSamples, values[i - 1]), toScreen(rMax * i / kSamples, values[i]),
                IM_COL32(230, 230, 240, 255), 1.5f);

  bool changed = false;
  if (auto* c = std::get_if<forces::Curve>(&f); c != nullptr && editable) {
    const ImGuiID key = ImGui::GetID("selected");
    int selected = storage->GetInt(key, -1);
    const ImVec2 mouse = ImGui::GetIO().MousePos;
    const std::size_t n = c->points.size() / 2;
    if (hovered && ImGui::IsMouseClicked(ImGuiMouseButton_Left)) {
      selected = -1;
      float best = 10.0f * 10.0f;
      for (std::size_t k = 0; k < n; ++k) {
        const ImVec2 s = toScreen(c->points[2 * k], c->points[2 * k + 1]);
        const float d = (s.x - mouse.x) * (s.x - mouse.x) + (s.y - mouse.y) * (s.y - mouse.y);
        if (d < best) {
          best = d;
          selected = static_cast<int>(k);
        }
      }
    }
    if (!active) selected = -1;
    if (selected >= 0 && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.0f)) {
      auto [r, v] = fromScreen(mouse);
      const std::size_t k = static_cast<std::size_t>(selected);
      const double gap = 1e-3 * cut;
      const double rLo = k == 0 ? 0.0 : c->points[2 * (k - 1)] + gap;
      const double rHi = k + 1 == n ? rMax : c->points[2 * (k + 1)] - gap;
      c->points[2 * k] = std::clamp(r, rLo, std::max(rLo, rHi));
      c->points[2 * k + 1] = v;
      changed = true;
    }
    storage->SetInt(key, selected);
    for (std::size_t k = 0; k < n; ++k)
      dl->AddCircleFilled(toScreen(c->points[2 * k], c->points[2 * k + 1]), static_cast<int>(k) == selected ? 6.0f : 4.5f,
                          IM_COL32(90, 200, 255, 255));
  }
  dl->PopClipRect();
  dl->AddRect(p0, p1, IM_COL32(80, 80, 90, 255));
  dl->AddText(ImVec2(p0.x + 4, p0.y + 2), IM_COL32(200, 200, 210, 255), fmt::format("F max {:.3g}", hi - pad).c_str());
  dl->AddText(ImVec2(p0.x + 4, p1.y - 16), IM_COL32(200, 200, 210, 255), fmt::format("F min {:.3g}", lo + pad).c_str());
  dl->AddText(ImVec2(p1.x - 90, p1.y - 16), IM_COL32(200, 200, 210, 255), fmt::format("r to {:.3g}", rMax).c_str());
  if (hovered) {
    const auto [r, v] = fromScreen(ImGui::GetIO().MousePos);
    (void)v;
    ImGui::SetTooltip("r = %.4g\nformula F = %.5g\ntable   F = %.5g", r, forces::evaluate(f, r), table.at(r));
  }
  if (ImGui::Checkbox("zoom on the attraction", &zoom)) storage->SetBool(zoomKey, zoom);
  ImGui::SameLine();
  ImGui::TextDisabled("line: formula, dots: sampled table%s",
                      std::holds_alternative<forces::Curve>(f) && editable ? ", blue: drag the points" : "");
  ImGui::PopID();
  return changed;
}

/// Edits one interaction: its function kind and parameters, its velocity terms, and its
/// plot. Returns true when anything changed.
bool editInteraction(const char* id, scene::InteractionDesc& d) {
  ImGui::PushID(id);
  bool changed = false;
  constexpr const char* kinds[] = {"Linear", "LennardJones", "LennardJonesForce", "Curve"};
  int kind = static_cast<int>(d.function.index());
  if (ImGui::Combo("kind", &kind, kinds, 4) && kind != static_cast<int>(d.function.index())) {
    const double cut = forces::cutoff(d.function);
    switch (kind) {
      case 0: d.function = forces::Linear{5, cut, 0, 5}; break;
      case 1: d.function = forces::LennardJones{1, cut / 1.5, -1, 10, cut}; break;
      case 2: d.function = forces::LennardJonesForce{1, cut / 2.5, cut}; break;
      default: d.function = curveFrom(d.function); break;
    }
    changed = true;
  }
  if (auto* l = std::get_if<forces::Linear>(&d.function)) {
    changed |= dragDouble("AtZero", l->atZero, 0.05, -1e6, 1e6);
    changed |= dragDouble("Cutoff", l->cutoff, 0.01, 1e-4, 1e4);
    changed |= dragDouble("Min", l->min, 0.05, -1e6, 1e6);
    changed |= dragDouble("Max", l->max, 0.05, -1e6, 1e6);
  } else if (auto* j = std::get_if<forces::LennardJones>(&d.function)) {
    changed |= dragDouble("Amplitude", j->amplitude, 0.1, 0, 1e6);
    changed |= dragDouble("FiniteDistance", j->finiteDistance, 0.01, 1e-4, 1e4);
    changed |= dragDouble("Min", j->min, 0.1, -1e6, 0);
    changed |= dragDouble("Max", j->max, 0.5, 0, 1e6);
    changed |= dragDouble("Cutoff", j->cutoff, 0.01, 1e-4, 1e4);
  } else if (auto* t = std::get_if<forces::LennardJonesForce>(&d.function)) {
    changed |= dragDouble("Epsilon", t->epsilon, 0.01, 0, 1e6);
    changed |= dragDouble("Sigma", t->sigma, 0.01, 1e-4, 1e4);
    changed |= dragDouble("Cutoff", t->cutoff, 0.01, 1e-4, 1e4);
  } else if (auto* c = std::get_if<forces::Curve>(&d.function)) {
    if (ImGui::SmallButton("add point") && c->points.size() >= 2) {
      const double r = c->points[c->points.size() - 2];
      c->points.push_back(r * 1.2 + 1e-3);
      c->points.push_back(0);
      changed = true;
    }
    ImGui::SameLine();
    if (ImGui::SmallButton("remove last") && c->points.size() > 4) {
      c->points.resize(c->points.size() - 2);
      changed = true;
    }
  }
  changed |= dragDouble("Damping", d.damping, 0.01, 0, 1e6);
  changed |= dragDouble("RelativeVelocity", d.relativeVelocity, 0.01, 0, 1e6);
  changed |= plotFunction("plot", d.function, true);
  if (!std::holds_alternative<forces::Curve>(d.function) && ImGui::SmallButton("edit as curve")) {
    d.function = curveFrom(d.function);
    changed = true;
  }
  ImGui::PopID();
  return changed;
}

}  // namespace

void Viewer::applyEdits(std::optional<InputError>* refused) {
  editsPending_ = false;
  lastApply_ = std::chrono::steady_clock::now();
  if (!live()) return;
  try {
    const auto result = session_->applyEdits();
    if (result == session::EditResult::Restarted) setMessage("the edit changed the particles: restarted at frame 0");
    else if (messageIsError_) setMessage("");
  } catch (const InputError& e) {
    if (refused) refused->emplace(e);
    else setMessage(e.what(), true);
  }
  refreshStability();
}

void Viewer::refreshStability() {
  if (live()) stability_ = solver::assessStability(session_->model(), &session_->simulation().state());
}

void Viewer::drawPanels() {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(380, 0), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSizeConstraints(ImVec2(300, 100), ImVec2(600, ImGui::GetIO().DisplaySize.y - 20));
  ImGui::Begin("softsub");
  if (live()) {
    drawSimulationPanel();
    drawFluidPanels();
    drawInteractionsPanel();
  } else {
    drawPlaybackPanel();
  }
  if (!message_.empty()) {
    ImGui::Separator();
    ImGui::PushTextWrapPos(0);
    ImGui::TextColored(messageIsError_ ? kBad : ImVec4(0.8f, 0.85f, 0.9f, 1), "%s", message_.c_str());
    ImGui::PopTextWrapPos();
  }
  ImGui::TextDisabled("H: help");
  ImGui::End();
  if (showHelp_) drawHelpOverlay();
}

void Viewer::drawSimulationPanel() {
  const FrameSnapshot& f = frame();
  const solver::Model& model = session_->model();
  if (session_->substepInFrame() > 0)
    ImGui::Text("frame %lld + substep %d/%d   %s", static_cast<long long>(f.frame), session_->substepInFrame(),
                model.substeps, paused_ ? "(paused)" : "");
  else
    ImGui::Text("frame %lld   t = %.3f s   %s", static_cast<long long>(f.frame), f.time, paused_ ? "(paused)" : "");
  ImGui::Text("%zu particles   %.2f ms/step   %.0f fps", model.particleCount(), session_->lastStepMilliseconds(),
              uiFps_);
  drawTransport("restart");
  ImGui::SameLine();
  if (ImGui::Button("write caches")) writeCaches();
  ImGui::TextDisabled("%s", options_.record == 0 ? "not recording (--record 0): S writes nothing"
                                                 : session_->recordingNote().c_str());

  if (ImGui::CollapsingHeader("Simulation", ImGuiTreeNodeFlags_DefaultOpen)) {
    scene::SimulationDesc& sim = session_->editableDesc().simulation;
    int substeps = sim.substeps;
    if (ImGui::InputInt("Substeps", &substeps) && substeps >= 1 && substeps <= 10000) {
      sim.substeps = substeps;
      editsPending_ = true;
    }
    double g[3] = {sim.gravity.x(), sim.gravity.y(), sim.gravity.z()};
    if (ImGui::DragScalarN("Gravity", ImGuiDataType_Double, g, 3, 0.05f)) {
      sim.gravity = {g[0], g[1], g[2]};
      editsPending_ = true;
    }
    if (stability_) {
      const solver::StabilityReport& s = *stability_;
      ImGui::TextColored(verdictColour(s.verdict), "stability: %s at %d substeps",
                         std::string(solver::verdictName(s.verdict)).c_str(), s.substeps);
      if (s.worst < s.pairs.size() && s.verdict != solver::StabilityVerdict::Stable) {
        const solver::PairStability& p = s.pairs[s.worst];
        ImGui::PushTextWrapPos(0);
        if (s.minimumSubsteps > 0)
          ImGui::TextColored(verdictColour(s.verdict), "%s / %s: raise Substeps to %d or more, or soften the function",
                             p.first.c_str(), p.second.c_str(), s.minimumSubsteps);
        else
          ImGui::TextColored(kBad, "%s / %s: no substep count keeps this stable; soften the function",
                             p.first.c_str(), p.second.c_str());
        ImGui::PopTextWrapPos();
      }
    }
    ImGui::InputText("##save", savePath_, sizeof savePath_);
    ImGui::SameLine();
    if (ImGui::Button("save scene")) saveScene(savePath_);
  }
}

void Viewer::drawFluidPanels() {
  scene::SceneDesc& desc = session_->editableDesc();
  for (std::size_t i = 0; i < desc.fluids.size(); ++i) {
    scene::FluidDesc& fl = desc.fluids[i];
    ImGui::PushID(static_cast<int>(i));
    if (ImGui::CollapsingHeader(fmt::format("Fluid {}", fl.name).c_str(), i == 0 ? ImGuiTreeNodeFlags_DefaultOpen : 0)) {
      fluid::FluidParams& p = fl.params;
      bool changed = false;
      changed |= dragDouble("Amplitude", p.amplitude, 0.1, 0, 1e6);
      changed |= dragDouble("FiniteDistance", p.finiteDistance, 0.01, 1e-4, 1e4);
      changed |= dragDouble("MinimumForce", p.minimumForce, 0.1, -1e6, 0);
      changed |= dragDouble("MaximumForce", p.maximumForce, 0.5, 0, 1e6);
      changed |= dragDouble("InteractionDistance", p.interactionDistance, 0.01, 1e-4, 1e4);
      changed |= dragDouble("Viscosity", p.viscosity, 0.01, 0, 1e6);
      changed |= dragDouble("ParticleSize", p.particleSize, 0.01, 1e-4, 1e4);
      float colour[3] = {static_cast<float>(fl.colour.x()), static_cast<float>(fl.colour.y()),
                         static_cast<float>(fl.colour.z())};
      if (ImGui::ColorEdit3("Colour", colour)) {
        fl.colour = {colour[0], colour[1], colour[2]};
        changed = true;
      }
      forces::PairFunction own = fluid::ownFunction(p);
      plotFunction("own", own, false);
      ImGui::PushTextWrapPos(0);
      if (stability_)
        for (const solver::PairStability& s : stability_->pairs)
          if (s.first == fl.name && s.second == fl.name)
            ImGui::TextColored(verdictColour(s.verdict), "%s: omega dt %.3f, damping %.3f%s",
                               std::string(solver::verdictName(s.verdict)).c_str(), s.omegaDt,
                               std::max(s.dampingNumber, s.latticeDampingNumber),
                               s.verdict == solver::StabilityVerdict::Stable
                                   ? ""
                                   : fmt::format(", needs {} substeps", s.minimumSubsteps).c_str());
      ImGui::PopTextWrapPos();
      if (changed) editsPending_ = true;
    }
    ImGui::PopID();
  }
}

void Viewer::drawInteractionsPanel() {
  scene::InteractionsDesc& in = session_->editableDesc().interactions;
  if (!ImGui::CollapsingHeader("Interactions")) return;
  if (ImGui::TreeNode("FluidFluid (different fluids)")) {
    editsPending_ |= editInteraction("ff", in.fluidFluid);
    ImGui::TreePop();
  }
  if (ImGui::TreeNode("FluidObject (fluids and objects)")) {
    editsPending_ |= editInteraction("fo", in.fluidObject);
    ImGui::TreePop();
  }
  for (std::size_t k = 0; k < in.pairs.size(); ++k) {
    scene::PairDesc& p = in.pairs[k];
    ImGui::PushID(static_cast<int>(k));
    if (ImGui::TreeNode(fmt::format("Pair {} / {}", p.a, p.b).c_str())) {
      editsPending_ |= editInteraction("pair", p.interaction);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

void Viewer::drawPlaybackPanel() {
  const FrameSnapshot& f = frame();
  std::size_t particles = 0;
  for (const FluidSnapshot& fl : f.fluids) particles += fl.count();
  ImGui::Text("recording %s: %zu frames", sceneName_.c_str(), recorded_->frameCount());
  ImGui::Text("frame %lld   t = %.3f s   %zu particles   %.0f fps", static_cast<long long>(f.frame), f.time,
              particles, uiFps_);
  int index = static_cast<int>(playIndex_);
  if (ImGui::SliderInt("frame", &index, 0, static_cast<int>(recorded_->frameCount()) - 1) &&
      static_cast<std::size_t>(index) != playIndex_) {
    playIndex_ = static_cast<std::size_t>(index);
    playFrame_ = recorded_->load(playIndex_);
  }
  drawTransport("first frame");
  for (const std::string& w : playbackWarnings_) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", w.c_str());
    ImGui::PopStyleColor();
  }
}

void Viewer::drawTransport(const char* restartLabel) {
  if (ImGui::Button(paused_ ? "play" : "pause")) {
    // Playing a recording that has reached its end starts it again.
    if (paused_ && !live() && playIndex_ + 1 >= recorded_->frameCount()) restart();
    paused_ = !paused_;
  }
  ImGui::SameLine();
  if (ImGui::Button("step")) {
    stepOnce_ = true;
    paused_ = true;
  }
  ImGui::SameLine();
  if (ImGui::Button(restartLabel)) restart();
  ImGui::SameLine();
  ImGui::Checkbox("surfaces (M)", &surfaces_);
}

void Viewer::drawHelpOverlay() {
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(size.x - 10, 10), ImGuiCond_Always, ImVec2(1, 0));
  ImGui::SetNextWindowBgAlpha(0.8f);
  ImGui::Begin("keys", &showHelp_, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
  constexpr std::pair<const char*, const char*> keys[] = {
      {"Up / Down", "move the camera forward / back"},
      {"Left / Right", "turn the camera left / right"},
      {"left drag", "orbit around the scene"},
      {"mouse wheel", "zoom"},
      {"C", "back to the scene's camera"},
      {"Space", "pause / play"},
      {"N", "step one frame"},
      {"R", "restart (recording: first frame)"},
      {"S", "write the recorded frames as caches"},
      {"M", "surfaces instead of particles"},
      {"P", "screenshot <scene>.screenshot.NNNN.png"},
      {"H / F1", "this help"},
      {"Esc / Q", "quit"},
  };
  for (const auto& [k, what] : keys) {
    ImGui::TextColored(ImVec4(0.6f, 0.8f, 1, 1), "%-13s", k);
    ImGui::SameLine();
    ImGui::TextUnformatted(what);
  }
  ImGui::End();
}

}  // namespace softsub::app
