#include "cases/box_test_scene.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cases/clump_overrides.hpp"
#include "cases/clump_presets.hpp"
#include "cases/json_fields.hpp"
#include "cases/numerics_presets.hpp"
#include "cases/scene_bounds.hpp"
#include "engine/contact_laws.hpp"

namespace ballast {

namespace {

const auto positive = [](double v) { return v > 0.0; };
const auto fraction = [](double v) { return v >= 0.0 && v <= 1.0; };

// With /particles/file the file says what the particles are and where: the keys
// that generate a sample would be silently ignored, so they are refused.
void refuse_with_file(const nlohmann::json& object, const char* key, const std::string& parent) {
  const auto it = object.find(key);
  if (it == object.end()) return;
  throw SetupError("invalid " + parent + "/" + key + " = " + it->dump() +
                   " together with /particles/file (allowed with a file: mass_mode, "
                   "mass_accuracy, and diameter for mass_mode \"paper\"; the file gives the "
                   "particles, and stages 1-2 of the preparation, which " +
                   key + " would shape, are skipped)");
}

// /materials/contact_law and what each entity brings to a contact: for each of the
// ball, the walls and the base, <entity>_stiffness (kn = ks, the paper's way) and
// <entity>_<parameter> for every parameter of every law (ball_kn, ball_young_modulus,
// ...), so that a study may switch the law without rewriting the materials.
void read_contact_materials(JsonFields& m, BoxTestScene& s) {
  m.text("contact_law", s.sim.contact_law, "one of: " + contact_law_names(),
         [](const std::string& v) { return contact_law_index(v) >= 0; });
  const std::pair<const char*, Material*> entities[] = {
      {"ball", &s.ball}, {"wall", &s.wall}, {"base", &s.base}};
  for (const auto& [entity, material] : entities) {
    const std::string prefix = std::string(entity) + "_";
    double k = 0.0;
    if (m.number((prefix + "stiffness").c_str(), k, "> 0 N/m", positive))
      material->kn = material->ks = k;
    for (int law = 0; law < kContactLawCount; ++law)
      for (const LawParameter& p : law_parameters(law))
        m.number((prefix + std::string(p.name)).c_str(), material->*p.member,
                 std::string(p.allowed), [&](double v) { return p.allows(v); });
  }
}

void read_particles(const nlohmann::json& j, BoxTestScene& s, const std::string& scene_dir) {
  JsonFields f(j, "/particles");
  const bool has_file = f.text("file", s.packing_file, "a non-empty path to a packing file",
                               [](const std::string& v) { return !v.empty(); });
  if (has_file && std::filesystem::path(s.packing_file).is_relative() && !scene_dir.empty())
    s.packing_file = (std::filesystem::path(scene_dir) / s.packing_file).lexically_normal();
  const std::vector<std::string> presets = available_clump_presets();
  std::string names = "\"spheres\"";
  for (const std::string& p : presets) names += ", \"" + p + "\"";
  f.text("shape", s.shape, names, [&](const std::string& v) {
    return v == "spheres" || std::find(presets.begin(), presets.end(), v) != presets.end();
  });
  f.integer("count", s.count, ">= 1", [](long v) { return v >= 1; });
  // All 64 bits: a study run's seed is a 64-bit hash (docs/STUDY.md).
  f.unsigned_integer("seed", s.seed);
  f.number("diameter", s.diameter, "> 0 m", positive);
  std::string mass = mass_mode_name(s.mass_mode);
  f.text("mass_mode", mass, "\"sum\", \"paper\" or \"uniform\"",
         [](const std::string& v) { return v == "sum" || v == "paper" || v == "uniform"; });
  s.mass_mode = parse_mass_mode(mass);
  f.number("mass_accuracy", s.mass_accuracy, "in [1e-5, 0.1]",
           [](double v) { return v >= 1e-5 && v <= 0.1; });
  const nlohmann::json& clump = f.object("clump");
  f.finish();
  if (has_file) {
    for (const char* key : {"shape", "count", "seed", "clump"})
      refuse_with_file(j, key, "/particles");
    s.clumps.reset();
    return;
  }
  if (s.shape == "spheres") {
    if (!clump.empty())
      throw SetupError(
          "invalid /particles/clump for shape \"spheres\" (allowed: "
          "only with a clump preset as shape)");
    s.clumps.reset();
    return;
  }
  ClumpParams p = load_clump_preset(s.shape).params;
  JsonFields c(clump, "/particles/clump");
  read_clump_overrides(c, p);
  c.finish();
  p.nominal_diameter = s.diameter;
  s.clumps = p;
}

}  // namespace

BoxTestScene parse_box_test_scene(const nlohmann::json& given, const std::string& scene_dir) {
  BoxTestScene s;
  nlohmann::json j = given;
  s.preset_fields_kept = apply_numerics_preset(j);
  JsonFields top(j, "");
  top.text("name", s.name, "a non-empty string", [](const std::string& v) { return !v.empty(); });
  read_particles(top.object("particles"), s, scene_dir);

  JsonFields box(top.object("box"), "/box");
  box.number("length", s.length, "> 0 m", positive);
  box.number("width", s.width, "> 0 m", positive);
  box.number("height", s.height, "> 0 m", positive);
  box.finish();

  JsonFields m(top.object("materials"), "/materials");
  read_contact_materials(m, s);
  m.number("density", s.density, "> 0 kg/m^3", positive);
  const auto mu = [](double v) { return v >= 0.0 && v <= 10.0; };
  m.number("friction_compaction", s.friction_compaction, "in [0, 10]", mu);
  m.number("friction_loading", s.friction_loading, "in [0, 10]", mu);
  m.finish();

  JsonFields n(top.object("numerics"), "/numerics");
  n.number("dt_safety", s.sim.dt_safety, "in (0, 1]", [](double v) { return v > 0.0 && v <= 1.0; });
  double dt = 0.0;
  if (n.number("dt", dt, "> 0 s", positive)) s.sim.fixed_dt = dt;
  n.number("local_damping", s.sim.local_damping, "in [0, 1)",
           [](double v) { return v >= 0.0 && v < 1.0; });
  std::string rotation = rotation_integrator_name(s.sim.rotation);
  n.text("rotation", rotation, "\"pfc\" or \"full\"",
         [](const std::string& v) { return v == "pfc" || v == "full"; });
  s.sim.rotation = parse_rotation_integrator(rotation);
  n.boolean("adaptive_rebuild", s.sim.adaptive_rebuild);
  n.number("mass_scale", s.mass_scale, "in [1, 1e4]",
           [](double v) { return v >= 1.0 && v <= 1e4; });
  n.text("preset", s.numerics_preset, numerics_preset_names(),
         [](const std::string&) { return true; });  // checked by apply_numerics_preset
  n.finish();

  JsonFields p(top.object("preparation"), "/preparation");
  p.number("initial_porosity", s.initial_porosity, "in [0.3, 0.7]",
           [](double v) { return v >= 0.3 && v <= 0.7; });
  p.number("expansion_speed", s.expansion_speed, "in (0, 1] m/s",
           [](double v) { return v > 0.0 && v <= 1.0; });
  if (!s.packing_file.empty())
    for (const char* key : {"initial_porosity", "expansion_speed"})
      refuse_with_file(top.object("preparation"), key, "/preparation");
  p.boolean("frictionless_settling", s.frictionless_settling);
  p.boolean("seating_creep_rule", s.seating_creep_rule);
  double seating_damping = 0.0;
  if (p.number("seating_local_damping", seating_damping, "in [0, 1)",
               [](double v) { return v >= 0.0 && v < 1.0; }))
    s.seating_local_damping = seating_damping;
  const bool levelling_given =
      p.number("levelling_pressure", s.levelling_pressure, "in [0, 1e6] Pa",
               [](double v) { return v >= 0.0 && v <= 1e6; });
  p.number("gravity_factor", s.gravity_factor, "in [1, 1000]",
           [](double v) { return v >= 1.0 && v <= 1000.0; });
  p.number("equilibrium_ratio", s.equilibrium_ratio, "in (0, 0.5]",
           [](double v) { return v > 0.0 && v <= 0.5; });
  p.integer("max_stage_steps", s.max_stage_steps, ">= 1000", [](long v) { return v >= 1000; });
  p.text("stop_after", s.stop_after, "\"\", \"prepare\" or \"compact\"",
         [](const std::string& v) { return v.empty() || v == "prepare" || v == "compact"; });
  p.finish();

  JsonFields sl(top.object("sleeper"), "/sleeper");
  sl.number("length", s.sleeper_length, "> 0 m and < the box length",
            [&](double v) { return v > 0.0 && v < s.length; });
  sl.number("height", s.sleeper_height, "> 0 m", positive);
  sl.number("edge_radius", s.sleeper_edge_radius,
            "in [0, half the smaller of /sleeper/length and /sleeper/height) m", [&](double v) {
              return v >= 0.0 && 2.0 * v < std::min(s.sleeper_length, s.sleeper_height);
            });
  sl.number("preload", s.preload, "> 0 N", positive);
  sl.number("peak_load", s.peak_load, "> preload", [&](double v) { return v > s.preload; });
  sl.number("frequency", s.frequency, "> 0 Hz", positive);
  sl.integer("cycles", s.cycles, ">= 1", [](long v) { return v >= 1; });
  sl.number("max_speed", s.sleeper_max_speed, "> 0 m/s", positive);
  sl.number("gain", s.sleeper_gain, "in (0, 1]", [](double v) { return v > 0.0 && v <= 1.0; });
  sl.finish();
  if (!levelling_given) s.levelling_pressure = s.preload / (s.sleeper_length * s.width);

  JsonFields me(top.object("measurement"), "/measurement");
  me.number("cube_side", s.cube_side, "> 0 m", positive);
  me.number("sphere_radius", s.sphere_radius, "> 0 m", positive);
  me.integer("series_every", s.series_every, ">= 1", [](long v) { return v >= 1; });
  me.integers("snapshot_cycles", s.snapshot_cycles,
              "in [1, /sleeper/cycles = " + std::to_string(s.cycles) + "]",
              [&](long v) { return v >= 1 && v <= s.cycles; });
  me.number("zone_depth", s.zone_depth, "> 0 m", positive);
  me.finish();
  top.finish();
  if (s.packing_file.empty()) check_generated_bed(s);
  check_loading_bounds(s, s.packing_file.empty());
  check_measurement_bounds(s);
  return s;
}

BoxTestScene load_box_test_scene(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SetupError("cannot read scene file '" + path + "'");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw SetupError("scene file '" + path + "' is not valid JSON: " + e.what());
  }
  try {
    return parse_box_test_scene(j, std::filesystem::path(path).parent_path().string());
  } catch (const SetupError& e) {
    throw SetupError("scene file '" + path + "': " + e.what());
  }
}

}  // namespace ballast
