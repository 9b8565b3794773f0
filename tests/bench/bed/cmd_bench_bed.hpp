#pragma once
#include <CLI/CLI.hpp>

namespace ballast {
// `ballast bench-bed BED.txt --steps N`: the side-by-side benchmark's run of our
// engine (cases/bench_bed.hpp): ball-steps per second of the stepping alone, and
// the physics after N steps that LAMMPS and YADE must reproduce.
void register_bench_bed_command(CLI::App& app);
}  // namespace ballast
