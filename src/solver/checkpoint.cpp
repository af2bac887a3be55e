#include "solver/checkpoint.h"

#include <cstring>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "core/hash.h"

namespace softsub::solver {

namespace {

constexpr char kMagic[8] = {'S', 'O', 'F', 'T', 'C', 'K', 'P', 'T'};
constexpr std::uint32_t kVersion = 2;        // 2: the bodies' contact memory after the bodies
constexpr std::uint32_t kOldestVersion = 1;  // 1: no contact memory (read as none)
constexpr std::uint32_t kForcesValid = 1;
constexpr std::uint32_t kHasReference = 2;
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8 + 8 + 8 + 8;
constexpr std::size_t kBodyDoubles = 13;  // position 3, orientation w x y z, velocity 3, angular momentum 3
constexpr std::size_t kContactBytes = 3 * 4 + 6 * 8;  // a, b, wall; point in a xyz, force xyz

template <class T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <class T>
void putArray(std::string& out, std::span<const T> a) {
  out.append(reinterpret_cast<const char*>(a.data()), a.size_bytes());
}

/// Reads values from the bytes in order; every read is bounds-checked.
class Reader {
 public:
  Reader(std::string_view bytes, const std::string& file) : bytes_(bytes), file_(file) {}

  template <class T>
  T get() {
    T v;
    need(sizeof v);
    std::memcpy(&v, bytes_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  template <class T>
  void getArray(std::vector<T>& a, std::uint64_t n) {
    if (n > (bytes_.size() - at_) / sizeof(T)) fail("is truncated");
    a.resize(n);
    std::memcpy(a.data(), bytes_.data() + at_, n * sizeof(T));
    at_ += n * sizeof(T);
  }
  [[nodiscard]] std::size_t offset() const { return at_; }
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError({file_, 0, "checkpoint"}, problem, "a checkpoint written by this version of softsub");
  }

 private:
  void need(std::size_t n) const {
    if (n > bytes_.size() - at_) fail("is truncated");
  }
  std::string_view bytes_;
  const std::string& file_;
  std::size_t at_ = 0;
};

struct Header {
  std::uint32_t version = 0;
  std::uint32_t flags = 0;
  std::uint64_t contacts = 0;
  CheckpointInfo info;
};

Header readHeader(Reader& r, std::string_view bytes) {
  char magic[8];
  for (char& c : magic) c = r.get<char>();
  if (std::memcmp(magic, kMagic, sizeof magic) != 0) r.fail("is not a softsub checkpoint");
  const auto version = r.get<std::uint32_t>();
  if (version < kOldestVersion || version > kVersion) r.fail(fmt::format("has version {}", version));
  Header h;
  h.version = version;
  h.flags = r.get<std::uint32_t>();
  h.info.frame = r.get<std::int64_t>();
  h.info.fingerprint = r.get<std::uint64_t>();
  h.info.particles = r.get<std::uint64_t>();
  h.info.bodies = r.get<std::uint64_t>();
  if (bytes.size() < kHeaderBytes + 8) r.fail("is truncated");
  // The checksum covers everything before it: a damaged or cut file is refused here.
  std::uint64_t stored;
  std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
  if (hashBytes(bytes.substr(0, bytes.size() - 8)) != stored) r.fail("is damaged (checksum mismatch)");
  const std::uint64_t perParticle = 9 * 4 + 2 + 4 + 4 + ((h.flags & kHasReference) ? 12 : 0);
  const std::uint64_t payload = bytes.size() - kHeaderBytes - 8;
  const auto wrongSize = [&] { r.fail("has the wrong size for its particle and object counts"); };
  if (h.info.particles > payload / perParticle || h.info.bodies > payload / (kBodyDoubles * 8)) wrongSize();
  std::uint64_t fixed = h.info.particles * perParticle + h.info.bodies * kBodyDoubles * 8;
  if (h.version >= 2) {  // the contact count follows the bodies
    if (fixed > payload || payload - fixed < 8) wrongSize();
    std::memcpy(&h.contacts, bytes.data() + kHeaderBytes + fixed, 8);
    fixed += 8;
    if (h.contacts > (payload - fixed) / kContactBytes) wrongSize();
    fixed += h.contacts * kContactBytes;
  }
  if (fixed != payload) wrongSize();
  if (h.info.frame < 0) r.fail("has a negative frame");
  return h;
}

}  // namespace

void encodeCheckpoint(const Simulation& sim, std::uint64_t fingerprint, std::string& out) {
  const State& st = sim.state();
  const ParticleStore& s = st.particles;
  const Simulation::ListReference ref = sim.listReference();
  const bool hasRef = !ref.x.empty();
  const std::size_t n = s.size();
  out.clear();
  out.reserve(kHeaderBytes + n * (9 * 4 + 10 + (hasRef ? 12 : 0)) + st.bodies.size() * kBodyDoubles * 8 + 8 +
              st.contacts.size() * kContactBytes + 8);
  out.append(kMagic, sizeof kMagic);
  put(out, kVersion);
  put(out, static_cast<std::uint32_t>((st.forcesValid ? kForcesValid : 0) | (hasRef ? kHasReference : 0)));
  put(out, static_cast<std::int64_t>(st.frame));
  put(out, fingerprint);
  put(out, static_cast<std::uint64_t>(n));
  put(out, static_cast<std::uint64_t>(st.bodies.size()));
  for (const std::vector<float>* a : {&s.px, &s.py, &s.pz, &s.vx, &s.vy, &s.vz})
    putArray(out, std::span<const float>(*a));
  {  // the forces as three arrays, as before they were records in the store
    std::vector<float> component(n);
    for (float Force::*c : {&Force::x, &Force::y, &Force::z}) {
      for (std::size_t i = 0; i < n; ++i) component[i] = s.f[i].*c;
      putArray(out, std::span<const float>(component));
    }
  }
  putArray(out, std::span<const std::uint16_t>(s.material));
  putArray(out, std::span<const std::uint32_t>(s.owner));
  putArray(out, std::span<const std::uint32_t>(s.id));
  if (hasRef)
    for (const std::span<const float> a : {ref.x, ref.y, ref.z}) putArray(out, a);
  for (const rigid::BodyState& b : st.bodies) {
    const double v[kBodyDoubles] = {b.position.x(),        b.position.y(),        b.position.z(),
                                    b.orientation.w(),     b.orientation.x(),     b.orientation.y(),
                                    b.orientation.z(),     b.velocity.x(),        b.velocity.y(),
                                    b.velocity.z(),        b.angularMomentum.x(), b.angularMomentum.y(),
                                    b.angularMomentum.z()};
    putArray(out, std::span<const double>(v));
  }
  put(out, static_cast<std::uint64_t>(st.contacts.size()));
  for (const rigid::ContactMemory& c : st.contacts) {
    put(out, c.a);
    put(out, c.b);
    put(out, c.wall);
    const double v[6] = {c.pointInA.x(), c.pointInA.y(), c.pointInA.z(),
                         c.force.x(),    c.force.y(),    c.force.z()};
    putArray(out, std::span<const double>(v));
  }
  put(out, hashBytes(out));
}

CheckpointInfo checkpointInfo(std::string_view bytes, const std::string& file) {
  Reader r(bytes, file);
  return readHeader(r, bytes).info;
}

void restoreCheckpoint(Simulation& sim, std::string_view bytes, std::uint64_t fingerprint, const std::string& file) {
  Reader r(bytes, file);
  const Header h = readHeader(r, bytes);
  if (h.info.fingerprint != fingerprint)
    r.fail("belongs to a run with other settings (the scene or the options changed)");
  const std::uint64_t n = h.info.particles;
  State st;
  ParticleStore& s = st.particles;
  for (std::vector<float>* a : {&s.px, &s.py, &s.pz, &s.vx, &s.vy, &s.vz}) r.getArray(*a, n);
  {  // three arrays (checked against the bytes left before anything is sized by n)
    std::vector<float> fx, fy, fz;
    r.getArray(fx, n);
    r.getArray(fy, n);
    r.getArray(fz, n);
    s.f.resize(n);
    for (std::size_t i = 0; i < n; ++i) s.f[i] = {fx[i], fy[i], fz[i], 0.0f};
  }
  r.getArray(s.material, n);
  r.getArray(s.owner, n);
  r.getArray(s.id, n);
  // Ids are a permutation of 0..n-1: slotsById and the outputs rely on it.
  std::vector<char> seen(n, 0);
  for (const std::uint32_t id : s.id) {
    if (id >= n || seen[id]) r.fail("has duplicate or out-of-range particle ids");
    seen[id] = 1;
  }
  std::vector<float> refX, refY, refZ;
  if (h.flags & kHasReference) {
    r.getArray(refX, n);
    r.getArray(refY, n);
    r.getArray(refZ, n);
  }
  st.bodies.resize(h.info.bodies);
  for (rigid::BodyState& b : st.bodies) {
    double v[kBodyDoubles];
    for (double& x : v) x = r.get<double>();
    b.position = {v[0], v[1], v[2]};
    b.orientation = Quat(v[3], v[4], v[5], v[6]);
    b.velocity = {v[7], v[8], v[9]};
    b.angularMomentum = {v[10], v[11], v[12]};
  }
  if (h.version >= 2) {
    if (r.get<std::uint64_t>() != h.contacts) r.fail("is damaged (contact count)");
    st.contacts.resize(h.contacts);
    for (rigid::ContactMemory& c : st.contacts) {
      c.a = r.get<std::int32_t>();
      c.b = r.get<std::int32_t>();
      c.wall = r.get<std::int32_t>();
      double v[6];
      for (double& x : v) x = r.get<double>();
      c.pointInA = {v[0], v[1], v[2]};
      c.force = {v[3], v[4], v[5]};
    }
  }
  st.frame = h.info.frame;
  st.forcesValid = (h.flags & kForcesValid) != 0;
  try {
    sim.restore(std::move(st), std::move(refX), std::move(refY), std::move(refZ));
  } catch (const std::invalid_argument& e) {
    r.fail(e.what());
  }
}

}  // namespace softsub::solver
