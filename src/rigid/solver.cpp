#include "rigid/solver.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace softsub::rigid {

namespace {

// The mass ratio between two touching bodies from which their island takes shock
// propagation (RigidSolver::propagateShock).
constexpr double kShockRatio = 10;

// cos 3 degrees: two flat faces whose normals are this close to opposite meet face to face.
constexpr double kFacesMeet = 0.9986;

// Effective inverse mass of a contact along d: 1/ma + 1/mb + (ra x d) . Ia⁻¹ (ra x d) + (rb x d) . Ib⁻¹ (rb x d).
double inverseMassAlong(double invMa, const Mat3& invIa, const Vec3& ra, double invMb, const Mat3& invIb,
                        const Vec3& rb, const Vec3& d) {
  const Vec3 ca = ra.cross(d);
  double k = invMa + ca.dot(invIa * ca);
  if (invMb > 0 || !invIb.isZero()) {
    const Vec3 cb = rb.cross(d);
    k += invMb + cb.dot(invIb * cb);
  }
  return k;
}

// Calls fn(f, k, b) for each listed pair of a fluid particle (slot f) and a particle of
// body b (slot k).
template <class Fn>
void forFluidBodyPairs(const ParticleStore& s, std::uint32_t firstEntity, std::span<const SlotPair> pairs,
                       Fn&& fn) {
  for (const SlotPair& p : pairs) {
    std::uint32_t f = p[0], k = p[1];
    const bool fIsBody = s.owner[f] >= firstEntity, kIsBody = s.owner[k] >= firstEntity;
    if (fIsBody == kIsBody) continue;  // body/body: contacts
    if (fIsBody) std::swap(f, k);
    fn(f, k, s.owner[k] - firstEntity);
  }
}

// A fluid/body pair that drags: its function's velocity terms and the offset d from the
// body particle to the fluid particle, within the cutoff.
struct DragPair {
  double c = 0, k = 0;  ///< damping, RelativeVelocity
  Vec3 d{0, 0, 0};
  double r2 = 0;
};
bool dragPair(const forces::InteractionTable& table, const ParticleStore& s, std::uint32_t f, std::uint32_t k,
              DragPair& out) {
  const forces::PairEntry& e = table.entry(s.material[f], s.material[k]);
  if (e.damping == 0 && e.relativeVelocity == 0) return false;
  out.d = Vec3(s.px[f] - s.px[k], s.py[f] - s.py[k], s.pz[f] - s.pz[k]);
  out.r2 = out.d.squaredNorm();
  out.c = e.damping;
  out.k = e.relativeVelocity;
  return out.r2 < e.cutoff2;
}

}  // namespace

void RigidSolver::findBodySlots(const BodySet& set, const ParticleStore& s) {
  bodySlots_.clear();
  if (set.empty()) return;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.owner[i] >= set.firstEntity) bodySlots_.push_back(static_cast<std::uint32_t>(i));
}

void RigidSolver::writeParticles(const BodySet& set, const std::vector<BodyState>& states, ParticleStore& s) {
  const std::size_t nb = set.bodies.size();
  rot_.resize(nb);
  omega_.resize(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    rot_[b] = states[b].orientation.toRotationMatrix();
    omega_[b] = set.bodies[b].dynamic ? angularVelocity(set.bodies[b], states[b]) : Vec3::Zero();
  }
  for (const std::uint32_t i : bodySlots_) {
    const std::uint32_t b = s.owner[i] - set.firstEntity;
    const std::uint32_t k = s.id[i] - set.firstId;
    const Vec3 r = rot_[b] * Vec3(set.ox[k], set.oy[k], set.oz[k]);
    const Vec3 x = states[b].position + r;
    const Vec3 v = states[b].velocity + omega_[b].cross(r);
    s.px[i] = static_cast<float>(x.x()); s.py[i] = static_cast<float>(x.y()); s.pz[i] = static_cast<float>(x.z());
    s.vx[i] = static_cast<float>(v.x()); s.vy[i] = static_cast<float>(v.y()); s.vz[i] = static_cast<float>(v.z());
  }
}

// The seed's particle → owner "event": the forces on a body's particles add up to a
// force on the body and a torque about its centre of mass.
void RigidSolver::gatherForces(const BodySet& set, const std::vector<BodyState>& states, const ParticleStore& s) {
  const std::size_t nb = set.bodies.size();
  force_.assign(nb, Vec3::Zero());
  torque_.assign(nb, Vec3::Zero());
  for (const std::uint32_t i : bodySlots_) {
    const std::uint32_t b = s.owner[i] - set.firstEntity;
    const Vec3 f(s.f[i].x, s.f[i].y, s.f[i].z);
    const Vec3 r = Vec3(s.px[i], s.py[i], s.pz[i]) - states[b].position;
    force_[b] += f;
    torque_[b] += r.cross(f);
  }
}

// The fluid and the bodies pull each other along through the velocity terms of the
// fluid/object function (damping c on the relative velocity, RelativeVelocity k on its
// normal part), summed over every pair of a fluid particle and a body particle within
// reach. Taken explicitly, that drag damps far faster than one substep can follow
// wherever one side meets many particles of the other: a light body of fine particles
// under mud (a pallet of mass 2 of 1,600 particles of 0.25 gained about 2.6 times its
// kinetic energy a frame until the run blew up), and a fluid particle lying on about 200
// fine body particles, static or not (RelativeVelocity 5 or 10: the mud was flung off at
// hundreds of units a second; reviews, twenty-eighth session). So both sides take the
// drag at the end of the substep (linearly implicit Euler), solved together:
//   body:  (M + dt C) dq - dt sum_f G_fᵀ dv_f = dt Q
//   fluid: (m I + dt D_f) dv_f - dt G_f dq = e_f
// with dq the body's (dV, dw), M its mass and world inertia, Q its force and torque (the
// explicit drag included), C = sum Jᵀ D J over its pairs, J = [I, -[r]x] taking (V, w) to
// the velocity of the body particle at arm r, D = c I + k n nᵀ a pair's drag, D_f the sum
// of D over the fluid particle's pairs (all bodies), G_f = sum D J over its pairs with
// this body, and e_f = dt (f + m g) the fluid particle's explicit momentum step. Each
// fluid particle is eliminated (3 x 3), leaving per body
//   (M + dt C - dt² sum_f G_fᵀ A_f⁻¹ G_f) dq = dt Q + dt sum_f G_fᵀ A_f⁻¹ e_f,  A_f = m I + dt D_f,
// then dv_f = A_f⁻¹ (e_f + dt sum_b G_fb dq_b). The whole system's matrix is the masses
// plus dt times a sum of [J, -I]ᵀ D [J, -I], so it and the eliminated one are symmetric
// positive definite, and the pair impulses cancel: momentum is kept. A fluid particle
// touching two bodies couples them; each body's solve holds the other still (its share
// of the particle's A_f is still implicit). Where the drag is slight, every increment is
// the explicit step's to first order.
void RigidSolver::gatherDrag(const BodySet& set, const std::vector<BodyState>& states, const ParticleStore& s,
                             std::span<const SlotPair> pairs, const forces::InteractionTable& table,
                             std::span<const float> materialInverseMass, const Vec3& gravity, double dt) {
  const std::size_t nb = set.bodies.size();
  drag_.resize(nb);
  dragRhs_.resize(nb);
  dragged_.assign(nb, 0);
  for (const FluidDrag& fluid : fluids_) fluidRow_[fluid.slot] = kNoRow;  // a step left unfinished
  fluids_.clear();
  couplings_.clear();
  if (!table.hasVelocityTerms()) return;
  if (fluidRow_.size() < s.size()) fluidRow_.resize(s.size(), kNoRow);
  forFluidBodyPairs(s, set.firstEntity, pairs, [&](std::uint32_t f, std::uint32_t k, std::uint32_t b) {
    DragPair q;
    if (!dragPair(table, s, f, k, q)) return;
    // D = c I + k n nᵀ (n = d / |d|; coincident particles: no normal term).
    const Vec3& d = q.d;
    const double c = q.c, kd = q.r2 > 0 ? q.k / q.r2 : 0.0;  // kd on d, not on n
    Mat3 D = kd * d * d.transpose();
    D.diagonal().array() += c;
    std::uint32_t& row = fluidRow_[f];
    if (row == kNoRow) {
      row = static_cast<std::uint32_t>(fluids_.size());
      fluids_.push_back({f, -1, Mat3::Zero(), Mat3::Zero(), Vec3::Zero()});
    }
    FluidDrag& fluid = fluids_[row];
    fluid.sum += D;
    if (!set.bodies[b].dynamic) return;
    auto& C = drag_[b];
    if (!dragged_[b]) {
      C.setZero();
      dragRhs_[b].setZero();
      dragged_[b] = 1;
    }
    // With m = r x d the blocks of Jᵀ D J are D, -D [r]x = -c [r]x + kd d mᵀ, its
    // transpose, and -[r]x D [r]x = c (|r|² I - r rᵀ) + kd m mᵀ: outer products.
    const Vec3 r = Vec3(s.px[k], s.py[k], s.pz[k]) - states[b].position;
    const Vec3 m = r.cross(d);
    Mat3 rx;  // [r]x
    rx << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
    const Mat3 Drx = kd * d * m.transpose() - c * rx;  // -D [r]x
    C.topLeftCorner<3, 3>() += D;
    C.topRightCorner<3, 3>() += Drx;
    C.bottomRightCorner<3, 3>() += kd * m * m.transpose() - c * r * r.transpose();
    C.bottomRightCorner<3, 3>().diagonal().array() += c * r.squaredNorm();
    // G_fb += D J = [D, -D [r]x]: this pair's share of the fluid particle's coupling.
    std::int32_t at = fluid.first;
    while (at >= 0 && couplings_[static_cast<std::size_t>(at)].body != b)
      at = couplings_[static_cast<std::size_t>(at)].next;
    if (at < 0) {
      at = static_cast<std::int32_t>(couplings_.size());
      couplings_.push_back({b, fluid.first, Eigen::Matrix<double, 3, 6>::Zero()});
      fluid.first = at;
    }
    auto& g = couplings_[static_cast<std::size_t>(at)].g;
    g.leftCols<3>() += D;
    g.rightCols<3>() += Drx;
  });
  for (std::size_t b = 0; b < nb; ++b)  // the lower left block: the upper right's transpose
    if (dragged_[b]) drag_[b].bottomLeftCorner<3, 3>() = drag_[b].topRightCorner<3, 3>().transpose();
  // Each fluid particle eliminated: A_f⁻¹ and its explicit step, then its couplings'
  // terms in their bodies' systems (drag_ becomes C - dt sum Gᵀ A⁻¹ G, dragRhs_ sum Gᵀ A⁻¹ e).
  for (FluidDrag& fluid : fluids_) {
    const std::uint32_t f = fluid.slot;
    const double mass = 1.0 / materialInverseMass[s.material[f]];
    fluid.step = dt * (Vec3(s.f[f].x, s.f[f].y, s.f[f].z) + mass * gravity);
    Mat3 a = dt * fluid.sum;
    a.diagonal().array() += mass;
    fluid.inverse = a.inverse();  // symmetric positive definite, at least the particle's mass on the diagonal
    for (std::int32_t at = fluid.first; at >= 0; at = couplings_[static_cast<std::size_t>(at)].next) {
      const Coupling& cp = couplings_[static_cast<std::size_t>(at)];
      const Eigen::Matrix<double, 6, 3> gtInv = cp.g.transpose() * fluid.inverse;
      drag_[cp.body] -= dt * (gtInv * cp.g);
      dragRhs_[cp.body] += gtInv * fluid.step;
    }
  }
}

void RigidSolver::prepareDrag(const BodySet& set, const std::vector<BodyState>& states,
                              const ParticleStore& s, std::span<const SlotPair> pairs,
                              std::span<const float> materialInverseMass,
                              const forces::InteractionTable& table, const Vec3& gravity, double dt) {
  if (set.empty()) return;
  gatherDrag(set, states, s, pairs, table, materialInverseMass, gravity, dt);
  dragReady_ = true;
}

void RigidSolver::dragFluidHeld(const BodySet& set, const std::vector<BodyState>& states, ParticleStore& s,
                                std::span<const SlotPair> pairs, std::span<const float> materialInverseMass,
                                const forces::InteractionTable& table, const Vec3& gravity, double h) {
  if (set.empty()) return;
  gatherDrag(set, states, s, pairs, table, materialInverseMass, gravity, h);
  dragReady_ = false;  // set up for this kick; the next step sets up its own
  // The fluid's side of the drag with every body held: no body moved (dq = 0), nothing drifts.
  dragStep_.assign(set.bodies.size(), Eigen::Matrix<double, 6, 1>::Zero());
  dragFluid(s, materialInverseMass, h, 0.0, FluidKick::Whole);
}

// The fluid particles' share of the implicit drag (gatherDrag): each had its explicit
// step e_f / m added to its velocity (and, when the integrator drifts after kicking, to
// its position over `drift`); it gets dv_f = A_f⁻¹ (e_f + dt sum_b G_fb dq_b) instead.
void RigidSolver::dragFluid(ParticleStore& s, std::span<const float> materialInverseMass, double dt,
                            double drift, FluidKick kick) {
  for (const FluidDrag& fluid : fluids_) {
    const std::uint32_t f = fluid.slot;
    Vec3 w = fluid.step;
    for (std::int32_t at = fluid.first; at >= 0; at = couplings_[static_cast<std::size_t>(at)].next) {
      const Coupling& cp = couplings_[static_cast<std::size_t>(at)];
      w += dt * (cp.g * dragStep_[cp.body]);
    }
    const double inverseMass = materialInverseMass[s.material[f]];
    Vec3 change = fluid.inverse * w - fluid.step * inverseMass;
    if (kick == FluidKick::OpeningHalf) change += 0.5 * fluid.step * inverseMass;  // half was never given
    if (kick == FluidKick::AfterHeldHalf) {
      // The closing half was given explicitly, e / 2m, then corrected to A_h⁻¹ e / 2
      // (A_h = m I + dt/2 D_f): that correction comes out too, so that the whole implicit
      // step replaces both halves.
      Mat3 a = 0.5 * dt * fluid.sum;
      a.diagonal().array() += 1.0 / inverseMass;
      change -= a.inverse() * (0.5 * fluid.step) - 0.5 * fluid.step * inverseMass;
    }
    s.vx[f] += static_cast<float>(change.x());
    s.vy[f] += static_cast<float>(change.y());
    s.vz[f] += static_cast<float>(change.z());
    if (drift > 0) {
      s.px[f] += static_cast<float>(drift * change.x());
      s.py[f] += static_cast<float>(drift * change.y());
      s.pz[f] += static_cast<float>(drift * change.z());
    }
    fluidRow_[f] = kNoRow;
  }
  fluids_.clear();
}

// Two particles of two bodies touch; the line between their centres is the contact
// normal of two spheres, but where one of them lies under a flat face (BodySet::faces),
// the face is what touches: the normal is the face's and the depth is measured along it,
// so a box resting on a box does not rest on tilted normals where the two lattices do not
// line up (a box dropped flat with its lattice 0.1 particles off its base's slid off it:
// every normal leant the same way). An edge's or corner's particle lies under two or
// three faces. Two faces that meet nearly opposite (within 3 degrees), one of each
// particle, share their bisector (two boxes' faces, or a box's bottom edge on its base's
// top edge); otherwise the rules below pick one normal. A face holds the contact only
// where the other particle lies over that face particle's patch (within kFacePatch radii
// of the normal through it); elsewhere, past an edge, the centre line stays.
//
// Which way a face pushes: out of its body (sides 1), even for a particle already past
// the face particle's middle. A thin part's face (2) pushes towards the side the other
// particle is on, unless both where that particle was a substep ago and the other body's
// centre are on the far side: then it has just been driven past the middle (a fast ball
// onto a plate one particle thick) and goes back the way it came.
void RigidSolver::faceContact(const BodySet& set, const ParticleStore& s, std::uint32_t i, std::uint32_t a,
                              std::uint32_t j, std::uint32_t b, const Vec3& d, double r, double dt,
                              Contact& c) const {
  if (set.faces.empty()) return;
  const BodyFaces& fi = set.faces[s.id[i] - set.firstId];
  const BodyFaces& fj = set.faces[s.id[j] - set.firstId];
  if (fi.count == 0 && fj.count == 0) return;
  const Vec3 before = d - dt * Vec3(s.vx[i] - s.vx[j], s.vy[i] - s.vy[j], s.vz[i] - s.vz[j]);
  const Vec3 xi(s.px[i], s.py[i], s.pz[i]), xj(s.px[j], s.py[j], s.pz[j]);
  // Contact normals (from j's side to i's) the faces give: i's face points out of a,
  // towards j, so its normal is the opposite. `away`: from the other body's centre
  // towards the face particle's side, for a thin part.
  const auto normals = [&](const BodyFaces& f, std::uint32_t body, double sign, const Vec3& away,
                           std::array<Vec3, 3>& m) {
    for (int g = 0; g < f.count; ++g) {
      m[g] = sign * (rot_[body] * Vec3(f.normal[g][0], f.normal[g][1], f.normal[g][2]));
      if (f.sides[g] == 2) {
        if (m[g].dot(d) < 0) m[g] = -m[g];                                 // towards where i is
        if (m[g].dot(before) < 0 && m[g].dot(away) < 0) m[g] = -m[g];      // just driven past the middle
      }
    }
  };
  std::array<Vec3, 3> mi, mj;
  normals(fi, a, -1.0, xi - pos_[b], mi);
  normals(fj, b, 1.0, pos_[a] - xj, mj);
  const Vec3 centre = d / r;
  Vec3 m = Vec3::Zero();
  double radius = 0, best = -2;
  for (int p = 0; p < fi.count; ++p)
    for (int q = 0; q < fj.count; ++q) {
      if (!(mi[p].dot(mj[q]) > kFacesMeet)) continue;
      const Vec3 bisector = (mi[p] + mj[q]).normalized();
      if (bisector.dot(centre) > best) {
        best = bisector.dot(centre);
        m = bisector;
        radius = std::max(set.bodies[a].particleRadius, set.bodies[b].particleRadius);
      }
    }
  if (best == -2) {
    // No two faces meet: a face against an edge, a corner or a curve takes the face's
    // normal (a box landing on its edge is pushed straight up by the floor's face, not
    // sideways by its own tilted bottom); two faces meeting at an angle, the one nearer
    // the centre line; two edges, the normal of both edges; anything else, the centre line.
    const auto pick = [&](const BodyFaces& f, const std::array<Vec3, 3>& n, double rad) {
      for (int g = 0; g < f.count; ++g)
        if (n[g].dot(centre) > best) {
          best = n[g].dot(centre);
          m = n[g];
          radius = rad;
        }
    };
    if (fi.count == 1 && fj.count != 1) {
      pick(fi, mi, set.bodies[a].particleRadius);
    } else if (fj.count == 1 && fi.count != 1) {
      pick(fj, mj, set.bodies[b].particleRadius);
    } else if (fi.count == 1 && fj.count == 1) {
      pick(fi, mi, set.bodies[a].particleRadius);
      pick(fj, mj, set.bodies[b].particleRadius);
    } else if (fi.count == 2 && fj.count == 2) {
      const Vec3 n = mi[0].cross(mi[1]).cross(mj[0].cross(mj[1]));
      if (n.squaredNorm() < 1e-6) return;  // parallel edges: the centre line
      m = n.dot(centre) < 0 ? Vec3(-n.normalized()) : Vec3(n.normalized());
      radius = std::max(set.bodies[a].particleRadius, set.bodies[b].particleRadius);
    } else {
      return;
    }
  }
  const double along = m.dot(d);
  if (r * r - along * along > kFacePatch * kFacePatch * radius * radius) return;
  // Behind the face particle's middle, and already behind it a substep ago: the other
  // particle did not come through this face but lies beyond the part, at another face (a
  // plank two particles thick, whose bottom face pushed a box resting on its top down
  // into it and off the shelf, and spun a box thrown onto it away sideways).
  if (along < 0 && m.dot(before) <= 0) return;
  c.normal = m;
  c.depth = set.bodies[a].particleRadius + set.bodies[b].particleRadius - along;
}

void RigidSolver::collectContacts(const BodySet& set, const ParticleStore& s, std::span<const SlotPair> pairs,
                                  const Walls* walls, double dt) {
  contacts_.clear();
  const std::uint32_t first = set.firstEntity;
  // Body/body: overlapping particles of two bodies, one of them dynamic.
  for (const SlotPair& p : pairs) {
    std::uint32_t i = p[0], j = p[1];
    if (s.owner[i] < first || s.owner[j] < first) continue;  // a fluid particle: pushFluidOut
    std::uint32_t a = s.owner[i] - first, b = s.owner[j] - first;
    if (a == b) continue;
    const BodyInfo& A = set.bodies[a];
    const BodyInfo& B = set.bodies[b];
    if (!A.dynamic && !B.dynamic) continue;
    const Vec3 xi(s.px[i], s.py[i], s.pz[i]), xj(s.px[j], s.py[j], s.pz[j]);
    const Vec3 d = xi - xj;
    const double reach = A.particleRadius + B.particleRadius;
    const double r2 = d.squaredNorm();
    if (!(r2 < faceReach2(A.particleRadius, B.particleRadius)) || r2 == 0) continue;
    const double r = std::sqrt(r2);
    Contact c;
    c.normal = d / r;
    c.depth = reach - r;
    faceContact(set, s, i, a, j, b, d, r, dt, c);
    if (!(c.depth > 0)) continue;
    const Vec3 point = xj + c.normal * (B.particleRadius - 0.5 * c.depth);
    if (!A.dynamic) {  // keep the dynamic body as a
      std::swap(a, b);
      c.normal = -c.normal;
    }
    c.a = static_cast<std::int32_t>(a);
    c.b = static_cast<std::int32_t>(b);
    c.slop = settings.slop * std::min(A.particleRadius, B.particleRadius);
    c.restitution = 0.5 * (A.restitution + B.restitution);
    c.friction = 0.5 * (A.friction + B.friction);
    c.ra = point - pos_[a];
    c.rb = point - pos_[b];
    contacts_.push_back(c);
  }
  // Body/walls: each particle of a dynamic body against each plane.
  if (!walls) return;
  for (const std::uint32_t i : bodySlots_) {
    const std::uint32_t a = s.owner[i] - first;
    const BodyInfo& A = set.bodies[a];
    if (!A.dynamic) continue;
    const double rad = A.particleRadius;
    const double x[3] = {s.px[i], s.py[i], s.pz[i]};
    for (int axis = 0; axis < 3; ++axis) {
      for (int side = -1; side <= 1; side += 2) {
        if (side == 1 && axis == 1 && !walls->closed) continue;
        const double depth = side < 0 ? (walls->lo[axis] + rad) - x[axis] : x[axis] - (walls->hi[axis] - rad);
        if (!(depth > 0)) continue;
        Contact c;
        c.a = static_cast<std::int32_t>(a);
        c.b = -1;
        c.wall = 2 * axis + (side > 0 ? 1 : 0);
        c.normal = Vec3::Zero();
        c.normal[axis] = -side;  // into the container
        c.depth = depth;
        c.slop = settings.slop * rad;
        c.restitution = 0.5 * (A.restitution + walls->restitution);
        c.friction = 0.5 * (A.friction + walls->friction);
        Vec3 point(x[0], x[1], x[2]);
        point[axis] = side < 0 ? walls->lo[axis] : walls->hi[axis];
        c.ra = point - pos_[a];
        contacts_.push_back(c);
      }
    }
  }
}

namespace {

// The velocities an impulse changes, and how: a body's own mass and inertia, or, for a
// body dragging fluid along (`coupled`: RigidSolver's dragged_), its 6 x 6 mobility: the
// inverse of its mass with the dragged fluid's coupled inertia, so a contact impulse
// moves it and that fluid together, and the fluid following the body's whole-substep
// motion takes no momentum the contacts did not give.
struct BodyRefs {
  std::vector<Vec3>& vel;
  std::vector<Vec3>& omega;
  const std::vector<Mat3>& invInertia;
  const std::vector<double>& invMass;
  const std::vector<Eigen::Matrix<double, 6, 6>>* mobility = nullptr;
  const std::vector<char>* coupled = nullptr;

  [[nodiscard]] bool isCoupled(std::int32_t b) const { return coupled != nullptr && (*coupled)[b]; }
  [[nodiscard]] Vec3 relative(const Contact& c) const {
    Vec3 v = vel[c.a] + omega[c.a].cross(c.ra);
    if (c.b >= 0) v -= vel[c.b] + omega[c.b].cross(c.rb);
    return v;
  }
  /// Body b's inverse mass along d at arm r: how fast its point there moves along d per
  /// unit impulse along d.
  [[nodiscard]] double along(std::int32_t b, const Vec3& r, const Vec3& d) const {
    const Vec3 turn = r.cross(d);
    if (isCoupled(b)) {
      Eigen::Matrix<double, 6, 1> j;
      j << d, turn;
      return j.dot((*mobility)[b] * j);
    }
    return invMass[b] + turn.dot(invInertia[b] * turn);
  }
  /// The impulse p at arm r on body b.
  void push(std::int32_t b, const Vec3& r, const Vec3& p) {
    if (isCoupled(b)) {
      Eigen::Matrix<double, 6, 1> j;
      j << p, r.cross(p);
      const Eigen::Matrix<double, 6, 1> dq = (*mobility)[b] * j;
      vel[b] += dq.head<3>();
      omega[b] += dq.tail<3>();
      return;
    }
    vel[b] += p * invMass[b];
    omega[b] += invInertia[b] * r.cross(p);
  }
  void apply(const Contact& c, const Vec3& impulse) {
    push(c.a, c.ra, impulse);
    if (c.b >= 0) push(c.b, c.rb, -impulse);
  }
  /// The contact's inverse mass along d, both bodies.
  [[nodiscard]] double contact(const Contact& c, const Vec3& d) const {
    return along(c.a, c.ra, d) + (c.b >= 0 ? along(c.b, c.rb, d) : 0.0);
  }
};

const Mat3 kZero3 = Mat3::Zero();

}  // namespace

// The contacts between one pair of bodies (or a body and one wall) are many touching
// particles. Solved one by one, the order they are visited in breaks the symmetry of the
// configuration: a body at rest picks up spin and creeps, and sweeps do not converge in
// time. When the normals of a pair agree (a face, an edge or a point of contact: every
// normal within about 25 degrees of their mean), the pair keeps at most four contacts
// that span its contact area (the deepest, the farthest from it, the farthest from the
// line through those two, and the farthest on the other side of that line: a face's
// corners), all along the mean normal. Four contacts in a plane pin a resting body's
// vertical motion and tilts exactly, and the sweeps converge in a few iterations. Pairs
// whose normals disagree (a ring around a post) keep all their contacts.
void RigidSolver::reduceContacts() {
  if (contacts_.size() < 2) return;
  auto key = [](const Contact& c) { return std::tuple(c.a, c.b, c.wall); };
  std::stable_sort(contacts_.begin(), contacts_.end(),
                   [&](const Contact& x, const Contact& y) { return key(x) < key(y); });
  std::size_t out = 0;
  for (std::size_t begin = 0; begin < contacts_.size();) {
    std::size_t end = begin + 1;
    while (end < contacts_.size() && key(contacts_[end]) == key(contacts_[begin])) ++end;
    double weight = 0;
    Vec3 normal = Vec3::Zero();
    std::size_t deepest = begin;
    for (std::size_t k = begin; k < end; ++k) {
      const Contact& c = contacts_[k];
      weight += c.depth;
      normal += c.depth * c.normal;
      if (c.depth > contacts_[deepest].depth) deepest = k;
    }
    if (end - begin <= 4 || !(normal.norm() >= 0.9 * weight)) {
      for (std::size_t k = begin; k < end; ++k) contacts_[out++] = contacts_[k];
      begin = end;
      continue;
    }
    normal.normalize();
    auto argmax = [&](auto score) {
      std::size_t best = begin;
      double bestScore = -1;
      for (std::size_t k = begin; k < end; ++k) {
        const double v = score(contacts_[k].ra);
        if (v > bestScore) { bestScore = v; best = k; }
      }
      return std::pair{best, bestScore};
    };
    const Vec3 p1 = contacts_[deepest].ra;
    const auto [i2, d2] = argmax([&](const Vec3& p) { return (p - p1).squaredNorm(); });
    const Vec3 dir = contacts_[i2].ra - p1;
    const auto [i3, a3] = argmax([&](const Vec3& p) { return (p - p1).cross(dir).squaredNorm(); });
    const Vec3 side = (contacts_[i3].ra - p1).cross(dir);
    const auto [i4, a4] = argmax([&](const Vec3& p) { return -(p - p1).cross(dir).dot(side); });
    std::size_t picked[4] = {deepest, i2, i3, i4};
    int count = 1;
    if (d2 > 0) picked[count++] = i2;
    if (d2 > 0 && a3 > 0) picked[count++] = i3;
    if (d2 > 0 && a3 > 0 && a4 > 0) picked[count++] = i4;
    Contact kept[4];
    for (int k = 0; k < count; ++k) {
      kept[k] = contacts_[picked[k]];
      kept[k].normal = normal;
    }
    for (int k = 0; k < count; ++k) contacts_[out++] = kept[k];
    begin = end;
  }
  contacts_.resize(out);
}

void RigidSolver::prepareContacts(double dt, const Vec3& gravity) {
  // Below this approach speed a contact is resting: one substep of gravity (with margin)
  // must not bounce, or a body at rest would jitter.
  const double restingSpeed = 3.0 * gravity.norm() * dt + 1e-9;
  BodyRefs refs{vel_, omega_, invInertia_, invMass_, &mobility_, &dragged_};
  BodyRefs start{startVel_, startOmega_, invInertia_, invMass_};
  for (Contact& c : contacts_) {
    c.massN = 1.0 / refs.contact(c, c.normal);
    const Vec3 v = refs.relative(c);
    const double vn = v.dot(c.normal);
    const Vec3 vt = v - vn * c.normal;
    const double vtLen = vt.norm();
    if (vtLen > 1e-12) {
      c.t1 = vt / vtLen;
    } else {  // any tangent
      c.t1 = std::abs(c.normal.x()) < 0.9 ? c.normal.cross(Vec3::UnitX()).normalized()
                                          : c.normal.cross(Vec3::UnitY()).normalized();
    }
    c.t2 = c.normal.cross(c.t1);
    c.massT1 = 1.0 / refs.contact(c, c.t1);
    c.massT2 = 1.0 / refs.contact(c, c.t2);
    const bool impact = vn < -restingSpeed;
    // An impact bounces with restitution e and keeps (1 - friction) of its sliding speed
    // (the seed's attenuations); a resting contact neither bounces nor slides (Coulomb).
    // The bounce is e times the approach at the start of the substep: this substep's
    // gravity, added before the contact was found, is not part of the approach the body
    // had at the surface, and bouncing it back too gave a ball with e = 1 0.4 of its
    // energy of 49 at each bounce (+8% in 20 s).
    const double vnStart = start.relative(c).dot(c.normal);
    c.impactN = c.targetN = impact ? c.restitution * std::max(0.0, -std::max(vn, vnStart)) : 0.0;
    c.impactT1 = c.targetT1 = impact ? (1.0 - c.friction) * vtLen : 0.0;
    c.lambdaN = c.lambdaT1 = c.lambdaT2 = c.lambdaP = 0;
    c.warmN = c.warmT1 = c.warmT2 = 0;
  }
}

// Warm start. A resting contact's impulse hardly changes from one substep to the next,
// but the sweeps started from zero every substep: twenty of them did not carry the
// weight of a six-box stack down to the floor (the top box crept 0.4 in 5 s and the
// stack fell at 30 s), nor a crate of mass 50 on a plank of mass 1 (it sank through).
// So each contact starts from the impulse last substep's contact at the same place
// ended with: same bodies (or wall), the nearest point on body a in its own axes, within
// a particle radius (points, not particle ids: the reduction to four may pick another
// particle pair at the same corner). The impulse is kept as a force (impulse / dt), so a
// frame with other substeps starts from the same push. The normal part is clamped to
// push only and the friction part to the Coulomb disk, and the sweeps correct both; a
// contact with nothing there before starts from zero, as every contact did before.
void RigidSolver::recallImpulses(const BodySet& set, std::span<const ContactMemory> memory, double dt) {
  if (memory.empty()) return;
  recalled_.assign(memory.size(), 0);
  const auto key = [](const auto& c) { return std::tuple(c.a, c.b, c.wall); };
  std::size_t from = 0;  // memory is in key order, as contacts_ is
  for (Contact& c : contacts_) {
    while (from < memory.size() && key(memory[from]) < key(c)) ++from;
    const double reach = set.bodies[c.a].particleRadius;
    const Vec3 local = rot_[c.a].transpose() * c.ra;
    std::size_t best = memory.size();
    double bestDist = reach * reach;
    for (std::size_t k = from; k < memory.size() && key(memory[k]) == key(c); ++k) {
      const double d = (memory[k].pointInA - local).squaredNorm();
      if (!recalled_[k] && d < bestDist) {
        bestDist = d;
        best = k;
      }
    }
    if (best == memory.size()) continue;
    recalled_[best] = 1;
    const Vec3 impulse = memory[best].force * dt;
    c.warmN = std::max(0.0, impulse.dot(c.normal));
    c.warmT1 = impulse.dot(c.t1);
    c.warmT2 = impulse.dot(c.t2);
    const double bound = c.friction * c.warmN;
    if (const double len = std::hypot(c.warmT1, c.warmT2); len > bound) {
      const double k = len > 0 ? bound / len : 0.0;
      c.warmT1 *= k;
      c.warmT2 *= k;
    }
  }
}

void RigidSolver::rememberImpulses(std::vector<ContactMemory>& memory, double dt) const {
  memory.clear();
  for (const Contact& c : contacts_) {
    if (c.lambdaN == 0 && c.lambdaT1 == 0 && c.lambdaT2 == 0) continue;
    ContactMemory m;
    m.a = c.a;
    m.b = c.b;
    m.wall = c.wall;
    m.pointInA = rot_[c.a].transpose() * c.ra;
    m.force = (c.lambdaN * c.normal + c.lambdaT1 * c.t1 + c.lambdaT2 * c.t2) / dt;
    memory.push_back(m);
  }
}

void RigidSolver::applyWarmStart() {
  BodyRefs refs{vel_, omega_, invInertia_, invMass_, &mobility_, &dragged_};
  for (Contact& c : contacts_) {
    const double scale = islands_[island_[c.a]].scale;  // a is dynamic: it has an island
    c.lambdaN = scale * c.warmN;
    c.lambdaT1 = scale * c.warmT1;
    c.lambdaT2 = scale * c.warmT2;
    if (c.lambdaN != 0 || c.lambdaT1 != 0 || c.lambdaT2 != 0)
      refs.apply(c, c.lambdaN * c.normal + c.lambdaT1 * c.t1 + c.lambdaT2 * c.t2);
  }
}

// Sequential impulses (projected Gauss-Seidel) with accumulated, clamped impulses: the
// normal impulse of a contact never pulls, the friction impulse stays inside the
// Coulomb disk |lambda_t| <= friction * lambda_n. The impulse per contact is the seed's
// J = -(1 + e) v_rel . n / (1/m1 + 1/m2 + (I1⁻¹ (r1 x n) x r1 + I2⁻¹ (r2 x n) x r2) . n),
// reached iteratively so that many contacts between the same bodies share it.
void RigidSolver::solveVelocities() {
  BodyRefs refs{vel_, omega_, invInertia_, invMass_, &mobility_, &dragged_};
  for (int it = 0; it < settings.velocityIterations; ++it) {
    for (Contact& c : contacts_) {
      // Friction first, with the normal impulse of the previous sweep as its bound.
      const Vec3 v = refs.relative(c);
      const double old1 = c.lambdaT1, old2 = c.lambdaT2;
      double l1 = c.lambdaT1 + c.massT1 * (c.targetT1 - v.dot(c.t1));
      double l2 = c.lambdaT2 + c.massT2 * (0.0 - v.dot(c.t2));
      const double bound = c.friction * c.lambdaN;
      const double len = std::sqrt(l1 * l1 + l2 * l2);
      if (len > bound) {
        const double k = len > 0 ? bound / len : 0.0;
        l1 *= k;
        l2 *= k;
      }
      c.lambdaT1 = l1;
      c.lambdaT2 = l2;
      refs.apply(c, (l1 - old1) * c.t1 + (l2 - old2) * c.t2);

      const double vn = refs.relative(c).dot(c.normal);
      const double next = std::max(0.0, c.lambdaN + c.massN * (c.targetN - vn));
      refs.apply(c, (next - c.lambdaN) * c.normal);
      c.lambdaN = next;
    }
  }
  propagateShock();
}

// Shock propagation (after Guendelman, Bridson and Fedkiw 2003). Sweeps converge slowly
// down a chain of contacts with a large mass ratio: a crate of mass 1,000 on a plank of
// mass 1 pressed the plank into the floor faster than twenty sweeps could carry the
// floor's push up through it, and sank through in two seconds. So each body resting on
// static ground (a wall, a static body) has level 0, a body resting on a level-L body
// level L + 1 (breadth first), and after the sweeps the resting contacts are visited
// level by level from the ground up, each contact's lower body held still (infinite
// mass): the plank is stopped by the floor, then the crate by the plank. Only resting
// contacts (no impact target) between two levels take part: a push along the normal
// that stops the upper body closing in, and friction within the Coulomb disk of what
// the sweeps and this pass pushed together; where the sweeps converged it does nothing.
// Bodies with no path to the ground (a stack falling freely) have no level and are left
// to the sweeps, and so are islands without a mass ratio of kShockRatio between two
// touching bodies. Velocities only: the same pass on the overlap fix's
// pseudo-velocities held a dropped heavy box on a light plank too, but lifted a heavy
// box on two light ones with what the sweeps had pushed the middle one up by (the total
// rose 38% and the tower blew apart; a review, twenty-ninth session).
void RigidSolver::propagateShock() {
  const std::size_t nb = vel_.size();
  level_.assign(nb, -1);
  std::vector<std::uint32_t>& queue = levelQueue_;
  queue.clear();
  for (const Contact& c : contacts_)
    if ((c.b < 0 || invMass_[c.b] == 0) && level_[c.a] < 0) {
      level_[c.a] = 0;
      queue.push_back(static_cast<std::uint32_t>(c.a));
    }
  if (queue.empty()) return;
  // Only islands with a mass ratio of kShockRatio or more between two touching bodies:
  // elsewhere the sweeps converge (a stack of equal boxes), and the pass, visiting a
  // face's four contacts one by one, would only leave them a little turn to creep by.
  shocked_.assign(islands_.size(), 0);
  bool any = false;
  for (const Contact& c : contacts_)
    if (c.b >= 0 && invMass_[c.b] > 0 &&
        std::max(invMass_[c.a], invMass_[c.b]) >= kShockRatio * std::min(invMass_[c.a], invMass_[c.b])) {
      shocked_[static_cast<std::size_t>(island_[c.a])] = 1;
      any = true;
    }
  if (!any) return;
  // Breadth first through the contacts between dynamic bodies (as (body, other) pairs
  // sorted by body: linear in the contacts whatever the height of the pile).
  std::vector<std::array<std::uint32_t, 2>>& links = levelLinks_;
  links.clear();
  for (const Contact& c : contacts_)
    if (c.b >= 0 && invMass_[c.b] > 0) {
      links.push_back({static_cast<std::uint32_t>(c.a), static_cast<std::uint32_t>(c.b)});
      links.push_back({static_cast<std::uint32_t>(c.b), static_cast<std::uint32_t>(c.a)});
    }
  std::sort(links.begin(), links.end());
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t body = queue[head];
    auto it = std::lower_bound(links.begin(), links.end(), std::array<std::uint32_t, 2>{body, 0});
    for (; it != links.end() && (*it)[0] == body; ++it)
      if (level_[(*it)[1]] < 0) {
        level_[(*it)[1]] = level_[body] + 1;
        queue.push_back((*it)[1]);
      }
  }
  // Each taking part contact under its upper body's level (counting sort, stable: the
  // contacts of a level are visited in the sweeps' order). upper: 0 body a, 1 body b.
  const std::int32_t levels = level_[queue.back()] + 1;
  std::vector<std::uint32_t>& start = levelStart_;
  std::vector<std::uint32_t>& order = levelOrder_;
  start.assign(static_cast<std::size_t>(levels) + 1, 0);
  const auto upperOf = [&](const Contact& c) -> std::int32_t {  // -1: not taking part
    if (c.impactN != 0 || !shocked_[static_cast<std::size_t>(island_[c.a])]) return -1;
    const bool ground = c.b < 0 || invMass_[c.b] == 0;
    const std::int32_t la = level_[c.a], lb = ground ? -1 : level_[c.b];
    if (la >= 0 && (ground || lb == la - 1)) return 0;  // a over the ground or a lower b
    if (!ground && lb >= 0 && la == lb - 1) return 1;   // b over a
    return -1;
  };
  const auto levelOf = [&](const Contact& c, std::int32_t upper) {
    return upper == 0 ? level_[c.a] : level_[c.b];
  };
  for (const Contact& c : contacts_)
    if (const std::int32_t u = upperOf(c); u >= 0) ++start[static_cast<std::size_t>(levelOf(c, u)) + 1];
  for (std::size_t l = 1; l < start.size(); ++l) start[l] += start[l - 1];
  order.resize(start.back());
  {
    std::vector<std::uint32_t>& fill = levelFill_;
    fill.assign(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < contacts_.size(); ++k)
      if (const std::int32_t u = upperOf(contacts_[k]); u >= 0)
        order[fill[static_cast<std::size_t>(levelOf(contacts_[k], u))]++] = static_cast<std::uint32_t>(k);
  }
  for (Contact& c : contacts_) c.shockN = c.shockT1 = c.shockT2 = 0;
  BodyRefs refs{vel_, omega_, invInertia_, invMass_, &mobility_, &dragged_};  // as the sweeps
  constexpr int kSweeps = 8;
  for (std::int32_t level = 0; level < levels; ++level) {
    for (int sweep = 0; sweep < kSweeps; ++sweep) {
      for (std::uint32_t q = start[static_cast<std::size_t>(level)];
           q < start[static_cast<std::size_t>(level) + 1]; ++q) {
        Contact& c = contacts_[order[q]];
        const std::int32_t upper = upperOf(c);
        const std::int32_t body = upper == 0 ? c.a : c.b;
        const Vec3& arm = upper == 0 ? c.ra : c.rb;
        // The contact's impulse P (as on a) changes the closing velocity by K P with K
        // the upper body's own inverse mass along it, the lower body held still.
        const auto relative = [&] { return refs.relative(c); };
        const auto along = [&](const Vec3& d) { return refs.along(body, arm, d); };
        const auto apply = [&](const Vec3& p) { refs.push(body, arm, upper == 0 ? p : Vec3(-p)); };
        {  // Coulomb friction, within what the sweeps and this pass pushed together
          const Vec3 v = relative();
          const double k1 = along(c.t1), k2 = along(c.t2);
          if (k1 > 0 && k2 > 0) {
            double l1 = c.lambdaT1 + c.shockT1 - v.dot(c.t1) / k1;
            double l2 = c.lambdaT2 + c.shockT2 - v.dot(c.t2) / k2;
            const double bound = c.friction * (c.lambdaN + c.shockN);
            const double len = std::sqrt(l1 * l1 + l2 * l2);
            if (len > bound) {
              const double scale = len > 0 ? bound / len : 0.0;
              l1 *= scale;
              l2 *= scale;
            }
            l1 -= c.lambdaT1;
            l2 -= c.lambdaT2;
            apply((l1 - c.shockT1) * c.t1 + (l2 - c.shockT2) * c.t2);
            c.shockT1 = l1;
            c.shockT2 = l2;
          }
        }
        const double kn = along(c.normal);
        if (!(kn > 0)) continue;
        const double next = std::max(0.0, c.shockN - relative().dot(c.normal) / kn);
        apply((next - c.shockN) * c.normal);
        c.shockN = next;
      }
    }
  }
}

// The impact law above sets each contact's velocity after the impact on its own (the
// seed's restitution and attenuation as targets). Where a body turns, or several
// contacts share it, the tangential and normal directions are coupled, and the targets
// together can ask for more energy than the body had: a spinning cone dropped with
// restitution 1 and friction 1 left the floor with 2.4 times its energy, a tumbling slab
// with restitution 0.9 gained 60% at impact. So every group of bodies joined by contacts
// (an island: static bodies and walls join nothing) that ends above its budget (its
// energy less the overlap fix's lift, below) is solved again with its impact targets
// scaled down, the largest scale that keeps to the budget found by regula falsi (at 0
// the impact is inelastic, with Coulomb friction, which removes energy). Islands are
// independent, so the others' results are the same bits whether or not the solve runs
// again. The warm starts (recallImpulses) are scaled with the targets: a heavy body's
// stopping impulse at an impact, started from again on the next substep, was more than
// the sweeps took back at a mass ratio of 50, and a box dropped with restitution 0 on a
// light one bounced (the total rose by 413 in a frame). docs/architecture.md, "Rigid
// bodies", step 4.
void RigidSolver::solveVelocitiesWithoutGain(const Vec3& gravity) {
  const std::size_t nb = vel_.size();
  // Union-find over the dynamic bodies through the contacts (each set's root its lowest
  // body), then the islands numbered in body order.
  std::vector<std::int32_t>& parent = islandRoot_;
  parent.assign(nb, -1);
  for (std::size_t b = 0; b < nb; ++b)
    if (invMass_[b] > 0) parent[b] = static_cast<std::int32_t>(b);
  const auto root = [&](std::int32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const Contact& c : contacts_)
    if (c.b >= 0 && parent[c.b] >= 0) {
      const std::int32_t ra = root(c.a), rb = root(c.b);
      parent[std::max(ra, rb)] = std::min(ra, rb);
    }
  island_.assign(nb, -1);
  std::int32_t islands = 0;
  for (std::size_t b = 0; b < nb; ++b)
    if (parent[b] >= 0) {
      const std::int32_t r = root(static_cast<std::int32_t>(b));
      island_[b] = r == static_cast<std::int32_t>(b) ? islands++ : island_[r];  // r <= b: numbered
    }
  const auto energies = [&](std::vector<double>& out) {
    out.assign(static_cast<std::size_t>(islands), 0.0);
    for (std::size_t b = 0; b < nb; ++b)
      if (island_[b] >= 0)
        out[island_[b]] += 0.5 * (vel_[b].squaredNorm() / invMass_[b] +
                                  omega_[b].dot(invInertia_[b].ldlt().solve(omega_[b])));
  };
  energies(islandAfter_);
  islands_.assign(static_cast<std::size_t>(islands), Island{});
  for (std::size_t k = 0; k < islands_.size(); ++k)
    islands_[k].kinetic = islands_[k].budget = islandAfter_[k];
  for (const Contact& c : contacts_)
    if (c.impactN != 0 || c.impactT1 != 0 || c.warmN != 0 || c.warmT1 != 0 || c.warmT2 != 0)
      islands_[island_[c.a]].scalable = true;
  // The overlap fix lifts a body out of what it sank into at the impact, over this and
  // the next few substeps: that height is energy too, which the bounce must not also
  // give back (a box bouncing with e = 1 and no friction gained 21% in 34 s, and a ball
  // 11% in 20 s: a lift a bounce). So each body's share of its deepest impact contact's
  // overlap beyond the slop, along "up", is taken from what the impact may give back.
  if (const double g = gravity.norm(); g > 0) {
    const Vec3 up = -gravity / g;
    lift_.assign(nb, 0.0);
    for (const Contact& c : contacts_) {
      if (c.impactN == 0 || !(c.depth > c.slop)) continue;
      const double invB = c.b >= 0 ? invMass_[c.b] : 0.0;
      const double share = invMass_[c.a] / (invMass_[c.a] + invB);
      lift_[c.a] = std::max(lift_[c.a], share * (c.depth - c.slop) * std::max(0.0, c.normal.dot(up)));
      if (c.b >= 0 && invB > 0)
        lift_[c.b] =
            std::max(lift_[c.b], (1 - share) * (c.depth - c.slop) * std::max(0.0, -c.normal.dot(up)));
    }
    for (std::size_t b = 0; b < nb; ++b)
      if (island_[b] >= 0) islands_[island_[b]].budget -= g * lift_[b] / invMass_[b];
  }
  // Per island: the scale its targets were last solved with, and the bracket of the
  // scale where the energy after the impact meets the budget: lo gains nothing (g(lo) <=
  // 0), hi gains (g(hi) > 0), g the energy after minus the budget. Regula falsi with the
  // Illinois step (the end kept twice has its g halved) closes it in a few solves: the
  // energy after is nearly quadratic in the scale. An island is settled at lo once g(lo)
  // is within 1e-6 of its energy or the bracket is narrower than 1e-4 (a bisection to
  // 1/32, the first form of this check, cut a sphere's e = 1 to 31/32 for a gain of
  // rounding's size: 6% of the energy at each bounce).
  savedVel_ = vel_;
  savedOmega_ = omega_;
  applyWarmStart();
  for (int round = 0;; ++round) {
    solveVelocities();
    energies(islandAfter_);
    bool again = false;
    for (std::size_t k = 0; k < islands_.size(); ++k) {
      Island& is = islands_[k];
      if (is.search == Search::Settled) continue;
      const double g = islandAfter_[k] - is.budget;
      const bool gained = g > 1e-9 * is.kinetic;
      if (is.search == Search::First) {  // at scale 1
        if (!gained || !is.scalable) {   // no impact target or warm start to scale
          is.search = Search::Settled;
          continue;
        }
        is.hi = 1.0;
        is.gHi = g;
        is.scale = 0.0;
        is.search = Search::AtZero;
        again = true;
        continue;
      }
      if (is.search == Search::AtZero) {
        if (gained) {  // even inelastic: nothing left to scale
          is.search = Search::Settled;
          continue;
        }
        is.gLo = g;
        is.search = Search::Bracket;
      } else if (is.search == Search::Final) {
        is.search = Search::Settled;
        continue;
      } else if (gained) {  // Bracket
        is.hi = is.scale;
        is.gHi = g;
        if (is.side == 1) is.gLo *= 0.5;
        is.side = 1;
      } else {
        is.lo = is.scale;
        is.gLo = g;
        if (is.side == -1) is.gHi *= 0.5;
        is.side = -1;
      }
      if (!gained && (-is.gLo <= 1e-6 * is.kinetic || is.hi - is.lo < 1e-4) && is.scale == is.lo) {
        is.search = Search::Settled;  // this solve was at lo
        continue;
      }
      if (is.hi - is.lo < 1e-4 || round >= 12) {
        is.scale = is.lo;
        is.search = Search::Final;
      } else {
        is.scale = is.lo + std::clamp(is.gLo / (is.gLo - is.gHi), 0.001, 0.999) * (is.hi - is.lo);
      }
      again = true;
    }
    if (!again) return;
    vel_ = savedVel_;
    omega_ = savedOmega_;
    for (Contact& c : contacts_) {
      const double scale = islands_[island_[c.a]].scale;
      c.targetN = scale * c.impactN;
      c.targetT1 = scale * c.impactT1;
    }
    applyWarmStart();
  }
}

// The seed's stage 5: what overlap is left beyond the slop is removed over a few substeps
// by pseudo-velocities that move the bodies but add no momentum (split impulses), so
// fixing an overlap never launches a body.
void RigidSolver::solvePositions(double dt) {
  // With the mobility the contacts' masses (massN) were found with.
  BodyRefs refs{pseudoVel_, pseudoOmega_, invInertia_, invMass_, &mobility_, &dragged_};
  for (int it = 0; it < settings.positionIterations; ++it) {
    for (Contact& c : contacts_) {
      const double error = c.depth - c.slop;
      if (error <= 0) continue;
      const double target = settings.correction * error / dt;
      const double vn = refs.relative(c).dot(c.normal);
      const double next = std::max(0.0, c.lambdaP + c.massN * (target - vn));
      refs.apply(c, (next - c.lambdaP) * c.normal);
      c.lambdaP = next;
    }
  }
}

bool RigidSolver::pushFluidOut(const BodySet& set, std::vector<BodyState>& states, ParticleStore& s,
                               std::span<const SlotPair> pairs, std::span<const float> materialInverseMass,
                               std::span<const float> materialRadius) {
  bool pushedBody = false;
  forFluidBodyPairs(s, set.firstEntity, pairs, [&](std::uint32_t f, std::uint32_t k, std::uint32_t b) {
    const BodyInfo& B = set.bodies[b];
    const Vec3 xf(s.px[f], s.py[f], s.pz[f]), xk(s.px[k], s.py[k], s.pz[k]);
    const Vec3 d = xf - xk;
    const double reach = materialRadius[s.material[f]] + B.particleRadius;
    const double r2 = d.squaredNorm();
    if (!(r2 < reach * reach) || r2 == 0) return;
    const double r = std::sqrt(r2);
    const Vec3 n = d / r;  // from the body towards the fluid particle
    const Vec3 put = xf + n * (reach - r);
    s.px[f] = static_cast<float>(put.x());
    s.py[f] = static_cast<float>(put.y());
    s.pz[f] = static_cast<float>(put.z());
    // Inelastic: the fluid particle keeps the body's normal velocity at that point.
    const Vec3 arm = xk - states[b].position;
    const Vec3 vBody = vel_[b] + omega_[b].cross(arm);
    const Vec3 vf(s.vx[f], s.vy[f], s.vz[f]);
    const double vn = (vf - vBody).dot(n);
    if (!(vn < 0)) return;
    const double imf = materialInverseMass[s.material[f]];
    const double kb = B.dynamic ? inverseMassAlong(invMass_[b], invInertia_[b], arm, 0, kZero3, Vec3::Zero(), n) : 0.0;
    const double j = -vn / (imf + kb);
    const Vec3 vNew = vf + n * (j * imf);
    s.vx[f] = static_cast<float>(vNew.x());
    s.vy[f] = static_cast<float>(vNew.y());
    s.vz[f] = static_cast<float>(vNew.z());
    if (B.dynamic) {
      const Vec3 impulse = -j * n;
      vel_[b] += impulse * invMass_[b];
      states[b].angularMomentum += arm.cross(impulse);
      omega_[b] = invInertia_[b] * states[b].angularMomentum;
      pushedBody = true;
    }
  });
  return pushedBody;
}

void RigidSolver::step(const BodySet& set, std::vector<BodyState>& states, std::vector<ContactMemory>& memory,
                       ParticleStore& s, std::span<const SlotPair> pairs,
                       std::span<const float> materialInverseMass, const forces::InteractionTable* table,
                       const Walls* walls, const Vec3& gravity, double dt, double fluidDrift,
                       FluidKick fluidKick) {
  if (set.empty()) return;
  const std::size_t nb = set.bodies.size();
  // Body particles may have been moved by the fluid integrator: put them back on their
  // bodies before reading their forces' lever arms.
  writeParticles(set, states, s);
  gatherForces(set, states, s);
  if (table != nullptr) {
    if (!dragReady_) gatherDrag(set, states, s, pairs, *table, materialInverseMass, gravity, dt);
    dragReady_ = false;
    dragStep_.resize(nb);
  } else {
    dragged_.assign(nb, 0);
    for (const FluidDrag& fluid : fluids_) fluidRow_[fluid.slot] = kNoRow;
    fluids_.clear();
  }
  pos_.resize(nb); vel_.resize(nb); omega_.resize(nb); invInertia_.resize(nb); invMass_.resize(nb);
  mobility_.resize(nb);
  startVel_.assign(nb, Vec3::Zero());
  startOmega_.assign(nb, Vec3::Zero());
  pseudoVel_.assign(nb, Vec3::Zero());
  pseudoOmega_.assign(nb, Vec3::Zero());
  for (std::size_t b = 0; b < nb; ++b) {
    const BodyInfo& info = set.bodies[b];
    BodyState& st = states[b];
    pos_[b] = st.position;
    if (!info.dynamic) {
      vel_[b] = omega_[b] = Vec3::Zero();
      invInertia_[b] = Mat3::Zero();
      invMass_[b] = 0;
      continue;
    }
    // Free motion: forces, torques and gravity for one substep (the velocities before it
    // kept for the impact law).
    invInertia_[b] = worldInverseInertia(info, st);  // the free motion does not turn the body
    startVel_[b] = st.velocity;
    startOmega_[b] = invInertia_[b] * st.angularMomentum;
    if (dragged_[b]) {  // the fluid's drag implicitly (gatherDrag)
      Eigen::Matrix<double, 6, 6> a = dt * drag_[b];
      const Mat3 inertia = invInertia_[b].inverse();
      a.topLeftCorner<3, 3>().diagonal().array() += info.mass;
      a.bottomRightCorner<3, 3>() += inertia;
      Eigen::Matrix<double, 6, 1> q;
      q << (force_[b] + info.mass * gravity) * dt, torque_[b] * dt;
      q += dt * dragRhs_[b];
      const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> solve = a.ldlt();
      const Eigen::Matrix<double, 6, 1> dq = solve.solve(q);
      mobility_[b] = solve.solve(Eigen::Matrix<double, 6, 6>::Identity());
      st.velocity += dq.head<3>();
      st.angularMomentum += inertia * dq.tail<3>();
    } else {
      st.velocity += (force_[b] * info.inverseMass + gravity) * dt;
      st.angularMomentum += torque_[b] * dt;
    }
    invMass_[b] = info.inverseMass;
    vel_[b] = st.velocity;
    omega_[b] = invInertia_[b] * st.angularMomentum;
  }
  collectContacts(set, s, pairs, walls, dt);
  reduceContacts();
  prepareContacts(dt, gravity);
  recallImpulses(set, memory, dt);
  solveVelocitiesWithoutGain(gravity);
  rememberImpulses(memory, dt);
  solvePositions(dt);
  if (!fluids_.empty()) {
    // The fluid follows what the bodies did in the whole substep, contacts included: a
    // pallet resting on the floor under mud is stopped by the floor, and so is the mud
    // dragged along with it. (Following the free motion alone, the mud was given the
    // fall the floor took back from the pallet, every substep: it pressed into the
    // pallet and the pallet shook.)
    for (std::size_t b = 0; b < nb; ++b)
      if (dragged_[b]) dragStep_[b] << vel_[b] - startVel_[b], omega_[b] - startOmega_[b];
    dragFluid(s, materialInverseMass, dt, fluidDrift, fluidKick);
  }
  for (std::size_t b = 0; b < nb; ++b) {
    const BodyInfo& info = set.bodies[b];
    if (!info.dynamic) continue;
    BodyState& st = states[b];
    st.velocity = vel_[b];
    // L from the solved angular velocity, with the tensor of this substep's orientation.
    st.angularMomentum = invInertia_[b].isZero() ? Vec3::Zero().eval() : Vec3(invInertia_[b].inverse() * omega_[b]);
    // The turn: torque-free rotation from L (turnFree), then the split impulses' turn,
    // which moves the body without being motion: L turns with it, so the body keeps its
    // angular velocity in its own axes and its energy.
    turnFree(info, st, dt);
    if (const double angle = pseudoOmega_[b].norm() * dt; angle > 0) {
      const Quat turn(Eigen::AngleAxisd(angle, pseudoOmega_[b].normalized()));
      st.angularMomentum = turn * st.angularMomentum;
    }
    integratePose(info, st, vel_[b] + pseudoVel_[b], pseudoOmega_[b], dt);
  }
  // New poses: body particles to their places. The fluid is kept outside the bodies
  // after the container's walls have acted (keepFluidOut).
  writeParticles(set, states, s);
}

void RigidSolver::keepFluidOut(const BodySet& set, std::vector<BodyState>& states, ParticleStore& s,
                               std::span<const SlotPair> pairs, std::span<const float> materialInverseMass,
                               std::span<const float> materialRadius) {
  if (set.empty()) return;
  const std::size_t nb = set.bodies.size();
  // The bodies' velocities and world inertia at their new poses (omega_ was set from them
  // when step() put their particles in place).
  for (std::size_t b = 0; b < nb; ++b) {
    if (!set.bodies[b].dynamic) continue;
    vel_[b] = states[b].velocity;
    invInertia_[b] = worldInverseInertia(set.bodies[b], states[b]);
  }
  if (!pushFluidOut(set, states, s, pairs, materialInverseMass, materialRadius)) return;
  // Some body took an impulse from the fluid: its particles' velocities follow.
  for (std::size_t b = 0; b < nb; ++b)
    if (set.bodies[b].dynamic) states[b].velocity = vel_[b];
  writeParticles(set, states, s);
}

}  // namespace softsub::rigid
