// ParaView output of a clump sample (`ballast clump --vtk DIR`): DIR/clumps.vtk, a
// legacy-format VTK polydata file with one vertex per ball, point data "radius" (m)
// and "clump" (index). Clumps are laid out on a square grid in the x-y plane, each in
// its principal frame, 2.5 virtual-sphere radii apart. In ParaView: Glyph filter,
// sphere glyph, scale by "radius" with scale factor 2 (the glyph's unit is a diameter).
#pragma once

#include <string>
#include <vector>

#include "engine/clump_template.hpp"

namespace ballast {

// Creates DIR if needed and writes DIR/clumps.vtk; returns the file's path.
// Throws std::runtime_error naming the path on failure.
std::string write_clump_vtk(const std::string& dir, const std::vector<ClumpTemplate>& clumps,
                            double virtual_radius, const std::string& title);

}  // namespace ballast
