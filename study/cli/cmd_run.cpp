#include "study/cli/cmd_run.hpp"

#include <omp.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "cases/box_test_load.hpp"
#include "cases/packing_bodies.hpp"
#include "engine/errors.hpp"
#include "study/archive/run_archive.hpp"
#include "study/build_info.hpp"
#include "study/cli/checkpoint_options.hpp"
#include "study/cli/output_paths.hpp"
#include "study/cli/run_summary.hpp"
#include "study/cli/run_vtk.hpp"

namespace ballast {

namespace {

struct RunOptions {
  std::string scene;
  std::string output;
  std::string vtk_dir;
  std::string export_packing;          // packing file of the bed after the last stage
  std::vector<std::string> overrides;  // "/numerics/rotation=full"
  int threads = 0;
  bool json = false;
  bool resume = false;               // continue from OUTPUT.checkpoint
  long checkpoint_cycles = 0;        // a checkpoint after every K-th load cycle; 0: not by cycles
  double checkpoint_minutes = 10.0;  // and at least this often (wall minutes); 0: not by time
};

// "/a/b=value": value is parsed as JSON, or taken as a string if it is not JSON.
void apply_override(nlohmann::json& j, const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || text.empty() || text[0] != '/')
    throw SetupError("invalid --set '" + text +
                     "' (allowed: /json/pointer=value, e.g. "
                     "/numerics/rotation=full)");
  nlohmann::json value;
  try {
    value = nlohmann::json::parse(text.substr(eq + 1));
  } catch (const nlohmann::json::parse_error&) {
    value = text.substr(eq + 1);
  }
  j[nlohmann::json::json_pointer(text.substr(0, eq))] = value;
}

void run(const RunOptions& o) {
  if (o.threads > 0) omp_set_num_threads(o.threads);
  std::ifstream in(o.scene);
  if (!in) throw SetupError("cannot read scene file '" + o.scene + "'");
  std::ostringstream text;
  text << in.rdbuf();
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text.str());
  } catch (const nlohmann::json::parse_error& e) {
    throw SetupError("scene file '" + o.scene + "' is not valid JSON: " + e.what());
  }
  for (const std::string& s : o.overrides) apply_override(j, s);
  BoxTestScene scene;
  try {
    scene = parse_box_test_scene(j, std::filesystem::path(o.scene).parent_path().string());
  } catch (const SetupError& e) {
    throw SetupError("scene file '" + o.scene + "': " + e.what());
  }
  // Refused now rather than after a run of many minutes.
  if (!o.output.empty()) check_writable_file("-o", o.output);
  CheckpointPlan plan;
  if (o.resume && o.output.empty())
    throw SetupError("--resume needs -o: the checkpoint it continues is OUTPUT.checkpoint");
  if (!o.output.empty()) {
    plan.path = o.output + ".checkpoint";
    plan.every_cycles = o.checkpoint_cycles;
    plan.every_minutes = o.checkpoint_minutes;
    plan.resume = o.resume;
    plan.build_id = kGitRevision;
    plan.scene_text = j.dump();
    if (!o.resume && std::filesystem::exists(plan.path))
      throw SetupError(plan.path +
                       " exists: the checkpoint of a run that did not finish. "
                       "--resume continues it; delete it to start the run again");
  }
  if (!o.vtk_dir.empty()) check_writable_directory("--vtk", o.vtk_dir);
  if (!o.export_packing.empty()) check_writable_file("--export-packing", o.export_packing);
  std::ostream* log = o.json ? &std::cerr : &std::cout;
  *log << "box test '" << scene.name << "' on " << omp_get_max_threads() << " thread(s)\n";
  const auto export_bed = [&](const Simulation& sim) {
    if (o.export_packing.empty()) return;
    const std::string after = scene.stop_after.empty()        ? "the load cycle"
                              : scene.stop_after == "prepare" ? "preparation"
                                                              : "compaction";
    write_packing_file(o.export_packing, packing_of(sim),
                       "ballast run " + o.scene + " (scene '" + scene.name + "'), after " + after);
    *log << "packing written to " << o.export_packing << "\n";
  };
  const BoxTestResult r = [&] {
    try {
      return run_box_test(scene, log, export_bed, plan);
    } catch (const SimulationError&) {
      // A blow-up is the run's answer, not an interruption: resumed, the run would meet
      // it again, so its checkpoint would only stand in the way of the next run.
      std::error_code ignored;
      std::filesystem::remove(plan.path, ignored);
      throw;
    }
  }();
  if (!o.output.empty()) {
    try {
      write_run_file(o.output, j.dump(2), r);
    } catch (const std::runtime_error& e) {
      // The last checkpoint that fitted holds the run up to where it was written.
      if (!std::filesystem::exists(plan.path)) throw;
      throw std::runtime_error(std::string(e.what()) + "; the run's last checkpoint, " + plan.path +
                               ", is kept: with room again, the same command with --resume "
                               "goes on from it");
    }
    std::error_code ignored;  // a checkpoint left behind costs disk, not results
    std::filesystem::remove(plan.path, ignored);  // the run is safe in its file now
  }
  if (!o.vtk_dir.empty()) write_run_vtk(o.vtk_dir, r);
  if (o.json)
    std::cout << run_summary_json(r).dump(2) << "\n";
  else
    print_run_summary(std::cout, r);
}

}  // namespace

void register_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Run one box test from a scene file");
  cmd->add_option("scene", o->scene, "scene file (cases/box_test/*.json)")->required();
  cmd->add_option("-o,--output", o->output, "write the run to this HDF5 file");
  cmd->add_option("--vtk", o->vtk_dir, "write ParaView files into this directory");
  cmd->add_option("--export-packing", o->export_packing,
                  "write the bed after the last stage that ran as a packing file (x y z r, or "
                  "body x y z r for clumps; docs/BOX_TEST.md)");
  cmd->add_option("--set", o->overrides, "override a scene value: /json/pointer=value");
  cmd->add_option("--threads", o->threads, "OpenMP threads (0: OMP_NUM_THREADS or all cores)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_flag("--json", o->json, "print the summary as JSON (progress goes to stderr)");
  cmd->add_flag("--resume", o->resume,
                "continue a killed run from OUTPUT.checkpoint (bit for bit), or start it "
                "when there is none");
  add_checkpoint_options(cmd, o->checkpoint_cycles, o->checkpoint_minutes,
                         "OUTPUT.checkpoint (with -o)");
  cmd->callback([o] { run(*o); });
}

}  // namespace ballast
