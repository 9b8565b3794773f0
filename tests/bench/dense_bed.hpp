// The settled 1,936-sphere bed the dense-bed and clump-bed benchmarks start from.
#pragma once

#include "cases/bed.hpp"

namespace ballast {

// How the bed's bodies are numbered: as the generator gives them, at random, or at
// random and then by the engine's spatial sort (as a packing file from another code).
enum class BedOrder { kSpatial = 0, kRandom = 1, kRandomEngineSorted = 2 };

// Pours and settles a bed; benchmarks step copies of it. `ledger`:
// SimulationSettings::energy_ledger (the bed's bits do not depend on it).
inline Simulation pour_dense_bed(BedOrder order, bool ledger = true) {
  BedOptions o;  // 1,936 spheres of 36.25 mm, kn = ks = 5.08e9 N/m
  o.sim.energy_ledger = ledger;
  o.spatial_order = order == BedOrder::kSpatial;
  o.engine_sort = order == BedOrder::kRandomEngineSorted;
  o.friction = 0.5;
  o.rubber_base = false;
  // Fast pour: 20 g, no local damping (it slows free fall to 0.3 g), inelastic
  // contacts. Then the benchmark conditions.
  o.sim.gravity = Vec3(0, 0, -9.81 * 20);
  o.sim.local_damping = 0.0;
  o.sim.damping_ratio = 0.5;
  Simulation sim = make_bed(o);
  while (sim.time() < 0.12) sim.step();
  sim.set_gravity(Vec3(0, 0, -9.81));
  sim.set_damping_ratio(0.0);
  sim.set_local_damping(0.7);
  sim.run(5000);
  return sim;
}

// Poured once per process and per body order.
inline const Simulation& settled_dense_bed(BedOrder order, bool ledger = true) {
  if (!ledger) {
    static const Simulation unbooked = pour_dense_bed(order, false);
    return unbooked;  // only ever asked for in spatial order
  }
  static const Simulation spatial = pour_dense_bed(BedOrder::kSpatial);
  if (order == BedOrder::kSpatial) return spatial;
  if (order == BedOrder::kRandom) {
    static const Simulation shuffled = pour_dense_bed(BedOrder::kRandom);
    return shuffled;
  }
  static const Simulation sorted = pour_dense_bed(BedOrder::kRandomEngineSorted);
  return sorted;
}

}  // namespace ballast
