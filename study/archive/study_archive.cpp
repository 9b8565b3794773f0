#include "study/archive/study_archive.hpp"

#include <cstdio>
#include <ctime>

#include "study/archive/hdf5_read.hpp"
#include "study/archive/run_archive.hpp"
#include "study/build_info.hpp"
#include "study/matrix/run_identity.hpp"

namespace ballast {

using namespace h5;
using nlohmann::json;

namespace {

json runs_table(const StudySpec& spec) {
  json runs = json::array();
  for (const RunSpec& r : spec.runs) {
    // The seed as text: JSON readers that hold numbers as doubles (Python's does not,
    // but many do) would round a 64-bit seed.
    runs.push_back({{"index", r.index},
                    {"id", r.id},
                    {"sample", r.sample},
                    {"replicate", r.replicate},
                    {"seed", std::to_string(r.seed)},
                    {"params", r.params}});
  }
  return runs;
}

std::string text_or_empty(hid_t target, const char* name) {
  return has_attribute(target, name) ? read_text_attribute(target, name) : std::string();
}

}  // namespace

std::string study_fingerprint(const StudySpec& spec, const json& base_scene) {
  json runs = json::array();
  for (const RunSpec& r : spec.runs) {
    runs.push_back({r.index, r.id, r.params, std::to_string(r.seed), r.replicate});
  }
  const json content = {
      {"format_version", kStudyArchiveVersion}, {"runs", runs}, {"scene", base_scene}};
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx",
                static_cast<unsigned long long>(fnv1a64(content.dump())));
  return hex;
}

StudyArchiveHeader make_archive_header(const StudySpec& spec, const std::string& study_text,
                                       const std::string& scene_text, const json& base_scene,
                                       const Shard& shard) {
  StudyArchiveHeader h;
  h.study_name = spec.name;
  h.study_json = study_text;
  h.study_seed = spec.seed;
  h.run_count = static_cast<long long>(spec.runs.size());
  h.fingerprint = study_fingerprint(spec, base_scene);
  h.program_version = kProgramVersion;
  h.git_revision = kGitRevision;
  h.scene_path = spec.scene;
  h.scene_json = scene_text;
  h.shard = shard;
  h.created = iso8601_utc(std::chrono::system_clock::now());
  h.runs_json = runs_table(spec).dump();
  return h;
}

Handle archive_file_access() {
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, "create file access properties");
  check(H5Pset_libver_bounds(fapl, H5F_LIBVER_V110, H5F_LIBVER_LATEST),
        "ask for the HDF5 1.10 file format");
  return fapl;
}

void write_archive_header(hid_t file, const StudyArchiveHeader& h) {
  string_attribute(file, "format", kStudyArchiveFormat);
  number_attribute(file, "format_version", kStudyArchiveVersion);
  string_attribute(file, "study_name", h.study_name);
  string_attribute(file, "study_json", h.study_json);
  number_attribute(file, "study_seed", h.study_seed);
  number_attribute(file, "run_count", h.run_count);
  string_attribute(file, "fingerprint", h.fingerprint);
  string_attribute(file, "program_version", h.program_version);
  string_attribute(file, "git_revision", h.git_revision);
  string_attribute(file, "scene_path", h.scene_path);
  string_attribute(file, "scene_json", h.scene_json);
  number_attribute(file, "shard_index", static_cast<long long>(h.shard.index));
  number_attribute(file, "shard_count", static_cast<long long>(h.shard.count));
  string_attribute(file, "created", h.created);
  string_attribute(file, "merged_from", h.merged_from);
  text_dataset(file, "study_runs", h.runs_json);
}

StudyArchiveHeader read_archive_header(hid_t file, const std::string& path) {
  if (text_or_empty(file, "format") != kStudyArchiveFormat) {
    throw ArchiveRefused(path + " is not a study archive (its root attribute format is \"" +
                         text_or_empty(file, "format") + "\", not \"" + kStudyArchiveFormat +
                         "\")");
  }
  const long long version = read_int_attribute(file, "format_version");
  if (version != kStudyArchiveVersion) {
    throw ArchiveRefused(path + " has archive format_version " + std::to_string(version) +
                         "; this program reads version " + std::to_string(kStudyArchiveVersion));
  }
  StudyArchiveHeader h;
  h.study_name = read_text_attribute(file, "study_name");
  h.study_json = read_text_attribute(file, "study_json");
  h.study_seed = read_uint64_attribute(file, "study_seed");
  h.run_count = read_int_attribute(file, "run_count");
  h.fingerprint = read_text_attribute(file, "fingerprint");
  h.program_version = read_text_attribute(file, "program_version");
  h.git_revision = read_text_attribute(file, "git_revision");
  h.scene_path = read_text_attribute(file, "scene_path");
  h.scene_json = read_text_attribute(file, "scene_json");
  h.shard.index = static_cast<int>(read_int_attribute(file, "shard_index"));
  h.shard.count = static_cast<int>(read_int_attribute(file, "shard_count"));
  h.created = read_text_attribute(file, "created");
  h.merged_from = read_text_attribute(file, "merged_from");
  h.runs_json = read_text_dataset(file, "study_runs");
  return h;
}

void write_run_group(hid_t g, const RunRecord& r) {
  string_attribute(g, "id", r.spec.id);
  number_attribute(g, "index", static_cast<long long>(r.spec.index));
  string_attribute(g, "sample", r.spec.sample);
  string_attribute(g, "params", r.spec.params.dump());
  number_attribute(g, "seed", r.spec.seed);
  number_attribute(g, "replicate", static_cast<long long>(r.spec.replicate));
  string_attribute(g, "status", r.ok ? "ok" : "failed");
  string_attribute(g, "message", r.message);
  string_attribute(g, "started", r.started);
  string_attribute(g, "finished", r.finished);
  number_attribute(g, "threads", static_cast<long long>(r.threads));
  string_attribute(g, "git_revision", r.git_revision);
  string_attribute(g, "scene_json", r.scene_json);
  text_dataset(g, "log", r.log);
  if (r.ok) {
    // The single writer of a run's measurements; it writes wall_seconds (the box
    // test's own time) among them.
    write_box_test_result(g, *r.result);
  } else {
    number_attribute(g, "wall_seconds", r.wall_seconds);
  }
}

ArchivedRun read_archived_run(hid_t g, const std::string& where) {
  for (const char* name : {"id", "index", "status", "finished"}) {
    if (!has_attribute(g, name)) {
      throw ArchiveRefused(where + " has no attribute " + name +
                           " (the archive is damaged or was not written by ballast study)");
    }
  }
  ArchivedRun a;
  a.id = read_text_attribute(g, "id");
  a.index = read_int_attribute(g, "index");
  const std::string status = read_text_attribute(g, "status");
  if (status != "ok" && status != "failed") {
    throw ArchiveRefused(where + " has status \"" + status + "\" (allowed: \"ok\" or \"failed\")");
  }
  a.ok = status == "ok";
  a.message = text_or_empty(g, "message");
  a.finished = read_text_attribute(g, "finished");
  a.git_revision = text_or_empty(g, "git_revision");
  return a;
}

std::vector<ArchivedRun> read_archived_runs(hid_t file, const std::string& path) {
  if (!has_link(file, "runs")) throw ArchiveRefused(path + " has no /runs group (damaged)");
  Handle runs(H5Gopen2(file, "runs", H5P_DEFAULT), H5Gclose, "open /runs in " + path);
  std::vector<ArchivedRun> out;
  for (const std::string& name : link_names(runs)) {
    const std::string where = path + ":/runs/" + name;
    Handle g(H5Gopen2(runs, name.c_str(), H5P_DEFAULT), H5Gclose, "open " + where);
    out.push_back(read_archived_run(g, where));
    if (out.back().id != name) {
      throw ArchiveRefused(where + " holds run '" + out.back().id + "' (damaged)");
    }
  }
  return out;
}

std::string iso8601_utc(std::chrono::system_clock::time_point t) {
  const std::time_t s = std::chrono::system_clock::to_time_t(t);
  std::tm utc{};
  gmtime_r(&s, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace ballast
