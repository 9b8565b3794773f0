// HDF5 archive of a generated clump sample (`ballast clump -o FILE.h5`), read by
// scripts/clump_gallery.py. Layout (all lengths in metres, SI throughout; every
// dataset carries a "units" attribute):
//
//   /                      attributes: format = "ballast-clumps", version = 1, preset,
//                          source, seed, count, mass_mode, density, accuracy, every
//                          ClumpParams field, central_radius, virtual_radius,
//                          expected_balls_per_clump
//   /balls/radius          [N]        radius
//   /balls/offset          [N, 3]     centre in its clump's principal frame
//   /balls/clump           [N]        index of the clump owning the ball
//   /clumps/first_ball     [M]        balls of clump i: first_ball[i] .. + ball_count[i]
//   /clumps/ball_count     [M]
//   /clumps/mass           [M]        kg
//   /clumps/principal_inertia [M, 3]  kg·m², ascending
//   /clumps/volume         [M]        volume the mass stands for (see MassMode)
//   /clumps/integration_error [M]     uniform mode's relative error estimate
//   /clumps/generation_centre [M, 3], /clumps/generation_rotation [M, 3, 3]
//   /shape/union_volume, surface_area, sphericity, elongation, flatness,
//          volume_ratio [M];  /shape/dimensions [M, 3] (a >= b >= c)
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

#include "engine/clump_generator.hpp"
#include "engine/clump_mass.hpp"
#include "engine/clump_shape.hpp"
#include "engine/clump_template.hpp"

namespace ballast {

struct ClumpArchiveHeader {
  std::string preset;  // preset name or parameter file
  std::string source;  // where the parameters come from
  ClumpParams params;
  ClumpMassOptions mass;
  std::uint64_t seed = 0;
};

// Writes the layout above (attributes, balls/, clumps/, shape/) into `where`, a file's
// root or a group: a study archive's /runs/<id>/clumps holds the same (docs/ARCHIVE.md).
void write_clump_sample(hid_t where, const ClumpArchiveHeader& header,
                        const std::vector<ClumpTemplate>& clumps,
                        const std::vector<ClumpShape>& shapes);

// Writes (overwrites) `path`. Throws std::runtime_error naming the file on failure.
void write_clump_archive(const std::string& path, const ClumpArchiveHeader& header,
                         const std::vector<ClumpTemplate>& clumps,
                         const std::vector<ClumpShape>& shapes);

}  // namespace ballast
