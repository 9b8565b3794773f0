#include "study/archive/run_archive.hpp"

#include <cstdio>

#include "cases/cycle_recorder.hpp"
#include "study/archive/clump_archive.hpp"
#include "study/archive/file_image.hpp"
#include "study/archive/hdf5_util.hpp"

namespace ballast {

using namespace h5;

namespace {

std::vector<double> flat(const std::vector<Vec3>& v) {
  std::vector<double> out;
  out.reserve(3 * v.size());
  for (const Vec3& x : v) out.insert(out.end(), {x.x(), x.y(), x.z()});
  return out;
}

void vec3_set(hid_t g, const char* name, const std::vector<Vec3>& v, const char* units) {
  dataset(g, name, {static_cast<hsize_t>(v.size()), 3}, flat(v), units);
}

void scalar_set(hid_t g, const char* name, const std::vector<double>& v, const char* units) {
  dataset(g, name, {static_cast<hsize_t>(v.size())}, v, units);
}

Handle group(hid_t parent, const std::string& name) {
  return create_group(parent, name);
}

// b - a per body; empty when one of them was not recorded (a run stopped before loading
// has no peak).
std::vector<Vec3> difference(const std::vector<Vec3>& b, const std::vector<Vec3>& a) {
  if (a.size() != b.size()) return {};
  std::vector<Vec3> d(a.size());
  for (std::size_t k = 0; k < a.size(); ++k) d[k] = b[k] - a[k];
  return d;
}

void write_near_pairs(hid_t g, const NearPairs& n) {
  scalar_set(g, "near_gap", n.gap, "m");
  const auto as_double = [](const std::vector<long>& v) {
    return std::vector<double>(v.begin(), v.end());
  };
  scalar_set(g, "near_pairs", as_double(n.ball_pairs), "1");
  scalar_set(g, "near_wall", as_double(n.wall_pairs), "1");
  number_attribute(g, "intra_clump_pairs", n.intra_clump_pairs);
}

void write_zone(hid_t parent, const char* name, const ZoneMotion& z) {
  Handle g = group(parent, name);
  number_attribute(g, "count", z.count);
  number_attribute(g, "dz_peak", z.dz_peak);
  number_attribute(g, "dz_end", z.dz_end);
  number_attribute(g, "rotation_loading_deg", z.rotation_loading_deg);
  number_attribute(g, "rotation_unloading_deg", z.rotation_unloading_deg);
  number_attribute(g, "rotation_cycle_deg", z.rotation_cycle_deg);
}

// The per-cycle records (docs/ARCHIVE.md, "cycles"): compressed 1-D datasets, one
// entry per cycle, and a group per snapshot cycle.
void write_cycles(hid_t run, const CycleRecords& c) {
  Handle g = group(run, "cycles");
  number_attribute(g, "count", static_cast<long>(c.count()));
  number_attribute(g, "settlement_log_slope", settlement_log_slope(c.settlement_trough));
  std::vector<int> cycle(c.count()), contacts(c.sleeper_contacts.begin(), c.sleeper_contacts.end()),
      bodies(c.sleeper_bodies.begin(), c.sleeper_bodies.end());
  for (std::size_t k = 0; k < cycle.size(); ++k) cycle[k] = static_cast<int>(k + 1);
  std::vector<double> resilient(c.count());
  for (std::size_t k = 0; k < resilient.size(); ++k)
    resilient[k] = c.settlement_peak[k] - c.settlement_trough[k];
  compressed_dataset(g, "cycle", cycle, "1");
  compressed_dataset(g, "settlement_peak", c.settlement_peak, "m");
  compressed_dataset(g, "settlement_trough", c.settlement_trough, "m");
  compressed_dataset(g, "resilient_settlement", resilient, "m");
  compressed_dataset(g, "sleeper_work", c.sleeper_work, "J");
  compressed_dataset(g, "rotation_mean", c.rotation_mean_deg, "deg");
  compressed_dataset(g, "sleeper_contacts", contacts, "1");
  compressed_dataset(g, "sleeper_bodies", bodies, "1");
  compressed_dataset(g, "porosity_under", c.porosity_under, "1");
  Handle snaps = group(g, "snapshots");
  for (const CycleSnapshot& s : c.snapshots) {
    char name[32];
    std::snprintf(name, sizeof name, "cycle_%06ld", s.cycle);
    Handle one = group(snaps, name);
    number_attribute(one, "cycle", s.cycle);
    number_attribute(one, "settlement", s.settlement);
    vec3_set(one, "position", s.position, "m");
    scalar_set(one, "rotation", s.rotation_deg, "deg");
  }
}

void write_contacts(hid_t parent, const char* name, const ContactSnapshot& c) {
  Handle g = group(parent, name);
  number_attribute(g, "ball_contacts", c.stats.ball_contacts);
  number_attribute(g, "wall_contacts", c.stats.wall_contacts);
  number_attribute(g, "coordination", c.stats.coordination);
  number_attribute(g, "max_force", c.stats.max_force);
  number_attribute(g, "mean_force", c.stats.mean_force);
  number_attribute(g, "force_p50", c.force_p50);
  number_attribute(g, "force_p90", c.force_p90);
  number_attribute(g, "force_p99", c.force_p99);
  number_attribute(g, "sleeper_contacts", c.sleeper.contacts);
  number_attribute(g, "sleeper_bodies", c.sleeper.bodies);
  number_attribute(g, "sleeper_force_total", c.sleeper.total);
  number_attribute(g, "sleeper_force_max", c.sleeper.max);
  number_attribute(g, "sleeper_force_p50", c.sleeper.p50);
  number_attribute(g, "sleeper_force_p90", c.sleeper.p90);
  vec3_set(g, "from", c.from, "m");
  vec3_set(g, "to", c.to, "m");
  scalar_set(g, "force", c.force, "N");
}

}  // namespace

void write_box_test_result(hid_t run, const BoxTestResult& r) {
  string_attribute(run, "scene", r.scene_name);
  number_attribute(run, "bodies", r.bodies);
  number_attribute(run, "balls", r.balls);
  number_attribute(run, "dt", r.dt);
  number_attribute(run, "dt_critical", r.dt_critical);
  number_attribute(run, "wall_seconds", r.wall_seconds);
  number_attribute(run, "loaded", static_cast<long>(r.loaded));
  number_attribute(run, "porosity_grid", r.porosity_grid);
  number_attribute(run, "porosity_grid_interior", r.porosity_grid_interior);
  number_attribute(run, "bed_height", r.bed_height);
  number_attribute(run, "settlement_peak", r.settlement_peak);
  number_attribute(run, "permanent_settlement", r.permanent_settlement);
  number_attribute(run, "resilient_settlement", r.resilient_settlement);
  number_attribute(run, "max_force_error", r.max_force_error);
  number_attribute(run, "rms_force_error", r.rms_force_error);
  number_attribute(run, "max_displacement_peak", r.max_displacement_peak);
  number_attribute(run, "max_displacement_after", r.max_displacement_after);
  const std::pair<const char*, RotationStats> rotations[] = {{"loading", r.rotation_loading},
                                                             {"unloading", r.rotation_unloading},
                                                             {"cycle", r.rotation_cycle}};
  for (const auto& [phase, s] : rotations) {
    number_attribute(run, ("rotation_" + std::string(phase) + "_mean_deg").c_str(), s.mean_deg);
    number_attribute(run, ("rotation_" + std::string(phase) + "_max_deg").c_str(), s.max_deg);
  }
  const EnergyBudget& e = r.energy;
  number_attribute(run, "energy_kinetic", e.kinetic());
  number_attribute(run, "energy_elastic", e.elastic);
  number_attribute(run, "energy_gravity_work", e.gravity_work);
  number_attribute(run, "energy_wall_work", e.wall_work);
  number_attribute(run, "energy_friction", e.friction_dissipated);
  number_attribute(run, "energy_local_damping", e.damping_dissipated);
  number_attribute(run, "energy_viscous", e.viscous_dissipated);
  number_attribute(run, "energy_balance", e.balance());

  {
    Handle stages = group(run, "stages");
    for (std::size_t k = 0; k < r.stages.size(); ++k) {
      const StageReport& s = r.stages[k];
      char name[64];
      std::snprintf(name, sizeof name, "%02zu_%s", k, s.name.c_str());
      Handle g = group(stages, name);
      number_attribute(g, "steps", s.steps);
      number_attribute(g, "simulated", s.simulated);
      number_attribute(g, "seconds", s.seconds);
      number_attribute(g, "unbalanced", s.unbalanced);
      number_attribute(g, "settled", static_cast<long>(s.settled()));
      string_attribute(g, "ended_by", s.what_ended());
      number_attribute(g, "energy_in", s.energy_in);
      number_attribute(g, "energy_dissipated", s.energy_dissipated);
      number_attribute(g, "energy_error", s.energy_error);
    }
  }
  {
    Handle contacts = group(run, "contacts");
    write_contacts(contacts, "before", r.before);
    if (r.loaded) {
      Handle before(H5Gopen2(contacts, "before", H5P_DEFAULT), H5Gclose, "open contacts/before");
      write_near_pairs(before, r.near_before);
      write_contacts(contacts, "peak", r.at_peak);
      write_contacts(contacts, "after", r.after);
    }
  }
  if (r.loaded) write_cycles(run, r.cycles);
  if (r.loaded) {
    Handle z = group(run, "zones");
    number_attribute(z, "surface", r.zones.surface);
    number_attribute(z, "layer_depth", r.zones.layer_depth);
    write_zone(z, "beneath", r.zones.beneath);
    write_zone(z, "beside", r.zones.beside);
  }
  {
    Handle series = group(run, "series");
    compressed_dataset(series, "time", r.time, "s");
    compressed_dataset(series, "target_force", r.target_force, "N");
    compressed_dataset(series, "sleeper_force", r.sleeper_force, "N");
    compressed_dataset(series, "settlement", r.settlement, "m");
  }
  {
    Handle p = group(run, "particles");
    vec3_set(p, "position_start", r.position_start, "m");
    vec3_set(p, "position_peak", r.position_peak, "m");
    vec3_set(p, "position_end", r.position_end, "m");
    // Figs 15-17 draw these: displacement from the start of loading.
    vec3_set(p, "displacement_peak", difference(r.position_peak, r.position_start), "m");
    vec3_set(p, "displacement_end", difference(r.position_end, r.position_start), "m");
    scalar_set(p, "rotation_loading", r.rotation_deg_loading, "deg");
    scalar_set(p, "rotation_unloading", r.rotation_deg_unloading, "deg");
    scalar_set(p, "rotation_cycle", r.rotation_deg_cycle, "deg");
    std::vector<int> shape(r.shape_index.begin(), r.shape_index.end());
    dataset(p, "shape_index", {static_cast<hsize_t>(shape.size())}, shape, "1");
  }
  {
    Handle p = group(run, "porosity");
    scalar_set(p, "sphere_heights", r.sphere_heights, "m");
    scalar_set(p, "sphere_porosity", r.porosity_spheres, "1");
  }
  if (r.clumps) {
    // The clump templates in `ballast clump -o`'s layout (Fig. 7 from a run).
    const ClumpSampleRecord& c = *r.clumps;
    Handle g = group(run, "clumps");
    write_clump_sample(g,
                       {c.shape, "box test scene '" + r.scene_name + "'", c.params, c.mass, c.seed},
                       c.templates, c.shapes);
  }
}

void write_run_file(const std::string& path, const std::string& scene_json,
                    const BoxTestResult& r) {
  quiet_errors();
  MemoryFile file(path);
  string_attribute(file, "format", "ballast-run");
  number_attribute(file, "version", 1L);
  string_attribute(file, "scene_json", scene_json);
  {
    Handle run = group(file, "run");
    write_box_test_result(run, r);
  }
  file.save(path);
}

}  // namespace ballast
