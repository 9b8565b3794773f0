// One box-test run in HDF5 (`ballast run -o RUN.h5`; the study archive holds one
// such group per run, docs/ARCHIVE.md). Layout under the run's group, SI units, each
// dataset with a "units" attribute:
//
//   attributes     scene, shape, bodies, balls, dt, dt_critical, wall_seconds, loaded,
//                  porosity_grid, bed_height, settlement_peak, permanent_settlement,
//                  resilient_settlement, max_force_error, rms_force_error,
//                  max_displacement_peak, max_displacement_after,
//                  rotation_{loading,unloading,cycle}_{mean,max}_deg, energy_* (J)
//   stages/NN_name attributes steps, simulated, seconds, unbalanced, settled
//   contacts/{before,peak,after}   attributes ball_contacts, wall_contacts,
//                  coordination, max_force, mean_force; datasets from [C,3], to [C,3],
//                  force [C] (ball–ball contacts: centres of the two balls, |F|)
//   series/{time,target_force,sleeper_force,settlement}   load–deformation (Fig 18)
//   particles/{position_start,position_peak,position_end} [N,3],
//             displacement_{peak,end} [N,3] (from position_start; peak empty when
//             the run stopped before loading),
//             rotation_{loading,unloading,cycle} [N] (deg), shape_index [N]
//   porosity/{sphere_heights,sphere_porosity}
//   clumps/        clump samples only: the templates, as `ballast clump -o` writes
//                  them (study/archive/clump_archive.hpp); body i is template shape_index[i]
#pragma once

#include <hdf5.h>

#include <string>

#include "cases/box_test_result.hpp"

namespace ballast {

// Writes the result into `group` (already created).
void write_box_test_result(hid_t group, const BoxTestResult& r);

// A file holding one run: the scene file's text as attribute "scene_json" on the
// root, the result under /run.
void write_run_file(const std::string& path, const std::string& scene_json, const BoxTestResult& r);

}  // namespace ballast
