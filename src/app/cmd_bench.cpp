#include "cmd_bench.h"
#include "number_checks.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <thread>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <tbb/global_control.h>

#include "cmd_render.h"
#include "core/error.h"
#include "scene/compile.h"
#include "scene/writer.h"
#include "solver/energy.h"
#include "solver/simulation.h"

extern char** environ;

namespace softsub::app {

namespace {

namespace fs = std::filesystem;

constexpr double kDensity = 0.8442;  // LAMMPS's bench/in.lj
constexpr double kTimeStep = 0.005;  // tau
constexpr double kRadius = 0.5;      // our particle radius (ParticleSize 1 = sigma)

/// The liquid both codes start from: an fcc lattice of 4 n^3 atoms at the density, each
/// moved by a fixed-seed jitter of up to +-0.02 sigma, at rest, in a box of edge L.
struct Liquid {
  int cells = 0;
  double edge = 0;  // L
  std::vector<Vec3> atoms;
};

Liquid makeLiquid(long wanted) {
  Liquid out;
  out.cells = std::max(1, static_cast<int>(std::lround(std::cbrt(static_cast<double>(wanted) / 4.0))));
  const double a = std::cbrt(4.0 / kDensity);
  out.edge = out.cells * a;
  const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  std::uint64_t state = 0x5DEECE66Dull;
  const auto jitter = [&state] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5) * 0.04;
  };
  for (int i = 0; i < out.cells; ++i)
    for (int j = 0; j < out.cells; ++j)
      for (int k = 0; k < out.cells; ++k)
        for (const auto& b : basis) {
          // x and z centred on 0, y from 0 (softsub's container); a quarter cell in from
          // every wall.
          const double x = (i + b[0] + 0.25) * a - 0.5 * out.edge + jitter();
          const double y = (j + b[1] + 0.25) * a + kRadius + jitter();
          const double z = (k + b[2] + 0.25) * a - 0.5 * out.edge + jitter();
          out.atoms.emplace_back(x, y, z);
        }
  return out;
}

/// softsub's scene: one fluid of the atoms, the true LJ force as its own pair, no
/// viscosity or gravity, velocity Verlet at 0.005, a closed elastic frictionless box
/// whose walls keep centres in [-L/2, L/2] x [r, L + r] x [-L/2, L/2].
scene::SceneDesc sceneOf(const Liquid& liquid, double cutoff, int steps) {
  scene::SceneDesc d;
  d.simulation.frames = 1;
  d.simulation.substeps = steps;
  d.simulation.framesPerSecond = 1.0 / (kTimeStep * steps);
  d.simulation.gravity = Vec3::Zero();
  d.simulation.integrator = scene::Integrator::VelocityVerlet;
  scene::EnvironmentDesc box;
  box.width = box.depth = box.height = liquid.edge + 2 * kRadius;
  box.normalAttenuation = 1;
  box.tangentAttenuation = 0;
  box.closed = true;
  d.environment = box;
  scene::FluidDesc f;
  f.name = "argon";
  f.params.particleSize = 2 * kRadius;
  f.params.particleMass = 1;
  f.params.viscosity = 0;
  f.particles = liquid.atoms;
  d.fluids.push_back(f);
  d.interactions.pairs.push_back({"argon", "argon", {forces::LennardJonesForce{1, 1, cutoff}, 0, 0}, 0});
  d.camera.eye = Vec3(0, 0.5 * liquid.edge, 2.5 * liquid.edge);
  return d;
}

void writeLammpsData(const Liquid& liquid, const fs::path& file) {
  std::ofstream out(file);
  out << fmt::format("softsub bench lammps: fcc LJ liquid, density {}, jittered, at rest\n\n", kDensity);
  out << liquid.atoms.size() << " atoms\n1 atom types\n\n";
  out << fmt::format("{:.10g} {:.10g} xlo xhi\n", -0.5 * liquid.edge, 0.5 * liquid.edge);
  out << fmt::format("{:.10g} {:.10g} ylo yhi\n", kRadius, kRadius + liquid.edge);
  out << fmt::format("{:.10g} {:.10g} zlo zhi\n\n", -0.5 * liquid.edge, 0.5 * liquid.edge);
  out << "Masses\n\n1 1.0\n\nAtoms # atomic\n\n";
  for (std::size_t i = 0; i < liquid.atoms.size(); ++i) {
    // The positions softsub reads are floats: give LAMMPS the same numbers.
    const Vec3& p = liquid.atoms[i];
    out << fmt::format("{} 1 {:.9g} {:.9g} {:.9g}\n", i + 1, static_cast<float>(p.x()), static_cast<float>(p.y()),
                       static_cast<float>(p.z()));
  }
  if (!out) throw IoError("cannot write " + file.string());
}

void writeLammpsInput(const fs::path& data, double cutoff, int steps, const fs::path& file) {
  std::ofstream out(file);
  out << "units lj\natom_style atomic\nboundary f f f\n";
  out << fmt::format("read_data {}\n", data.string());
  out << fmt::format("pair_style lj/cut {}\npair_coeff 1 1 1.0 1.0 {}\npair_modify shift yes\n", cutoff, cutoff);
  out << "neighbor 0.3 bin\nneigh_modify every 1 delay 0 check yes\n";
  out << "fix 1 all nve\nfix 2 all wall/reflect xlo EDGE xhi EDGE ylo EDGE yhi EDGE zlo EDGE zhi EDGE\n";
  out << fmt::format("timestep {}\nthermo_style custom step ke pe etotal\nthermo_modify norm no\nthermo {}\n",
                     kTimeStep, steps);
  out << fmt::format("run {}\n", steps);
  if (!out) throw IoError("cannot write " + file.string());
}

/// Runs argv with stdout and stderr into `log`; returns the exit status (-1: not started).
int runLogged(const std::vector<std::string>& args, const fs::path& log, const fs::path& cwd) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  const std::string where = cwd.string();
  posix_spawn_file_actions_addchdir_np(&actions, where.c_str());
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int started = posix_spawn(&pid, args[0].c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (started != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

struct Result {
  double atomStepsPerSecond = 0;
  double energy = 0;  // total after the run
};

std::optional<Result> runLammps(const std::string& lmp, int ranks, const fs::path& input, const fs::path& dir,
                                long atoms, int steps, int run, std::string& why) {
  std::vector<std::string> args;
  if (ranks > 1) {
    const std::string mpirun = findOnPath("mpirun");
    if (mpirun.empty()) {
      why = "mpirun not found";
      return std::nullopt;
    }
    args = {mpirun, "--allow-run-as-root", "--oversubscribe", "-np", std::to_string(ranks)};
  }
  for (const std::string& a : {lmp, std::string("-in"), input.string(), std::string("-log"), std::string("none")})
    args.push_back(a);
  const fs::path log = dir / fmt::format("{}.{}ranks.run{}.log", input.stem().string(), ranks, run);
  const int status = runLogged(args, log, dir);
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  const std::string out = text.str();
  if (status != 0) {
    why = fmt::format("LAMMPS exited with status {} (log: {})", status, log.string());
    return std::nullopt;
  }
  // "Loop time of <seconds> on <P> procs for <steps> steps with <N> atoms".
  const std::string marker = "Loop time of ";
  const std::size_t at = out.find(marker);
  char* end = nullptr;
  const double seconds = at == std::string::npos ? 0.0 : std::strtod(out.c_str() + at + marker.size(), &end);
  if (!(seconds > 0.0)) {
    why = "no 'Loop time' in LAMMPS's output (" + log.string() + ")";
    return std::nullopt;
  }
  Result r;
  r.atomStepsPerSecond = static_cast<double>(atoms) * steps / seconds;
  // The thermo line of the last step: "<steps> ke pe etotal" (the last such line).
  bool found = false;
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream fields(line);
    std::string step;
    double ke = 0, pe = 0, total = 0;
    if (fields >> step >> ke >> pe >> total && step == std::to_string(steps)) {
      r.energy = total;
      found = true;
    }
  }
  if (!found) {
    why = "no thermo line for step " + std::to_string(steps) + " in " + log.string();
    return std::nullopt;
  }
  return r;
}

Result runSoftsub(const scene::SceneDesc& desc, std::size_t threads, double& bytesPerParticle) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  scene::Compiled compiled = scene::compile(desc);
  const double atoms = static_cast<double>(compiled.model.particleCount());
  solver::Simulation sim(compiled.model, std::move(compiled.state));
  sim.prepare();  // the first forces, outside the time as LAMMPS's setup is outside its Loop time
  const auto t0 = std::chrono::steady_clock::now();
  sim.advanceFrame();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  bytesPerParticle = static_cast<double>(sim.memoryBytes()) / atoms;
  Result r;
  r.atomStepsPerSecond = atoms * desc.simulation.substeps / seconds;
  r.energy = solver::measureEnergy(sim.model(), sim.state()).total();
  return r;
}

}  // namespace

CLI::App* addBenchCommand(CLI::App& root, BenchOptions& o) {
  CLI::App* bench = root.add_subcommand("bench", "Benchmarks against other codes");
  bench->require_subcommand(1);
  CLI::App* lammps = bench->add_subcommand(
      "lammps", "The same Lennard-Jones liquid (fcc, density 0.8442, at rest, reflective box, velocity Verlet) "
                "run by softsub and by LAMMPS: atom-steps per second, ratio, total energy after the run");
  lammps->add_option("--particles", o.particles, "Atom counts (rounded to 4 n^3)")->delimiter(',')->capture_default_str();
  lammps->add_option("--cutoff", o.cutoffs, "Cutoffs in sigma")->delimiter(',')->capture_default_str();
  lammps->add_option("--steps", o.steps, "Steps of 0.005 tau")->transform(wholeNumberIn(1, 100000))->capture_default_str();
  lammps->add_option("--repeat", o.repeat,
                     "Runs of each code per row, alternating ours and LAMMPS's; the best of each is printed, so "
                     "a busy moment on a shared machine costs neither side")
      ->transform(wholeNumberIn(1, 100))
      ->capture_default_str();
  lammps->add_option("--lammps", o.lammps, "LAMMPS binary (default: lmp on PATH)")->check(nonEmptyPath());
  lammps->add_option("--keep", o.keep, "Keep the scenes, data files, inputs and logs in this folder")
      ->check(nonEmptyPath());
  return bench;
}

int benchLammpsCommand(const BenchOptions& o) {
  for (const long n : o.particles)
    if (n < 4 || n > 20000000)
      throw InputError({"command line", 0, "--particles"}, fmt::format("{} atoms is out of range", n),
                       "4 to 20,000,000");
  for (const double c : o.cutoffs)
    if (!(c > 1.0 && c <= 5.0))
      throw InputError({"command line", 0, "--cutoff"}, fmt::format("{} is out of range", c), "(1, 5] sigma");
  const std::string lmp = findOnPath(o.lammps.empty() ? "lmp" : o.lammps);
  if (lmp.empty())
    fmt::print(stderr, "note: LAMMPS not found ({}): softsub's side only (Debian: apt-get install lammps)\n",
               o.lammps.empty() ? "lmp on PATH" : o.lammps);
  const fs::path dir = o.keep.empty() ? fs::temp_directory_path() / fmt::format("softsub-bench-{}", ::getpid())
                                      : fs::absolute(fs::path(o.keep));  // LAMMPS runs in it: no path relative to here
  fs::create_directories(dir);
  // One thread, then --threads (all cores by default). The root's --threads also caps
  // the whole process (main.cpp), so a second row above it would run on fewer threads
  // than it says.
  const unsigned most =
      o.threads > 0 ? static_cast<unsigned>(o.threads) : std::max(1u, std::thread::hardware_concurrency());
  std::vector<unsigned> threadCounts{1};
  if (most > 1) threadCounts.push_back(most);

  fmt::print("# softsub vs LAMMPS: LJ liquid, fcc at density {}, jitter 0.02 sigma, at rest, {} steps of {} tau, "
             "velocity Verlet, reflective walls; best of {} run{} each\n", kDensity, o.steps, kTimeStep, o.repeat,
             o.repeat == 1 ? "" : "s");
  fmt::print("# {:>8} {:>6} {:>7} {:>16} {:>16} {:>6} {:>14} {:>14} {:>9} {:>10}\n", "atoms", "cutoff", "threads",
             "softsub atom-s/s", "LAMMPS atom-s/s", "ratio", "E softsub", "E LAMMPS", "rel. diff", "bytes/atom");
  for (const long wanted : o.particles) {
    const Liquid liquid = makeLiquid(wanted);
    const long atoms = static_cast<long>(liquid.atoms.size());
    const fs::path data = dir / fmt::format("lj-{}.data", atoms);
    if (!lmp.empty()) writeLammpsData(liquid, data);
    for (const double cutoff : o.cutoffs) {
      const scene::SceneDesc desc = sceneOf(liquid, cutoff, o.steps);
      const std::string stem = fmt::format("lj-{}-rc{}", atoms, cutoff);
      if (!o.keep.empty()) scene::writeSceneFile(desc, (dir / (stem + ".scene")).string());
      const fs::path input = dir / (stem + ".in");
      if (!lmp.empty()) writeLammpsInput(data.filename(), cutoff, o.steps, input);
      for (const unsigned threads : threadCounts) {
        // The best of --repeat runs of each, alternating, so that a busy moment on a
        // shared machine lands on both codes alike and the best run of each is compared.
        // A LAMMPS run that fails ends the row's runs: the row shows the best of the runs
        // made (LAMMPS's as "-" when none succeeded), and a note says which run failed.
        double bytes = 0;
        Result ours;
        std::optional<Result> theirs;
        std::string why;
        for (int run = 1; run <= o.repeat; ++run) {
          const Result mine = runSoftsub(desc, threads, bytes);
          if (mine.atomStepsPerSecond > ours.atomStepsPerSecond) ours = mine;
          if (lmp.empty()) continue;
          const std::optional<Result> other =
              runLammps(lmp, static_cast<int>(threads), input, dir, atoms, o.steps, run, why);
          if (!other) {
            why = fmt::format("{} (LAMMPS's run {} of {}{})", why, run, o.repeat,
                              theirs ? "; the row shows its best before it" : "");
            break;
          }
          if (!theirs || other->atomStepsPerSecond > theirs->atomStepsPerSecond) theirs = other;
        }
        if (!why.empty()) fmt::print(stderr, "note: {}\n", why);
        if (theirs)
          fmt::print("  {:>8} {:>6} {:>7} {:>16.4g} {:>16.4g} {:>6.2f} {:>14.8g} {:>14.8g} {:>9.2e} {:>10.0f}\n", atoms,
                     cutoff, threads, ours.atomStepsPerSecond, theirs->atomStepsPerSecond,
                     ours.atomStepsPerSecond / theirs->atomStepsPerSecond, ours.energy, theirs->energy,
                     std::abs(ours.energy - theirs->energy) / std::max(std::abs(theirs->energy), 1e-300), bytes);
        else
          fmt::print("  {:>8} {:>6} {:>7} {:>16.4g} {:>16} {:>6} {:>14.8g} {:>14} {:>9} {:>10.0f}\n", atoms, cutoff,
                     threads, ours.atomStepsPerSecond, "-", "-", ours.energy, "-", "-", bytes);
        std::fflush(stdout);
      }
    }
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  fmt::print("# peak resident memory of softsub's process: {:.0f} MiB\n", static_cast<double>(usage.ru_maxrss) / 1024.0);
  if (o.keep.empty()) {
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }
  return 0;
}

}  // namespace softsub::app
