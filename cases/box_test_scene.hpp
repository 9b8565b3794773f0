// The paper's box test (Lu & McDowell 2007, section 3) as a scene: every number has
// the paper's value as default and can be set from a JSON scene file
// (cases/box_test/*.json; format in docs/BOX_TEST.md).
#pragma once

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cases/box_test.hpp"
#include "engine/clump_generator.hpp"
#include "engine/clump_mass.hpp"
#include "engine/rigid_rotation.hpp"
#include "engine/simulation.hpp"

namespace ballast {

struct BoxTestScene {
  std::string name = "spheres";
  // particles: "spheres" or a clump preset ("table2/sample1"); clump parameters
  // given in the file override the preset's.
  std::string shape = "spheres";
  std::optional<ClumpParams> clumps;  // resolved from shape (unset for spheres)
  // A packing file (cases/packing_file.hpp) that stands for the prepared sample:
  // stages 1-2 are skipped. Resolved against the scene file's directory; empty: the
  // sample is generated.
  std::string packing_file;
  long count = box_test::kSphereCount;
  double diameter = box_test::kSphereDiameter;  // m, spheres and clumps' nominal sphere
  std::uint64_t seed = 1;
  MassMode mass_mode = MassMode::kPaper;  // eqs 10-15, as the paper
  double mass_accuracy = 0.005;           // uniform mode only
  // box, m
  double length = box_test::kLength, width = box_test::kWidth, height = box_test::kHeight;
  // materials: what each entity brings to a contact under the contact law
  // (sim.contact_law; each law reads its own members, engine/material.hpp). Friction
  // is set per stage from the two coefficients below, not from these.
  Material ball = box_test::ballast_material(0.0);
  Material wall = box_test::wall_material(0.0);  // side walls and sleeper
  Material base = box_test::rubber_base(0.0);    // rubber base
  double density = box_test::kDensity;           // kg/m³
  // /numerics/mass_scale, PFC users' mass (density) scaling: the bodies are simulated
  // mass_scale times heavier and gravity mass_scale times weaker, so that every weight
  // and every static force stays as it is while the critical timestep grows by
  // sqrt(mass_scale). What it changes is inertia: a load cycle at frequency f then
  // responds as one at f * sqrt(mass_scale) would (docs/TRADEOFFS.md).
  double mass_scale = 1.0;
  double simulated_density() const { return density * mass_scale; }
  // m/s², the gravity of a stage at `factor` × g, weakened by the mass scale.
  double gravity(double factor) const { return -9.81 * factor / mass_scale; }
  double friction_compaction = box_test::kFrictionCompaction;
  double friction_loading = box_test::kFrictionLoading;
  // The engine's settings the scene file sets: /numerics (dt_safety, dt as fixed_dt,
  // local_damping, rotation, adaptive_rebuild) and /materials/contact_law, with the
  // engine's defaults. Each stage's simulation starts from them and adds its domain
  // and gravity (box_test_prepare.cpp, settings_for).
  SimulationSettings sim;
  // /numerics/preset: the named preset whose fields filled what the scene left out
  // (cases/numerics_presets.hpp); empty: none.
  std::string numerics_preset;
  std::vector<std::string> preset_fields_kept;  // the preset's fields the scene gave itself
  // preparation (PFC radius expansion, then gravity compaction)
  double initial_porosity = 0.5;      // of the grown spheres in their fill region (loose:
                                      // denser jams while growing and springs apart)
  double expansion_speed = 0.05;      // m/s at which ball radii grow (slow enough not to fling)
  bool frictionless_settling = true;  // settle at 1 g without friction before compaction
  // Pa: the lid stays on through compaction as a servo plate pressing the bed's top
  // with this pressure, and is lifted off before the sleeper comes, so the sleeper
  // bears on a levelled surface (docs/BOX_TEST.md, "The levelling plate"). A scene
  // that does not give it gets the sleeper's preload pressure, preload / (sleeper
  // length × box width): 40 kPa in the paper's box. 0: the lid is lifted off after
  // growth and the bed settles with a free, rough top.
  double levelling_pressure = 3e3 / (0.25 * box_test::kWidth);
  double gravity_factor = 10.0;     // enhanced gravity during compaction, × 9.81 m/s²
  double equilibrium_ratio = 5e-3;  // unbalanced-force ratio ending a settling stage
  // The seating under the preload may also end by steady creep (docs/BOX_TEST.md,
  // "Stopping rules"); false: only by equilibrium or the step limit.
  bool seating_creep_rule = true;
  // PFC local damping while the sleeper seats under the preload (stage 4's settling);
  // unset: numerics/local_damping, as in every stage from compaction on. The cycle
  // runs with numerics/local_damping either way.
  std::optional<double> seating_local_damping;
  long max_stage_steps = 400000;  // a stage that has not settled by then stops
  // sleeper: a rigid block across the full width, centred in x (the paper gives
  // no size: an assumption, docs/BOX_TEST.md)
  double sleeper_length = 0.25, sleeper_height = 0.1;  // m
  // m: the sleeper's edges rounded to this radius (0: sharp, the paper's flat block).
  // Only the two long lower edges touch the bed: the block spans the box's width.
  double sleeper_edge_radius = 0.0;
  double preload = 3e3, peak_load = 40e3;  // N
  double frequency = 3.0;                  // Hz
  long cycles = 1;
  double sleeper_max_speed = 0.5;  // m/s, servo cap
  double sleeper_gain = 0.5;       // servo gain (engine/servo.hpp; docs/BOX_TEST.md)
  // measurements
  double cube_side = 0.005;     // m, the paper's porosity grid
  double sphere_radius = 0.05;  // m, measurement spheres
  long series_every = 200;      // steps between load-displacement samples
  // Cycles (1-based) whose end is snapshotted (positions, rotations) and whose
  // load–deformation series is sampled; empty: 1, 10, 100, ... and the last
  // (cases/cycle_recorder.hpp).
  std::vector<long> snapshot_cycles;
  // m: the top layer whose particles the zone measurements follow (beneath and
  // beside the sleeper): centres within this depth of the bed's surface at the start
  // of loading. Two nominal diameters.
  double zone_depth = 2.0 * box_test::kSphereDiameter;
  // "": all stages; "prepare" or "compact" stop early (for studies of settling).
  std::string stop_after;
};

// Parses a scene file's JSON. Errors (SetupError) give the JSON path, the value and
// what is allowed; unknown keys are errors. A relative /particles/file is taken
// relative to `scene_dir` (the scene file's directory; empty: as it stands).
BoxTestScene parse_box_test_scene(const nlohmann::json& j, const std::string& scene_dir = "");
BoxTestScene load_box_test_scene(const std::string& path);

// Volume-equivalent radius of the particles' nominal sphere, m.
inline double nominal_radius(const BoxTestScene& s) {
  return 0.5 * s.diameter;
}

}  // namespace ballast
