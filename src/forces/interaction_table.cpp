#include "forces/interaction_table.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace softsub::forces {

double SampledFunction::at(double r) const {
  if (r >= cutoff || pieces.empty()) return 0.0;
  const double t = std::max(r, 0.0) * invDr;
  const std::size_t k = std::min(static_cast<std::size_t>(t), intervals() - 1);
  return pieces[2 * k] + pieces[2 * k + 1] * (t - static_cast<double>(k));
}

SampledFunction sample(const PairFunction& f, int intervals) {
  SampledFunction s;
  s.cutoff = cutoff(f);
  const int n = std::max(intervals, 1);
  s.invDr = s.cutoff > 0 ? n / s.cutoff : 0;
  s.pieces.resize(2 * static_cast<std::size_t>(n));
  if (s.cutoff <= 0) return s;
  const double dr = s.cutoff / n;
  auto value = [&](int k) {
    // The last sample is the limit from below (F may jump to 0 at the cutoff).
    const double r = k == n ? s.cutoff * (1 - 1e-12) : k * dr;
    return evaluate(f, r);
  };
  double v0 = value(0);
  for (int k = 0; k < n; ++k) {
    const double v1 = value(k + 1);
    s.pieces[2 * k] = static_cast<float>(v0);
    s.pieces[2 * k + 1] = static_cast<float>(v1 - v0);
    v0 = v1;
  }
  return s;
}

double lengthScale(const PairFunction& f) {
  double length = 0;
  if (const auto* lj = std::get_if<LennardJones>(&f)) length = lj->finiteDistance;
  if (const auto* ljf = std::get_if<LennardJonesForce>(&f)) length = ljf->sigma;
  if (const auto* c = std::get_if<Curve>(&f))
    for (std::size_t k = 2; k + 1 < c->points.size(); k += 2)
      if (const double gap = c->points[k] - c->points[k - 2]; gap > 0 && (length == 0 || gap < length))
        length = gap;
  return length;
}

double samplingError(const PairFunction& f, int intervals) {
  const double length = lengthScale(f), rc = cutoff(f);
  if (!(length > 0) || !(rc > 0)) return 0;
  const SampledFunction s = sample(f, intervals);
  // From 0.9 length scales on, where particles sit: below it an unclamped 12-6 force is so
  // large that any error looks small beside it.
  const double begin = std::min(0.9 * length, rc), end = std::min(rc, 4 * length);
  constexpr int kPoints = 4096;
  double error = 0, largest = 0;
  for (int k = 0; k < kPoints; ++k) {
    const double r = begin + (end - begin) * (k + 0.5) / kPoints;
    const double exact = evaluate(f, r);
    largest = std::max(largest, std::abs(exact));
    error = std::max(error, std::abs(s.at(r) - exact));
  }
  return largest > 0 ? error / largest : 0;
}

int intervalsFor(const PairFunction& f, int intervals) {
  const int n = std::max(intervals, 1);
  const double rc = cutoff(f);
  const double length = lengthScale(f);  // 0: none (a straight line)
  if (!(length > 0) || !(rc > 2 * length)) return n;
  const double wanted = std::ceil(0.5 * n * rc / length);
  return wanted >= kMaxIntervals ? std::max(n, kMaxIntervals) : std::max(n, static_cast<int>(wanted));
}

namespace {
// InteractionTable::closedFormLj() for a table whose one interaction is `in`.
std::optional<ClosedFormLj> closedFormOf(const Interaction& in) {
  const auto* lj = std::get_if<LennardJonesForce>(&in.function);
  if (lj == nullptr || in.damping != 0 || in.relativeVelocity != 0) return std::nullopt;
  if (!(lj->epsilon > 0 && lj->sigma > 0 && lj->cutoff > 0)) return std::nullopt;
  ClosedFormLj c;
  const double s2 = lj->sigma * lj->sigma;
  c.a = static_cast<float>(48.0 * lj->epsilon / s2);
  c.b = static_cast<float>(24.0 * lj->epsilon / s2);
  c.sigma2 = static_cast<float>(s2);
  c.cutoff2 = static_cast<float>(lj->cutoff * lj->cutoff);
  // The distance where the formula reaches its clamp: F falls with r below sigma, so
  // bisect on (0, sigma] for the largest r whose F is still clamped.
  const double limit = evaluate(in.function, 0.0);
  if (evaluate(in.function, lj->sigma) >= limit) return std::nullopt;  // units where sigma is clamped: the table
  double lo = 0, hi = lj->sigma;
  for (int k = 0; k < 200 && hi - lo > 1e-12 * lj->sigma; ++k) {
    const double mid = 0.5 * (lo + hi);
    (evaluate(in.function, mid) >= limit ? lo : hi) = mid;
  }
  c.minR2 = static_cast<float>(hi * hi);
  return c;
}
}  // namespace

InteractionTable::InteractionTable(std::size_t materials, int intervals)
    : materials_(materials),
      intervals_(intervals),
      entries_(materials * materials),
      described_(materials * materials),
      samples_(2, 0.0f),
      rowCutoff2_(materials, 0.0f) {
  // Every pair starts as "nothing": zero cutoff, pointing at one zero piece at offset 0,
  // so that the branch-free kernel may read an entry's table whatever the distance.
}

std::uint32_t InteractionTable::addSamples(const PairFunction& f, double* cutoffOut, int* intervalsOut) {
  *cutoffOut = cutoff(f);
  // The function last found first: a scene of many fluids sets the same FluidFluid
  // function for most of its pairs.
  if (lastFound_ < sampledFunctions_.size() && sampledFunctions_[lastFound_].function == f) {
    *intervalsOut = sampledFunctions_[lastFound_].intervals;
    return sampledFunctions_[lastFound_].offset;
  }
  for (std::size_t k = 0; k < sampledFunctions_.size(); ++k)
    if (sampledFunctions_[k].function == f) {
      lastFound_ = k;
      *intervalsOut = sampledFunctions_[k].intervals;
      return sampledFunctions_[k].offset;
    }
  const int n = intervalsFor(f, intervals_);
  if (samples_.size() + 2 * static_cast<std::size_t>(n) > kMaxTableFloats)
    throw std::length_error(
        std::to_string(sampledFunctions_.size() + 1) + " distinct pair functions need more than the " +
        std::to_string(kMaxTableFloats * sizeof(float) >> 20) + " MiB the interaction table may hold");
  const SampledFunction s = sample(f, n);
  const auto offset = static_cast<std::uint32_t>(samples_.size());
  samples_.insert(samples_.end(), s.pieces.begin(), s.pieces.end());
  sampledFunctions_.push_back({f, offset, n});
  *intervalsOut = n;
  return offset;
}

void InteractionTable::set(std::size_t a, std::size_t b, const Interaction& in) {
  double rc = 0;
  int n = 0;
  PairEntry e;
  e.offset = addSamples(in.function, &rc, &n);
  e.cutoff2 = static_cast<float>(rc * rc);
  e.invDr = rc > 0 ? static_cast<float>(n / rc) : 0.0f;
  e.damping = static_cast<float>(in.damping);
  e.relativeVelocity = static_cast<float>(in.relativeVelocity);
  e.lastPiece = static_cast<std::uint32_t>(n - 1);
  // Count the entries with a velocity term as they are replaced (O(1) per set()).
  const auto moving = [](const PairEntry& p) { return p.damping != 0 || p.relativeVelocity != 0; };
  const float replaced = entries_[a * materials_ + b].cutoff2;
  for (const std::size_t k : {a * materials_ + b, b * materials_ + a}) {
    velocityEntries_ -= moving(entries_[k]) ? 1 : 0;
    velocityEntries_ += moving(e) ? 1 : 0;
    relativeEntries_ -= entries_[k].relativeVelocity != 0 ? 1 : 0;
    relativeEntries_ += e.relativeVelocity != 0 ? 1 : 0;
    entries_[k] = e;
    if (a == b) break;
  }
  described_[a * materials_ + b] = in;
  described_[b * materials_ + a] = in;

  // Only rows a and b changed. A cutoff that grows (as every pair's does when a scene is
  // compiled: from nothing to its function) raises their maxima in O(1); one that
  // shrinks has them looked for again, O(materials).
  for (const std::size_t r : {a, b}) {
    if (e.cutoff2 >= replaced) {
      rowCutoff2_[r] = std::max(rowCutoff2_[r], e.cutoff2);
      continue;
    }
    rowCutoff2_[r] = 0;
    for (std::size_t c = 0; c < materials_; ++c)
      rowCutoff2_[r] = std::max(rowCutoff2_[r], entries_[r * materials_ + c].cutoff2);
  }
  closedForm_ = materials_ == 1 ? closedFormOf(described_.front()) : std::nullopt;
}

double InteractionTable::maxCutoff() const {
  double m = 0;
  for (const PairEntry& e : entries_) m = std::max(m, std::sqrt(static_cast<double>(e.cutoff2)));
  return m;
}


double InteractionTable::sampledAt(std::size_t a, std::size_t b, double r) const {
  const PairEntry& e = entry(a, b);
  if (r * r >= e.cutoff2 || e.invDr == 0) return 0.0;
  const float t = static_cast<float>(r) * e.invDr;
  const std::uint32_t k = std::min(static_cast<std::uint32_t>(t), e.lastPiece);
  return samples_[e.offset + 2 * k] + samples_[e.offset + 2 * k + 1] * (t - static_cast<float>(k));
}

}  // namespace softsub::forces
