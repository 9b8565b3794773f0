#pragma once
#include <CLI/CLI.hpp>

namespace ballast {
// `ballast clump`: generate a sample of clumps (Lu & McDowell 2007 section 2) from a
// preset or a JSON file, print their statistics (table or --json), and optionally
// write them to HDF5 (-o) and VTK (--vtk). See docs/CLUMPS.md.
void register_clump_command(CLI::App& app);
}  // namespace ballast
