#pragma once
/// `softsub bench lammps`: the same Lennard-Jones liquid run by softsub and by LAMMPS
/// (issue #6): atom-steps per second for each, their ratio, and the two codes' total
/// energy after the run.
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace softsub::app {

/// The options of `bench lammps`.
struct BenchOptions {
  std::vector<long> particles{32000, 256000};  ///< rounded to 4 n^3 (an fcc lattice)
  std::vector<double> cutoffs{2.5, 2.0};       ///< in sigma
  int steps = 100;                             ///< velocity-Verlet steps of 0.005 tau
  int repeat = 3;                              ///< runs of each code per row, alternating; the best of each is printed
  std::string lammps;                          ///< LAMMPS binary; empty: lmp on PATH
  std::string keep;                            ///< folder to keep the inputs in; empty: none kept
  int threads = 0;                             ///< the root's --threads: the second row's count; 0: all cores
};

/// Adds `bench` (with its `lammps` subcommand) and returns `bench`.
CLI::App* addBenchCommand(CLI::App& root, BenchOptions& options);

/// Runs it; returns the exit code.
int benchLammpsCommand(const BenchOptions& options);

}  // namespace softsub::app
