// `ballast study STUDY.json -o ARCHIVE.h5`: every run of a study (or of one shard),
// side by side with OpenMP, into one archive (docs/STUDY.md "Running a study",
// docs/ARCHIVE.md).
//
// Exit codes (kStudyExit*): 0 every run ok; 2 bad input or an archive refused,
// nothing ran; 3 finished, some runs failed (listed); 128 + signal (130 SIGINT, 143
// SIGTERM) interrupted: --resume finishes; 1 anything else (an I/O error).
#pragma once

#include <string>

namespace ballast {

inline constexpr int kStudyExitRunsFailed = 3;

struct StudyOptions {
  std::string study_file;
  std::string output;
  int jobs = 0;     // 0: decided from the cores and the runs (plan_parallelism)
  int threads = 0;  // 0: likewise
  std::string shard = "1/1";
  bool resume = false;
  bool retry_failed = false;  // with --resume: run the failed runs again
  // Each run's load cycles write ARCHIVE.parts/NNNNNN.checkpoint after every K-th cycle
  // and at least every M wall minutes; --resume continues a run in flight from it.
  long checkpoint_cycles = 0;
  double checkpoint_minutes = 10.0;
  bool dry_run = false;           // check everything, list the runs, write nothing
  std::string progress = "auto";  // "auto" (live on a terminal), "live" or "plain"
};

// Runs the study; returns the exit code. Bad input throws SetupError (StudyError,
// ArchiveRefused) before anything runs or is written.
int run_study(const StudyOptions& options);

}  // namespace ballast
