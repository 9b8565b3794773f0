// ParaView files of a box-test run (legacy VTK, ASCII): the contact-force network at
// each stage (Figs 10-12) as lines between the centres of touching balls with |F| as
// cell data, and the particles (body centres) with their displacement and rotation
// fields (Figs 13-17).
//   DIR/contacts_before.vtk, contacts_peak.vtk, contacts_after.vtk
//   DIR/particles.vtk   point data: displacement_peak, displacement_end (m),
//                       rotation_loading, rotation_unloading, rotation_cycle (deg)
#pragma once

#include <string>

#include "cases/box_test_result.hpp"

namespace ballast {

// Writes the files into `dir` (created if missing); throws naming a file that
// cannot be written.
void write_run_vtk(const std::string& dir, const BoxTestResult& r);

}  // namespace ballast
