// What the box test records of a bed's contacts at one instant: the force network
// (Figs 10-12), its force distribution, how the sleeper bears on the bed, and the
// counts by other conventions than ours that PFC's figures may follow.
#pragma once

#include <optional>
#include <vector>

#include "cases/box_test_result.hpp"
#include "engine/simulation.hpp"

namespace ballast {

// The q-quantile (q in [0, 1]) of `values`, linearly interpolated between order
// statistics (numpy's default); 0 for no values.
double percentile(std::vector<double> values, double q);

// Ball–ball contacts touching now (pairs of different bodies) with their forces and
// percentiles, and, given the sleeper's wall index, its bearing.
ContactSnapshot snapshot_contacts(const Simulation& sim, std::optional<Index> sleeper = {});

// How the sleeper (wall index `sleeper`) bears on the bed now: its ball contacts, the
// bodies they belong to, their forces. Cheap: one pass over the wall contacts.
SleeperBearing sleeper_bearing(const Simulation& sim, Index sleeper);

// Gap tolerances at which near_pairs counts, m: touching (0) up to a quarter of a
// 36.25 mm sphere's diameter.
std::vector<double> near_pair_gaps();

// Pairs of balls of different bodies, and ball–wall pairs, whose gap is at most each
// of `gaps` (m, ascending); and the overlapping ball pairs inside clumps. A cell grid
// of its own: the neighbour lists hold only pairs within the skin.
NearPairs count_near_pairs(const Simulation& sim, const std::vector<double>& gaps);

}  // namespace ballast
