// Checkpoints of a box test's load cycles, from which a killed run resumes bit for bit
// (many cycles take a night: docs/CYCLES.md, "Checkpoints").
//
// A checkpoint holds everything the rest of the run reads: the engine's state
// (Simulation::save_state), the result measured so far, the load loop's own state
// (CycleLoop) and the clump templates the archive will describe. It is written at
// every point between two stages of the preparation (PrepStage: there it holds the
// bed's stages instead of a result and a loop), at the start of loading, after every
// K-th cycle and every M minutes of wall time, each time to a temporary file that is synced and
// then renamed over the last one: a kill at any moment leaves the previous checkpoint or the new
// one, whole. The file ends with an FNV-1a hash of its content, and its head names the build and
// the scene: a damaged checkpoint, or one that another build or another scene wrote, is refused
// with a message that says so, never half read.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cases/box_test_prepare.hpp"
#include "cases/box_test_result.hpp"
#include "cases/cycle_recorder.hpp"
#include "engine/simulation.hpp"

namespace ballast {

struct CheckpointPlan {
  std::string path;            // the checkpoint file; empty: no checkpoints
  long every_cycles = 0;       // after every K-th cycle; 0: not by cycles
  double every_minutes = 0.0;  // at least this often, wall-clock minutes; 0: not by time
  bool resume = false;         // continue from `path` when the file exists
  std::string build_id;        // the program that writes and reads (its git revision)
  std::string scene_text;      // the scene as run: a checkpoint resumes only the same scene
  // The run's log so far, kept in the checkpoint and written again to the log on
  // resuming (the study archives each run's whole log); empty function: not kept.
  std::function<std::string()> log_text;
  // A prepared bed (PrepStage::kPrepared) shared with other runs whose scenes give
  // the same bed_text (cases/shared_bed.hpp): a run starts from bed_path when the file
  // is there, and, when it prepares its own bed and is the bed's writer, writes it there.
  std::string bed_path, bed_text;
  bool bed_writer = false;
};

// What the load loop carries from step to step, besides the simulation.
struct CycleLoop {
  Index wall = 0, servo = 0;  // the sleeper and its servo
  double x0 = 0.0, x1 = 0.0;  // m, the sleeper's extent in x
  double top = 0.0;           // m, the bed's top under the sleeper before it was placed
  double t0 = 0.0, t_peak = 0.0, t_end = 0.0, z0 = 0.0;  // s, s, s, m
  long step0 = 0;                                        // the step count at the start of loading
  EnergyBudget energy0;                                  // at the start of loading
  double err2 = 0.0;                                     // N², Σ (achieved − target force)²
  long samples = 0;                                      // steps in that sum
  bool peak_done = false;                                // the first peak has been recorded
  std::vector<Vec3> rotation_peak;  // rad, each body's accumulated rotation at the first peak
  double seconds = 0.0;             // wall seconds the loop ran before the last resume
  double run_seconds = 0.0;         // wall seconds of the whole run before it
  CycleRecorder cycles;

  template <class Io>
  void state_fields(Io& io) {
    io(wall, servo, x0, x1, top, t0, t_peak, t_end, z0, step0, energy0, err2, samples, peak_done,
       rotation_peak, seconds, run_seconds, cycles);
  }
};

// What a checkpoint restores besides the simulation: a point of the preparation
// (point.done > kNone: the bed's stages and dt_spheres, the templates, the log), or
// the load cycles (point.done == kNone: the result so far, the loop, the templates,
// the log).
struct RunCheckpoint {
  PrepPoint point;
  std::vector<StageReport> stages;  // the preparation's, at a point of it
  double dt_spheres = 0.0;          // s, likewise
  BoxTestResult result;             // measured so far, in the load cycles
  CycleLoop loop;
  std::vector<ClumpTemplate> templates;  // the clump sample's (empty for spheres)
  std::string log;                       // the run's log so far (plan.log_text)
};

// Writes plan.path atomically, in the load cycles. Throws std::runtime_error naming
// the path and the cause when the file system refuses (the load loop reports it and
// goes on).
void write_checkpoint(const CheckpointPlan& plan, const Simulation& sim,
                      const BoxTestResult& result, const CycleLoop& loop,
                      const std::vector<ClumpTemplate>& templates);

// The same at a point of the preparation (`point.done` > kNone).
void write_preparation_checkpoint(const CheckpointPlan& plan, const PreparedBed& bed,
                                  const PrepPoint& point);

// Reads plan.path into `sim` (whose log stream it keeps) and returns the rest; throws
// SetupError for a file that is damaged, truncated, or of another build or scene.
RunCheckpoint read_checkpoint(const CheckpointPlan& plan, Simulation& sim);

}  // namespace ballast
