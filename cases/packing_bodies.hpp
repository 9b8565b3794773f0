// Packings (cases/packing_file.hpp) into a Simulation's bodies and back.
//
// A body of one ball becomes a sphere. A body of several balls becomes a rigid clump
// whose mass properties come from its balls through engine/clump_mass, exactly as
// a generated clump's do (cases/bed.cpp, box_test_prepare.cpp): centre of mass,
// principal frame and moments for the chosen mass mode. The file's coordinates are
// the generation frame, so the clump is placed at its centre of mass with its
// principal axes as orientation and its balls land back where the file put them
// (to rounding: one or two ulps of the coordinate).
#pragma once

#include "cases/packing_file.hpp"
#include "engine/clump_mass.hpp"
#include "engine/simulation.hpp"

namespace ballast {

// How imported clumps get their mass. mass.density is the balls' density (kg/m³);
// nominal_diameter (m) is the sphere whose volume is V_clump in mode "paper"
// (eq 10), as for generated clumps; the other modes ignore it.
struct PackingMass {
  ClumpMassOptions mass;
  double nominal_diameter = 0.0;
};

// The template a clump of the packing becomes (offsets in its principal frame,
// generation frame = the file's frame).
ClumpTemplate packing_clump_template(const Packing& p, Index body, const PackingMass& m);

// Adds every body of the packing, in file order, with material `material`. Returns
// the index of the first body added.
Index add_packing(Simulation& sim, const Packing& p, const PackingMass& m, Index material);

// An upper bound on the size of every body, m: the largest over bodies of
// 2·max_k(|c_k − c̄| + r_k), c̄ the mean of its ball centres. A body's centre of mass
// (any mass mode) lies inside the union of its balls, so no ball reaches farther
// than this from it; the domain must leave this much room. 2r for spheres.
double packing_body_size(const Packing& p);

// The balls of a simulation as a packing: spheres only gives x y z r; any clump
// makes it a clump packing (spheres then are one-ball bodies).
Packing packing_of(const Simulation& sim);

}  // namespace ballast
