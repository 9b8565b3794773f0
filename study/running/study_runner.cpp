#include "study/running/study_runner.hpp"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "cases/box_test_load.hpp"
#include "cases/shared_bed.hpp"
#include "study/archive/study_store.hpp"
#include "study/archive/study_summary.hpp"
#include "study/build_info.hpp"
#include "study/matrix/study_json.hpp"
#include "study/matrix/study_scene.hpp"
#include "study/running/run_log.hpp"
#include "study/running/shared_beds.hpp"
#include "study/running/stop_signals.hpp"
#include "study/running/study_progress.hpp"

namespace ballast {

namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

struct PreparedRun {
  const RunSpec* spec = nullptr;
  BoxTestScene scene;
  std::string scene_json;
  std::string bed_text;  // what its prepared bed depends on (cases/shared_bed.hpp)
};

// The study file, its base scene and every run's scene, all checked: whatever is wrong
// is thrown (StudyError) here, before an archive exists.
struct PreparedStudy {
  StudySpec spec;
  std::string study_text, scene_text;
  json base_scene;
  std::vector<PreparedRun> runs;  // every run of the study, in study order
};

PreparedStudy prepare(const std::string& study_file) {
  PreparedStudy p;
  p.study_text = read_study_text(study_file);
  p.spec = load_study_file(study_file);
  const std::string where = "scene = \"" + p.spec.scene + "\"";
  std::ifstream in(p.spec.scene_path);
  if (!in) {
    throw StudyError(study_file, "/scene",
                     where + " cannot be read (looked for " + p.spec.scene_path + ")",
                     "a scene file, relative to the study file's folder");
  }
  std::ostringstream text;
  text << in.rdbuf();
  p.scene_text = text.str();
  try {
    p.base_scene = json::parse(p.scene_text);
    parse_box_test_scene(p.base_scene);
  } catch (const json::parse_error& e) {
    throw StudyError(study_file, "/scene", where + " is not valid JSON: " + e.what(),
                     "a scene file (docs/BOX_TEST.md)");
  } catch (const SetupError& e) {
    throw StudyError(study_file, "/scene", where + ": " + e.what(), "");
  }
  p.runs.reserve(p.spec.runs.size());
  for (const RunSpec& r : p.spec.runs) {
    const json scene = run_scene_json(p.base_scene, r);
    p.runs.push_back({&r, parse_run_scene(scene, r, study_file, p.spec.scene), scene.dump(2),
                      bed_defining_text(scene)});
  }
  return p;
}

// What a run costs, roughly: its balls. A ball-step in a clump bed costs less than in
// a sphere bed but its timestep is shorter (docs/PERFORMANCE.md), so balls it is.
double estimated_cost(const PreparedRun& r) {
  const double balls_per_body = r.scene.clumps ? expected_ball_count(*r.scene.clumps) : 1.0;
  return double(r.scene.count) * balls_per_body;
}

// One run from start to end. Whatever it throws is its failure, recorded with the
// message; the study goes on.
RunRecord execute(const PreparedRun& run, int threads, ProgressBoard& board,
                  CheckpointPlan checkpoints) {
  RunRecord r;
  r.spec = *run.spec;
  r.threads = threads;
  r.git_revision = kGitRevision;
  r.scene_json = run.scene_json;
  r.started = iso8601_utc(std::chrono::system_clock::now());
  const auto start = Clock::now();
  RunLog log([&](const std::string& line) { board.log_line(*run.spec, line); });
  board.started(*run.spec, threads);
  try {
    checkpoints.scene_text = run.scene_json;
    checkpoints.log_text = [&log] { return log.text(); };
    r.result = run_box_test(run.scene, &log.stream(), {}, checkpoints);
    r.ok = true;
  } catch (const SimulationError& e) {
    r.message = std::string("blew up: ") + e.what();
  } catch (const SetupError& e) {
    r.message = std::string("refused by the box test: ") + e.what();
  } catch (const std::exception& e) {
    r.message = std::string("error: ") + e.what();
  }
  r.finished = iso8601_utc(std::chrono::system_clock::now());
  r.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  r.log = log.text();
  return r;
}

// Where run `run` keeps its checkpoint: beside the parts, which a finished study removes.
CheckpointPlan checkpoint_plan(const StudyOptions& o, const StudyStore& store,
                               const PreparedRun& run) {
  CheckpointPlan plan;
  char name[32];
  std::snprintf(name, sizeof name, "/%06zu.checkpoint", run.spec->index);
  plan.path = store.parts_dir() + name;
  plan.every_cycles = o.checkpoint_cycles;
  plan.every_minutes = o.checkpoint_minutes;
  plan.resume = o.resume;
  plan.build_id = kGitRevision;
  return plan;
}

void print_dry_run(const PreparedStudy& p, const std::vector<const PreparedRun*>& todo,
                   const Shard& shard, const Parallelism& plan) {
  std::cout << "study '" << p.spec.name << "': " << p.spec.runs.size() << " runs, scene "
            << p.spec.scene_path << "; shard " << shard.text() << ": " << todo.size() << " runs, "
            << plan.jobs << " side by side x " << plan.threads << " thread(s)\n";
  for (const PreparedRun* r : todo) {
    std::cout << "  " << r->spec->index << "  " << r->spec->id << "  seed " << r->spec->seed << "  "
              << r->spec->params.dump() << "\n";
  }
  std::cout << "dry run: every scene checked, nothing run or written\n";
}

// The shard's runs not yet in the archive (and, with --retry-failed, those that
// failed), dearest first: with fewer slots than runs the dearest run no longer starts
// last and leaves the other slots idle while it finishes (the default study: Sample
// 2 alone took as long as the other two together). Where each run's record goes does
// not depend on the order.
struct RunsToDo {
  std::vector<const PreparedRun*> runs;
  std::size_t archived = 0, retried = 0;
};

RunsToDo runs_to_do(const StudyStore& store, const std::vector<const PreparedRun*>& in_shard,
                    bool retry_failed) {
  RunsToDo t;
  for (const PreparedRun* r : in_shard) {
    const auto it = store.recorded().find(r->spec->id);
    const bool found = it != store.recorded().end();
    const bool retry = found && retry_failed && !it->second;
    t.archived += found ? 1 : 0;
    t.retried += retry ? 1 : 0;
    if (!found || retry) t.runs.push_back(r);
  }
  // At the same cost, a run that may start from another's bed (docs/STUDY.md, "Shared
  // beds") goes after the runs that prepare their own, so that its bed is ready.
  std::set<std::string> beds;
  std::map<const PreparedRun*, bool> shares;
  for (const PreparedRun* r : t.runs) shares[r] = !beds.insert(r->bed_text).second;
  std::stable_sort(t.runs.begin(), t.runs.end(),
                   [&shares](const PreparedRun* a, const PreparedRun* b) {
                     const double ca = estimated_cost(*a), cb = estimated_cost(*b);
                     return ca != cb ? ca > cb : shares[a] < shares[b];
                   });
  return t;
}

// Until `done`: watches the signals and redraws the live board. SIGINT once: no new
// run starts, those in flight finish. SIGTERM, or SIGINT again: exit now, once no
// write is in progress (the archive is closed between writes), losing only the runs
// in flight.
void watch_signals(ProgressBoard& board, StudyStore& store, const std::atomic<bool>& done,
                   bool live, const std::string& output) {
  int seen = 0;
  auto drawn = Clock::now();
  while (!done.load()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const int n = StopSignals::count();
    if (n > seen) {
      seen = n;
      const int sig = StopSignals::last();
      if (sig == SIGINT && n == 1) {
        board.note("interrupted (SIGINT): no new run starts; the " +
                   std::to_string(board.in_flight()) +
                   " in flight finish and are kept (Ctrl-C again abandons them)");
      } else {
        board.note(std::string("interrupted (") + (sig == SIGINT ? "SIGINT" : "SIGTERM") +
                   "): abandoning the " + std::to_string(board.in_flight()) +
                   " runs in flight; every finished run is in " + output +
                   ": run the same command with --resume to finish the study");
        std::lock_guard<std::mutex> lock(store.write_mutex());
        std::cout.flush();
        std::fflush(nullptr);
        std::_Exit(128 + sig);
      }
    }
    if (live && Clock::now() - drawn > std::chrono::milliseconds(500)) {
      board.redraw();
      drawn = Clock::now();
    }
  }
}

// Completes the archive and prints its summary; the exit code says whether any run
// of the archive failed.
int finish_study(StudyStore& store, const std::string& output, std::size_t study_runs,
                 const Shard& shard) {
  store.finish();
  const std::vector<SummaryRow> rows = read_summary(output);
  std::cout << "\n";
  print_summary(std::cout, rows);
  std::size_t failed = 0;
  for (const SummaryRow& r : rows) failed += r.ok ? 0 : 1;
  std::cout << "\n"
            << output << ": " << rows.size() << " of " << study_runs << " runs of the study"
            << (shard.whole() ? "" : " (shard " + shard.text() + ")") << ", " << failed
            << " failed\n";
  return failed > 0 ? kStudyExitRunsFailed : 0;
}

}  // namespace

int run_study(const StudyOptions& o) {
  if (o.retry_failed && !o.resume) {
    throw SetupError(
        "invalid --retry-failed without --resume (allowed: with --resume, to run "
        "the failed runs of an archive again)");
  }
  const Shard shard = parse_shard(o.shard);
  const PreparedStudy p = prepare(o.study_file);
  std::vector<const PreparedRun*> in_shard;
  for (const PreparedRun& r : p.runs) {
    if (shard.contains(r.spec->index)) in_shard.push_back(&r);
  }
  const int cores = omp_get_max_threads();  // OMP_NUM_THREADS, else every core
  if (o.dry_run) {
    print_dry_run(p, in_shard, shard, plan_parallelism(cores, in_shard.size(), o.jobs, o.threads));
    return 0;
  }

  const bool live = o.progress == "live" || (o.progress == "auto" && isatty(STDOUT_FILENO));
  std::mutex early_mutex;
  ProgressBoard* board_ptr = nullptr;
  // Until the board exists, reports go straight to stdout.
  const auto report = [&](const std::string& text) {
    if (board_ptr) {
      board_ptr->note(text);
    } else {
      std::lock_guard<std::mutex> lock(early_mutex);
      std::cout << text << "\n" << std::flush;
    }
  };
  const StudyArchiveHeader header =
      make_archive_header(p.spec, p.study_text, p.scene_text, p.base_scene, shard);
  const std::filesystem::path folder = std::filesystem::path(o.output).parent_path();
  if (!folder.empty()) std::filesystem::create_directories(folder);
  std::unique_ptr<StudyStore> store = o.resume ? StudyStore::resume(o.output, header, report)
                                               : StudyStore::create(o.output, header, report);
  const RunsToDo to_do = runs_to_do(*store, in_shard, o.retry_failed);
  const std::vector<const PreparedRun*>& todo = to_do.runs;
  const std::size_t archived = to_do.archived, retried = to_do.retried;
  std::size_t other_builds = 0;  // runs another build made: results may not match ours
  for (const auto& [id, revision] : store->revisions()) other_builds += revision != kGitRevision;
  if (other_builds > 0) {
    report("note: " + std::to_string(other_builds) + " runs in " + o.output +
           " were made by another build (git_revision differs from " + kGitRevision +
           "): each run's git_revision attribute says which");
  }
  const Parallelism plan = plan_parallelism(cores, todo.size(), o.jobs, o.threads);
  std::cout << "study '" << p.spec.name << "' (" << p.spec.runs.size() << " runs, shard "
            << shard.text() << ": " << in_shard.size() << "): " << archived << " in the archive"
            << (retried ? " (" + std::to_string(retried) + " failed, run again)" : "") << ", "
            << todo.size() << " to run, " << plan.jobs << " side by side x " << plan.threads
            << " thread(s) on " << cores << " core(s); " << kProgramName << " " << kProgramVersion
            << " (" << kGitRevision << ")\n"
            << std::flush;

  std::vector<std::string> bed_texts;
  for (const PreparedRun* r : todo) bed_texts.push_back(r->bed_text);
  SharedBeds beds(bed_texts, store->parts_dir());
  if (beds.receivers() > 0) {
    std::cout << "shared beds: " << beds.receivers() << " runs may start from " << beds.beds()
              << " beds that other runs prepare (the same scene but for its loading, the same "
                 "seed: docs/STUDY.md)\n"
              << std::flush;
  }
  ProgressBoard board(std::cout, live, todo.size(), archived - retried, plan.jobs);
  board_ptr = &board;
  std::exception_ptr failure;
  std::mutex failure_mutex;
  std::atomic<bool> stop{false}, done{false};
  {
    StopSignals signals;
    std::thread monitor([&] { watch_signals(board, *store, done, live, o.output); });

    omp_set_max_active_levels(2);
#pragma omp parallel for schedule(dynamic, 1) num_threads(plan.jobs)
    for (long k = 0; k < static_cast<long>(todo.size()); ++k) {
      if (stop.load() || StopSignals::count() > 0) continue;
      omp_set_num_threads(plan.threads);  // this run's engine: its own inner team
      try {
        const std::size_t at = static_cast<std::size_t>(k);
        const PreparedRun& run = *todo[at];
        CheckpointPlan checkpoints = checkpoint_plan(o, *store, run);
        beds.assign(at, checkpoints);
        const RunRecord r = execute(run, plan.threads, board, checkpoints);
        store->record(r);
        std::error_code ignored;  // the part holds the run; the study's end clears the rest
        std::filesystem::remove(checkpoints.path, ignored);
        beds.ended(at);
        board.finished(r);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        stop.store(true);
      }
    }
    done.store(true);
    monitor.join();
  }
  board.close();
  board_ptr = nullptr;
  if (failure) std::rethrow_exception(failure);
  if (StopSignals::count() > 0) {
    std::cout << "interrupted (SIGINT): the finished runs are in " << o.output
              << "; run the same command with --resume to finish the study\n";
    return 128 + SIGINT;
  }
  return finish_study(*store, o.output, p.spec.runs.size(), shard);
}

}  // namespace ballast
