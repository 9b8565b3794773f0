// Sample preparation of the box test, as the paper describes it (section 3):
//   1. spheres   generated at random without overlap at a reduced radius in a
//                closed box, grown to full size (PFC radius expansion) and cycled
//                to equilibrium; then the lid is lifted away;
//   2. clumps    (clump samples) each sphere replaced by a clump generated in its
//                virtual sphere, at a random orientation, shrunk to fit inside the
//                sphere and grown back, so the overlaps relax gradually;
//   3. compact   enhanced gravity with friction 0.3, gravity back to 9.81 m/s², then
//                friction raised to its loading value; each ends at equilibrium.
// A scene with a packing file (BoxTestScene::packing_file) skips stages 1-2: the
// imported bed stands for the prepared sample, in the box without its lid.
// Every settling stage ends when the unbalanced-force ratio falls below the scene's
// equilibrium_ratio (checked every 500 steps) or after max_stage_steps.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "cases/box_test_scene.hpp"
#include "engine/clump_template.hpp"
#include "engine/simulation.hpp"

namespace ballast {

struct StageReport {
  std::string name;
  long steps = 0;
  double simulated = 0.0;   // s
  double seconds = 0.0;     // wall-clock s
  double unbalanced = 0.0;  // ratio at the end
  bool settled = false;     // ended by the equilibrium rule, not the step limit
};

struct PreparedBed {
  Simulation sim;
  std::vector<StageReport> stages;
  double dt_spheres = 0.0;  // s, timestep of stage 1
  // Clump samples: body i's template (shape and mass properties), so that an archive
  // can show the clumps (Fig. 7). Empty for spheres.
  std::vector<ClumpTemplate> templates;
};

// Runs stages 1-3 (or fewer: scene.stop_after; 3 only for an imported packing). Progress lines go
// to `log` (nullptr: silent).
PreparedBed prepare_box_test(const BoxTestScene& scene, std::ostream* log);

enum class SettleRule {
  kRatio,    // unbalanced-force ratio below `ratio`, with contacts
  kKinetic,  // kinetic energy below 1e-4 of the potential energy above the base
};

// Steps until the rule holds (checked every 500 steps, after at least 2,000) or
// `max_steps` have run.
StageReport settle(Simulation& sim, const std::string& name, double ratio, long max_steps,
                   std::ostream* log, SettleRule rule = SettleRule::kRatio);

// Height of the bed's top surface over x in [x0, x1]: the highest point of any ball
// over that strip (the sleeper placed above it touches nothing), m.
double bed_top(const Simulation& sim, double x0, double x1);

}  // namespace ballast
