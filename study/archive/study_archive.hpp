// The study archive's layout (docs/ARCHIVE.md): the root attributes that say which
// study it holds, and one group per run under /runs. How runs get there safely
// (parts, resume) is study_store.hpp's business; this file only reads and writes.
//
//   /                 format = "ballast-study", format_version = 1, study_name,
//                     study_json, study_seed, run_count, fingerprint, program_version,
//                     git_revision, scene_path, scene_json, shard_index, shard_count,
//                     created, merged_from
//   /study_runs       every run of the study as JSON text (index, id, sample,
//                     replicate, seed, params), also those not in this archive
//   /runs/<id>        id, index, sample, params, seed, replicate, status, message,
//                     started, finished, wall_seconds, threads, git_revision,
//                     scene_json; dataset log; for an ok run everything
//                     write_box_test_result() writes (study/archive/run_archive.hpp)
#pragma once

#include <hdf5.h>

#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cases/box_test_result.hpp"
#include "study/archive/hdf5_util.hpp"
#include "study/matrix/study_matrix.hpp"
#include "study/matrix/study_plan.hpp"

namespace ballast {

inline constexpr const char* kStudyArchiveFormat = "ballast-study";
inline constexpr const char* kRunPartFormat = "ballast-study-part";
inline constexpr long kStudyArchiveVersion = 1;

// An archive that must not be used as it is: another study's, damaged, or in the way.
// A SetupError, so the command line exits 2 (nothing was changed).
struct ArchiveRefused : SetupError {
  using SetupError::SetupError;
};

struct StudyArchiveHeader {
  std::string study_name;
  std::string study_json;  // the study file's bytes, verbatim
  std::uint64_t study_seed = 0;
  long long run_count = 0;  // runs in the whole study, whatever the shard
  std::string fingerprint;  // study_fingerprint()
  std::string program_version, git_revision;
  std::string scene_path;  // the base scene as the study file names it
  std::string scene_json;  // the base scene file's text
  Shard shard;
  std::string created;      // ISO 8601 UTC
  std::string merged_from;  // `ballast merge`'s inputs, one per line; empty otherwise
  std::string runs_json;    // /study_runs
};

// What one run left: its spec, how it ended, and (ok) its result.
struct RunRecord {
  RunSpec spec;
  bool ok = false;
  std::string message;  // why it failed; empty when ok
  std::string started, finished;
  // s, the runner's clock over this attempt only: after a resume, the part since it.
  // A finished run's whole time, the parts before included, is result->wall_seconds.
  double wall_seconds = 0.0;
  int threads = 1;
  std::string git_revision;
  std::string scene_json;               // the scene the run ran (run_scene_json), for `ballast run`
  std::string log;                      // everything run_box_test wrote to its log
  std::optional<BoxTestResult> result;  // set when ok
};

// What the archive says about one of its runs.
struct ArchivedRun {
  std::string id;
  long long index = 0;
  bool ok = false;
  std::string message, finished, git_revision;
};

// 16 hex digits of FNV-1a over the expanded runs (index, id, params, seed, replicate)
// and the base scene's content (parsed and re-serialised, so formatting does not
// count). Name, description and notes do not enter: editing them does not block
// --resume or merge.
std::string study_fingerprint(const StudySpec& spec, const nlohmann::json& base_scene);

// The header of an archive about to hold `shard` of `spec`.
StudyArchiveHeader make_archive_header(const StudySpec& spec, const std::string& study_text,
                                       const std::string& scene_text,
                                       const nlohmann::json& base_scene, const Shard& shard);

// File access for archives and parts: the HDF5 1.10 file format (superblock 3), in
// which a writer that dies with the file open leaves it marked, so that the next open
// fails ("file is already open for write") instead of reading half-written metadata.
h5::Handle archive_file_access();

void write_archive_header(hid_t file, const StudyArchiveHeader& header);
// Throws ArchiveRefused when `file` is not a study archive of kStudyArchiveVersion.
StudyArchiveHeader read_archive_header(hid_t file, const std::string& path);

// Writes one run into `group` (already created).
void write_run_group(hid_t group, const RunRecord& record);
// Every group under /runs with its status, in name order; throws ArchiveRefused naming
// the first group without an id, index or status attribute (a damaged archive).
std::vector<ArchivedRun> read_archived_runs(hid_t file, const std::string& path);
ArchivedRun read_archived_run(hid_t group, const std::string& where);

// "2024-05-01T12:34:56Z".
std::string iso8601_utc(std::chrono::system_clock::time_point t);

}  // namespace ballast
