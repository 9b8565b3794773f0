// Everything a box-test run measures (Lu & McDowell 2007, section 3.3), in SI units
// (angles in degrees, as the paper's figures). Written to HDF5 by study/.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cases/box_test_prepare.hpp"
#include "engine/clump_shape.hpp"
#include "engine/diagnostics.hpp"

namespace ballast {

// How the sleeper bears on the bed: its touching ball contacts, the bodies they
// belong to, and their forces (N).
struct SleeperBearing {
  long contacts = 0, bodies = 0;
  double total = 0.0, max = 0.0, p50 = 0.0, p90 = 0.0;
};

// Contacts at one instant (Figs 11-12) and the force network behind Figs 10-12.
struct ContactSnapshot {
  ContactStats stats;
  // Ball–ball contacts touching now: the two ball centres and |F|, for drawing.
  std::vector<Vec3> from, to;
  std::vector<double> force;                                 // N
  double force_p50 = 0.0, force_p90 = 0.0, force_p99 = 0.0;  // N, percentiles of `force`
  SleeperBearing sleeper;                                    // zero before a sleeper is placed
};

// Contacts counted by other conventions than ours (touching pairs of different
// bodies, once), to see how PFC's figures can arise (docs/VALIDATION.md): pairs
// whose gap is at most gap[i], and the overlapping ball pairs inside clumps.
struct NearPairs {
  std::vector<double> gap;       // m
  std::vector<long> ball_pairs;  // pairs of balls of different bodies, counted once
  std::vector<long> wall_pairs;  // ball–wall pairs
  long intra_clump_pairs = 0;    // overlapping pairs of balls of one clump
};

// Mean motion of the top layer's particles beneath and beside the sleeper (the
// paper's displacement directions, Figs 15-17), from the start of loading.
struct ZoneMotion {
  long count = 0;
  double dz_peak = 0.0, dz_end = 0.0;  // m, mean vertical displacement, up positive
  double rotation_loading_deg = 0.0, rotation_unloading_deg = 0.0, rotation_cycle_deg = 0.0;
};

struct Zones {
  double surface = 0.0;      // m, bed top under the sleeper at the start of loading
  double layer_depth = 0.0;  // m, the top layer: centres at most this far below it
  ZoneMotion beneath, beside;
};

struct RotationStats {
  double mean_deg = 0.0, max_deg = 0.0;
};

// The clumps a clump sample is made of (Fig. 7, and Table 1's clump statistics):
// body i is templates[shape_index[i]], with the shape of its union of balls.
struct ClumpSampleRecord {
  std::string shape;  // the preset the parameters started from ("table2/sample1")
  ClumpParams params;
  ClumpMassOptions mass;
  std::uint64_t seed = 0;
  std::vector<ClumpTemplate> templates;
  std::vector<ClumpShape> shapes;  // measure_clump_shapes(templates), same order
};

// The state of the bed at the end of one load cycle the scene names
// (/measurement/snapshot_cycles), from the start of loading.
struct CycleSnapshot {
  long cycle = 0;           // 1-based
  double settlement = 0.0;  // m, the sleeper's, downward positive
  std::vector<Vec3> position;
  std::vector<double> rotation_deg;  // accumulated rotation since the start of loading
};

// One entry per completed load cycle (cycle n ends at t0 + n / frequency): the cheap
// measures every cycle, how settlement grows with the number of cycles N. Settlements
// are the sleeper's, downward positive, from the start of loading (m).
struct CycleRecords {
  std::vector<double> settlement_peak;    // at the cycle's peak load
  std::vector<double> settlement_trough;  // at its end (the preload): permanent after cycle n
  std::vector<double> sleeper_work;       // J, ∫F dδ over the cycle: the load–deformation
                                          // loop's area plus what it left in the bed
  std::vector<double> rotation_mean_deg;  // mean over bodies at the cycle's end
  std::vector<long> sleeper_contacts, sleeper_bodies;  // bearing on the sleeper at peak
  std::vector<double> porosity_under;  // grid porosity under the sleeper at the cycle's end
  std::vector<CycleSnapshot> snapshots;
  std::size_t count() const { return settlement_trough.size(); }
};

struct BoxTestResult {
  std::string scene_name;
  std::vector<StageReport> stages;
  long bodies = 0, balls = 0;
  double dt = 0.0;           // s, during loading
  double dt_critical = 0.0;  // s
  double wall_seconds = 0.0;
  bool loaded = false;  // false when the scene stopped after preparation or compaction

  // Porosity before loading: the paper's 5 mm grid in the column under the sleeper,
  // and PFC measurement spheres on the column's axis (spheres only: the balls of a
  // clump overlap, and a measurement sphere would count the overlaps twice).
  double porosity_grid = 0.0;
  double porosity_grid_interior = 0.0;  // one nominal diameter inside walls, base and top
  std::vector<double> sphere_heights, porosity_spheres;  // m, -
  double bed_height = 0.0;                               // m, top of the bed under the sleeper

  ContactSnapshot before, at_peak, after;
  NearPairs near_before;  // at the start of loading
  Zones zones;            // set for loaded runs
  RotationStats rotation_loading, rotation_unloading, rotation_cycle;
  double max_displacement_peak = 0.0, max_displacement_after = 0.0;  // m

  // Sleeper: settlement (downward positive) from the start of loading, m: at the first
  // peak, after the last cycle, and the last cycle's rebound (peak − end).
  double settlement_peak = 0.0, permanent_settlement = 0.0, resilient_settlement = 0.0;
  double max_force_error = 0.0, rms_force_error = 0.0;  // N, achieved − target

  // Load-deformation series (Fig 18), sampled during the snapshot cycles only (so
  // that 10^5 cycles do not fill the memory); time from the start of loading.
  std::vector<double> time, target_force, sleeper_force, settlement;
  CycleRecords cycles;

  // Per body: positions at the start of loading, at the first peak load and after the
  // last cycle; accumulated rotations (deg) during the first loading, from the first
  // peak to the end (unloading), and over all cycles;
  // template (shape) index.
  std::vector<Vec3> position_start, position_peak, position_end;
  std::vector<double> rotation_deg_loading, rotation_deg_unloading, rotation_deg_cycle;
  std::vector<long> shape_index;
  std::optional<ClumpSampleRecord> clumps;  // unset for spheres

  EnergyBudget energy;
};

}  // namespace ballast
