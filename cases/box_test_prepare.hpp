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
// equilibrium_ratio (checked every 500 steps) or after max_stage_steps; the
// frictionless settling and the seating of the sleeper have rules of their own
// (SettleRule), because neither reaches a low ratio (docs/BOX_TEST.md, "Stopping rules").
#pragma once

#include <functional>
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
  // What ended a settling stage: "equilibrium", "at rest", "steady creep"
  // or "step limit"; empty for a stage of fixed length (growth, the load cycle).
  std::string ended_by;
  // Ended by its rule (or of fixed length), not by the step limit.
  bool settled() const { return ended_by != "step limit"; }
  // What ended it, as the run summary and the archive record it.
  std::string what_ended() const { return ended_by.empty() ? "fixed length" : ended_by; }
  // The energy budget over the stage (engine/diagnostics.hpp), J: what gravity and the
  // walls put in, what friction, damping and dashpots took out, and the change of the
  // balance, which is the integration's error (and, while radii grow, the elastic
  // energy growth creates: nothing books it as work).
  double energy_in = 0.0, energy_dissipated = 0.0, energy_error = 0.0;
  void book_energy(const EnergyBudget& from, const EnergyBudget& to) {
    energy_in = (to.gravity_work - from.gravity_work) + (to.wall_work - from.wall_work);
    energy_dissipated = to.dissipated() - from.dissipated();
    energy_error = to.balance() - from.balance();
  }
};

struct PreparedBed {
  Simulation sim;
  std::vector<StageReport> stages;
  double dt_spheres = 0.0;  // s, timestep of stage 1
  // Clump samples: body i's template (shape and mass properties), so that an archive
  // can show the clumps (Fig. 7). Empty for spheres.
  std::vector<ClumpTemplate> templates;
};

// The points between two stages of the preparation, where a checkpoint is written and
// a killed run resumes (box_test_checkpoint.hpp): a preparation of Sample 2 at full
// scale takes half an hour of one core, and a kill in it lost all of it.
enum class PrepStage : int {
  kNone = 0,        // not in the preparation (a checkpoint of the load cycles)
  kGenerated,       // stages 1-2 done (or the packing imported), the plate on or the lid away
  kSettled,         // the frictionless settling done, the compaction friction set
  kCompacted,       // compaction under the enhanced gravity done
  kAtOneG,          // settled again at 9.81 m/s²
  kFrictionRaised,  // settled again with the loading friction
  kPrepared         // the plate lifted and the bed settled again (or no plate): what
                    // stage 4 starts from, and what runs of a study share
                    // (cases/shared_bed.hpp)
};

// Where a preparation stands at such a point, besides the bed (PreparedBed).
struct PrepPoint {
  PrepStage done = PrepStage::kNone;
  bool plate = false;        // the levelling plate is on the bed's top,
  Index plate_servo = 0;     // pressed by this servo
  double run_seconds = 0.0;  // wall seconds the run had taken when it got here

  template <class Io>
  void state_fields(Io& io) {
    io(done, plate, plate_servo, run_seconds);
  }
};

// Called at each point with the bed as it stands there (writes a checkpoint).
using PrepCheckpoint = std::function<void(const PreparedBed&, const PrepPoint&)>;

// Runs stages 1-3 (or fewer: scene.stop_after; 3 only for an imported packing). Progress lines go
// to `log` (nullptr: silent); `at_point`, when given, is called at every PrepStage.
PreparedBed prepare_box_test(const BoxTestScene& scene, std::ostream* log,
                             const PrepCheckpoint& at_point = {});

// The rest of the preparation for a bed restored where a checkpoint left it (`from`,
// done > kNone): the same steps, to the bit, as if it had never stopped.
void continue_box_test_preparation(const BoxTestScene& scene, PreparedBed& bed, PrepPoint from,
                                   std::ostream* log, const PrepCheckpoint& at_point = {});

enum class SettleRule {
  kRatio,    // unbalanced-force ratio below `ratio`, with contacts
  kKinetic,  // kinetic energy below 1e-4 of the potential energy above the base
  kSeated,   // the sleeper under its preload: kRatio, or the bed creeps at a steady rate
};

// kSeated ends the stage when the bed is quasi-static (unbalanced-force ratio below
// kQuasiStaticRatio) and the sleeper's settlement over the last kSettleWindow of
// simulated time is at least kSteadyCreep of its settlement over the window before:
// the creep no longer slows down.
inline constexpr double kSettleWindow = 0.01;  // s
inline constexpr double kSteadyCreep = 0.9;
inline constexpr double kQuasiStaticRatio = 0.1;

// Steps until the rule holds or `max_steps` have run. The ratio and energy rules are
// checked every 500 steps after the first 2,000; the creep rule at the end of every
// window from the second on. kSeated needs `depth`: how far the sleeper has moved
// down, m.
StageReport settle(Simulation& sim, const std::string& name, double ratio, long max_steps,
                   std::ostream* log, SettleRule rule = SettleRule::kRatio,
                   const std::function<double()>& depth = {});

// Height of the bed's top surface over x in [x0, x1]: the highest point of any ball
// over that strip (the sleeper placed above it touches nothing), m.
double bed_top(const Simulation& sim, double x0, double x1);

}  // namespace ballast
