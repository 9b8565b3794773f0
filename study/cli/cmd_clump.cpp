#include "study/cli/cmd_clump.hpp"

#include <omp.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cases/clump_presets.hpp"
#include "engine/clump_batch.hpp"
#include "engine/clump_param_table.hpp"
#include "engine/clump_shape.hpp"
#include "study/archive/clump_archive.hpp"
#include "study/cli/clump_vtk.hpp"
#include "study/cli/output_paths.hpp"

namespace ballast {
namespace {

struct ClumpCommandOptions {
  std::string preset;
  std::string params_file;
  std::string adjacency;  // empty: as in the preset
  long count = 1000;
  std::uint64_t seed = 1;
  std::string mass = "uniform";
  double accuracy = 0.005;
  int threads = 0;
  bool json = false;
  bool list = false;
  std::string output;
  std::string vtk_dir;
};

// One row of the summary: a statistic in display units.
struct Row {
  const char* key;    // JSON name (SI units)
  const char* label;  // table label (display units)
  double scale;       // display = SI * scale
  StatSummary stat;
};

std::vector<Row> summary_rows(const std::vector<ClumpTemplate>& clumps,
                              const ClumpShapeSummary& s) {
  std::vector<double> mass, i1, i2, i3, err;
  for (const ClumpTemplate& t : clumps) {
    mass.push_back(t.mass);
    i1.push_back(t.principal_inertia[0]);
    i2.push_back(t.principal_inertia[1]);
    i3.push_back(t.principal_inertia[2]);
    err.push_back(t.integration_error);
  }
  return {
      {"balls", "balls per clump", 1.0, s.balls},
      {"mass_kg", "mass (g)", 1e3, summarize(mass)},
      {"union_volume_m3", "union volume (cm^3)", 1e6, s.union_volume},
      {"surface_area_m2", "surface area (cm^2)", 1e4, s.surface_area},
      {"sphericity", "sphericity (Wadell)", 1.0, s.sphericity},
      {"a_m", "a, longest extent (mm)", 1e3, s.a},
      {"b_m", "b, middle extent (mm)", 1e3, s.b},
      {"c_m", "c, shortest extent (mm)", 1e3, s.c},
      {"elongation", "elongation b/a", 1.0, s.elongation},
      {"flatness", "flatness c/b", 1.0, s.flatness},
      {"volume_ratio", "union / virtual sphere vol.", 1.0, s.volume_ratio},
      {"inertia_1_kgm2", "I1 (kg m^2 x 1e-6)", 1e6, summarize(i1)},
      {"inertia_2_kgm2", "I2 (kg m^2 x 1e-6)", 1e6, summarize(i2)},
      {"inertia_3_kgm2", "I3 (kg m^2 x 1e-6)", 1e6, summarize(i3)},
      {"integration_error", "uniform-mode error estimate", 1.0, summarize(err)},
  };
}

// What the command measured, for the two ways it prints it.
struct ClumpReport {
  const ClumpPreset& preset;
  const ClumpMassOptions& mass;
  const ClumpCommandOptions& o;
  const ClumpShapeSummary& summary;
  const std::vector<Row>& rows;
  double seconds;         // s, generation and measurement
  double expected;        // balls per clump, 1 + p N n + p^2 E m
  double standard_error;  // of the measured mean ball count

  // The paper's balls per clump for the sample, where the preset gives its counts.
  std::optional<double> paper_balls_per_clump() const {
    if (!preset.paper_clumps) return std::nullopt;
    return static_cast<double>(*preset.paper_balls) / *preset.paper_clumps;
  }
};

void print_clump_json(const ClumpReport& c) {
  const ClumpPreset& preset = c.preset;
  const ClumpParams& q = preset.params;
  const ClumpMassOptions& mass = c.mass;
  const ClumpCommandOptions& o = c.o;
  const std::optional<double> paper_mean = c.paper_balls_per_clump();
  nlohmann::ordered_json j;
  j["preset"] = preset.name;
  j["source"] = preset.source;
  // Every parameter by its table name (lengths in metres carry "_m").
  nlohmann::ordered_json& params = j["parameters"];
  for (const ClumpParamField& f : clump_param_fields()) {
    const std::string key = std::string(f.name) + (f.unit == "m" ? "_m" : "");
    if (f.kind == ClumpParamKind::kInteger) params[key] = static_cast<int>(f.value(q));
    if (f.kind == ClumpParamKind::kNumber) params[key] = f.value(q);
    if (f.kind == ClumpParamKind::kChoice) params[key] = f.text(q);
  }
  params["central_radius_m"] = central_ball_radius(q);
  params["virtual_radius_m"] = virtual_sphere_radius(q);
  j["mass"] = {{"mode", mass_mode_name(mass.mode)},
               {"density_kg_m3", mass.density},
               {"accuracy", mass.accuracy}};
  j["count"] = o.count;
  j["seed"] = o.seed;
  j["threads"] = omp_get_max_threads();
  j["seconds"] = c.seconds;
  j["expected_balls_per_clump"] = c.expected;
  j["balls_per_clump_standard_error"] = c.standard_error;
  if (paper_mean) {
    j["paper"] = {{"clumps", *preset.paper_clumps},
                  {"balls", *preset.paper_balls},
                  {"balls_per_clump", *paper_mean}};
  }
  for (const Row& r : c.rows) {
    j["statistics"][r.key] = {
        {"mean", r.stat.mean}, {"min", r.stat.min}, {"max", r.stat.max}, {"stddev", r.stat.stddev}};
  }
  std::cout << j.dump(2) << "\n";
}

void print_clump_text(const ClumpReport& c) {
  const ClumpPreset& preset = c.preset;
  const ClumpParams& q = preset.params;
  const ClumpMassOptions& mass = c.mass;
  const ClumpCommandOptions& o = c.o;
  const std::optional<double> paper_mean = c.paper_balls_per_clump();
  std::printf("clumps: %s%s%s\n", preset.name.c_str(), preset.source.empty() ? "" : " - ",
              preset.source.c_str());
  std::printf(
      "  %d directions (%s adjacency), p %.2f, %d balls/direction, c %.2f R, "
      "D3 %.2f R, %d edge balls\n",
      q.directions, adjacency_name(q.adjacency), q.p, q.balls_per_direction, q.c, q.d3,
      q.edge_balls);
  std::printf(
      "  nominal diameter %.2f mm, virtual sphere Rv = %.2f x %.3f mm = %.3f mm, "
      "central ball R = %.3f mm\n",
      q.nominal_diameter * 1e3, q.virtual_sphere_factor, q.nominal_diameter * 500.0,
      virtual_sphere_radius(q) * 1e3, central_ball_radius(q) * 1e3);
  char accuracy[48] = "";
  if (mass.mode == MassMode::kUniform) {
    std::snprintf(accuracy, sizeof accuracy, ", accuracy %g", mass.accuracy);
  }
  std::printf(
      "  mass mode %s, density %.0f kg/m^3%s; %ld clumps, seed %llu, %d threads, "
      "%.2f s\n\n",
      mass_mode_name(mass.mode), mass.density, accuracy, o.count,
      static_cast<unsigned long long>(o.seed), omp_get_max_threads(), c.seconds);
  std::printf("  %-30s %12s %12s %12s\n", "statistic", "mean", "min", "max");
  for (const Row& r : c.rows) {
    if (mass.mode != MassMode::kUniform && std::string(r.key) == "integration_error") continue;
    std::printf("  %-30s %12.4g %12.4g %12.4g\n", r.label, r.stat.mean * r.scale,
                r.stat.min * r.scale, r.stat.max * r.scale);
  }
  std::printf(
      "\n  balls per clump: measured %.3f +- %.3f (standard error), expected %.3f "
      "(1 + p N n + p^2 E m)",
      c.summary.balls.mean, c.standard_error, c.expected);
  if (paper_mean) {
    std::printf(", paper %.3f (%d balls / %d clumps)", *paper_mean, *preset.paper_balls,
                *preset.paper_clumps);
  }
  std::printf("\n");
}

void run_clump_command(const ClumpCommandOptions& o) {
  if (o.list) {
    for (const std::string& name : available_clump_presets()) std::cout << name << "\n";
    return;
  }
  if (o.preset.empty() == o.params_file.empty()) {
    throw CLI::ValidationError("clump", "give exactly one of --preset NAME or --params FILE.json");
  }
  ClumpPreset preset =
      o.preset.empty() ? load_clump_params_file(o.params_file) : load_clump_preset(o.preset);
  if (!o.adjacency.empty()) preset.params.adjacency = parse_adjacency(o.adjacency);
  ClumpMassOptions mass;
  mass.mode = parse_mass_mode(o.mass);
  mass.density = preset.density;
  mass.accuracy = o.accuracy;
  if (o.threads > 0) omp_set_num_threads(o.threads);

  const ClumpParams& q = preset.params;
  if (!o.output.empty()) check_writable_file("-o", o.output);
  if (!o.vtk_dir.empty()) check_writable_directory("--vtk", o.vtk_dir);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<ClumpTemplate> clumps =
      generate_clump_templates(q, mass, static_cast<std::size_t>(o.count), o.seed);
  const std::vector<ClumpShape> shapes =
      measure_clump_shapes(clumps, virtual_sphere_radius(q), ClumpShapeOptions{});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const ClumpShapeSummary summary = summarize_shapes(shapes);
  const std::vector<Row> rows = summary_rows(clumps, summary);

  const double standard_error = summary.balls.stddev / std::sqrt(static_cast<double>(o.count));
  const ClumpReport report{preset,        mass, o, summary, rows, seconds, expected_ball_count(q),
                           standard_error};
  if (o.json)
    print_clump_json(report);
  else
    print_clump_text(report);

  if (!o.output.empty()) {
    write_clump_archive(o.output, ClumpArchiveHeader{preset.name, preset.source, q, mass, o.seed},
                        clumps, shapes);
    if (!o.json) std::printf("  wrote %s\n", o.output.c_str());
  }
  if (!o.vtk_dir.empty()) {
    const std::string path = write_clump_vtk(o.vtk_dir, clumps, virtual_sphere_radius(q),
                                             preset.name + ", seed " + std::to_string(o.seed));
    if (!o.json) std::printf("  wrote %s\n", path.c_str());
  }
}

}  // namespace

void register_clump_command(CLI::App& app) {
  auto o = std::make_shared<ClumpCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "clump", "Generate clumps (Lu & McDowell 2007 section 2) and print their statistics");
  auto* preset =
      cmd->add_option("--preset", o->preset, "named preset, e.g. table2/sample1 (see --list)");
  auto* params = cmd->add_option("--params", o->params_file,
                                 "JSON file of clump parameters (format: docs/CLUMPS.md)");
  preset->excludes(params);
  cmd->add_flag("--list", o->list, "list the named presets and exit");
  cmd->add_option("--count", o->count, "number of clumps")
      ->check(CLI::Range(1L, 100000000L))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "seed; clump i uses its own stream (seed, i)")
      ->capture_default_str();
  cmd->add_option("--mass", o->mass,
                  "mass properties: sum (PFC3D 3.x), paper (eqs 10-15), "
                  "uniform (union of the balls)")
      ->check(CLI::IsMember({"sum", "paper", "uniform"}))
      ->capture_default_str();
  cmd->add_option("--accuracy", o->accuracy, "uniform mode's relative accuracy")
      ->check(CLI::Range(1e-5, 0.1))
      ->capture_default_str();
  cmd->add_option("--adjacency", o->adjacency,
                  "override which direction pairs get edge balls: hull or face_to_diagonal")
      ->check(CLI::IsMember({"hull", "face_to_diagonal"}));
  cmd->add_option("--threads", o->threads, "OpenMP threads (0: OMP_NUM_THREADS or all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--json", o->json, "print the summary as JSON");
  cmd->add_option("-o,--output", o->output, "write the clumps to this HDF5 file");
  cmd->add_option("--vtk", o->vtk_dir, "write DIR/clumps.vtk for ParaView");
  cmd->callback([o] { run_clump_command(*o); });
}

}  // namespace ballast
