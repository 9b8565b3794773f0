// Bounds a box-test scene must keep that tie several of its fields together, checked
// while the scene is parsed so that `ballast study --dry-run` and the start of a run
// refuse what the run would otherwise only find minutes or hours in (a load no contact
// can carry, a cycle shorter than a few timesteps, a run of 10^150 steps). Each
// throws SetupError naming the field, its value and what is allowed.
#pragma once

#include "cases/box_test_scene.hpp"

namespace ballast {

// Particles smaller than the box, and a count that makes a bed in it and fits in the
// memory this machine has free.
void check_generated_bed(const BoxTestScene& s);

// The sleeper's load, speed and cycles against the ball's material, through the
// timestep estimate of one sphere (engine/timestep.hpp). `generated`: the particles
// are the scene's nominal spheres or clumps; a packing file's radii are not known
// here, so its steps are not estimated.
void check_loading_bounds(const BoxTestScene& s, bool generated);

// The porosity grid and the zones inside the box. (The measurement spheres are
// shrunk to fit the bed where they are placed: box_test_load.cpp.)
void check_measurement_bounds(const BoxTestScene& s);

}  // namespace ballast
