// The study archive read back with the HDF5 C API (study/archive/study_archive.hpp,
// study/archive/study_store.hpp, docs/ARCHIVE.md): what is written is what is read, seeds in
// full 64 bits, the fingerprint tells studies apart, and the store refuses, rebuilds
// and cleans up as documented. Synthetic results: nothing is simulated here (the runs
// themselves are tests/cli/test_study.py's).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "study/archive/hdf5_read.hpp"
#include "study/archive/study_archive.hpp"
#include "study/archive/study_store.hpp"
#include "study/matrix/study_json.hpp"
#include "study_text.hpp"
#include "test_helpers.hpp"

namespace ballast {
namespace {

using namespace h5;
namespace fs = std::filesystem;
using nlohmann::json;

// Three runs, one per cycle count.
StudySpec expand(std::uint64_t seed, const std::string& extra = "") {
  return study_text::expand(
      study_text::with_matrix(R"({"axes": {"cycles": [1, 2, 3]}})", "s.json", seed, extra));
}

const json kScene = json::parse(R"({"name": "s", "particles": {"count": 2}})");

BoxTestResult synthetic_result() {
  BoxTestResult r;
  r.scene_name = "s";
  r.stages = {{"expand", 100, 0.01, 0.5, 0.2, ""}, {"cycle", 300, 0.03, 1.5, 0.01, ""}};
  r.bodies = 2;
  r.balls = 3;
  r.loaded = true;
  r.porosity_grid = 0.375;
  r.position_start = {Vec3(0.1, 0.2, 0.3), Vec3(0.4, 0.5, 0.6)};
  r.position_peak = {Vec3(0.1, 0.2, 0.29), Vec3(0.4, 0.5, 0.59)};
  r.position_end = {Vec3(0.1, 0.2, 0.28), Vec3(0.41, 0.5, 0.58)};
  r.rotation_deg_loading = r.rotation_deg_unloading = r.rotation_deg_cycle = {1.0, 2.0};
  r.shape_index = {0, 1};
  r.time = {0.0, 0.1, 0.2};
  r.target_force = {1.0, 2.0, 1.0};
  r.sleeper_force = {1.1, 1.9, 1.0};
  r.settlement = {0.0, 1e-3, 5e-4};
  r.before.stats.ball_contacts = 7;
  r.before.from = {Vec3(0, 0, 0)};
  r.before.to = {Vec3(1, 0, 0)};
  r.before.force = {12.5};
  ClumpSampleRecord c;
  c.shape = "table2/sample1";
  c.seed = 42;
  ClumpTemplate a, b;
  a.radii = {0.01, 0.005};
  a.offsets = {Vec3(0, 0, 0), Vec3(0.01, 0, 0)};
  a.mass = 0.02;
  b.radii = {0.012};
  b.offsets = {Vec3(0, 0, 0)};
  b.mass = 0.03;
  c.templates = {a, b};
  c.shapes.resize(2);
  c.shapes[0].sphericity = 0.9;
  c.shapes[1].sphericity = 1.0;
  r.clumps = c;
  return r;
}

RunRecord synthetic_record(const RunSpec& spec, bool ok) {
  RunRecord r;
  r.spec = spec;
  r.ok = ok;
  r.message = ok ? "" : "blew up: step 3";
  r.started = "2024-01-01T00:00:00Z";
  r.finished = "2024-01-01T00:00:01Z";
  r.wall_seconds = 1.0;
  r.log = "stage 1: ...\n";
  if (ok) r.result = synthetic_result();
  return r;
}

class TempDir : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("ballast_archive_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    quiet_errors();
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

using StudyArchive = TempDir;

TEST_F(StudyArchive, RunGroupRoundTrip) {
  StudySpec spec = expand(1);
  spec.runs[0].seed = 0xffffffffffffffffULL;  // the largest seed survives
  const RunRecord written = synthetic_record(spec.runs[0], true);
  {
    Handle file(H5Fcreate(path("a.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                "create");
    Handle g = create_group(file, "run");
    write_run_group(g, written);
  }
  Handle file(H5Fopen(path("a.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open");
  Handle g(H5Gopen2(file, "run", H5P_DEFAULT), H5Gclose, "open run");
  const ArchivedRun a = read_archived_run(g, "run");
  EXPECT_EQ(a.id, spec.runs[0].id);
  EXPECT_EQ(a.index, 0);
  EXPECT_TRUE(a.ok);
  EXPECT_EQ(a.finished, written.finished);
  EXPECT_EQ(read_uint64_attribute(g, "seed"), 0xffffffffffffffffULL);
  EXPECT_EQ(json::parse(read_text_attribute(g, "params")), spec.runs[0].params);
  EXPECT_EQ(read_text_dataset(g, "log"), written.log);
  EXPECT_EQ(read_double_attribute(g, "porosity_grid"), 0.375);
  EXPECT_EQ(read_double_dataset(g, "series/sleeper_force"), written.result->sleeper_force);
  std::vector<hsize_t> dims;
  const std::vector<double> d = read_double_dataset(g, "particles/displacement_end", &dims);
  EXPECT_EQ(dims, (std::vector<hsize_t>{2, 3}));
  EXPECT_EQ(d[3], 0.41 - 0.4);  // body 1, x: end - start, computed the same way
  EXPECT_EQ(d[5], 0.58 - 0.6);
  EXPECT_EQ(read_double_dataset(g, "clumps/balls/radius"),
            (std::vector<double>{0.01, 0.005, 0.012}));
  EXPECT_EQ(read_double_dataset(g, "clumps/shape/sphericity"), (std::vector<double>{0.9, 1.0}));
  Handle clumps(H5Gopen2(g, "clumps", H5P_DEFAULT), H5Gclose, "open clumps");
  EXPECT_EQ(read_text_attribute(clumps, "format"), "ballast-clumps");
  EXPECT_EQ(read_double_attribute(g, "wall_seconds"), 0.0);  // the result's own
}

TEST_F(StudyArchive, FailedRunHasItsMessageAndNoMeasurements) {
  const StudySpec spec = expand(1);
  {
    Handle file(H5Fcreate(path("a.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                "create");
    Handle g = create_group(file, "run");
    write_run_group(g, synthetic_record(spec.runs[1], false));
  }
  Handle file(H5Fopen(path("a.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open");
  Handle g(H5Gopen2(file, "run", H5P_DEFAULT), H5Gclose, "open run");
  const ArchivedRun a = read_archived_run(g, "run");
  EXPECT_FALSE(a.ok);
  EXPECT_EQ(a.message, "blew up: step 3");
  EXPECT_EQ(read_double_attribute(g, "wall_seconds"), 1.0);
  EXPECT_FALSE(has_link(g, "particles"));
}

TEST_F(StudyArchive, HeaderRoundTrip) {
  const StudySpec spec = expand(0xfedcba9876543210ULL);
  const StudyArchiveHeader h = make_archive_header(spec, "{study}", "{scene}", kScene, Shard{2, 3});
  {
    Handle file(H5Fcreate(path("a.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                "create");
    write_archive_header(file, h);
  }
  Handle file(H5Fopen(path("a.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "open");
  const StudyArchiveHeader r = read_archive_header(file, "a.h5");
  EXPECT_EQ(r.study_seed, 0xfedcba9876543210ULL);
  EXPECT_EQ(r.study_json, "{study}");
  EXPECT_EQ(r.scene_json, "{scene}");
  EXPECT_EQ(r.run_count, 3);
  EXPECT_EQ(r.fingerprint, h.fingerprint);
  EXPECT_EQ(r.shard.index, 2);
  EXPECT_EQ(r.shard.count, 3);
  EXPECT_EQ(json::parse(r.runs_json).size(), 3u);
  EXPECT_EQ(json::parse(r.runs_json)[2]["seed"], std::to_string(spec.runs[2].seed));
}

TEST_F(StudyArchive, FingerprintFollowsRunsAndSceneNotDescriptions) {
  const std::string base = study_fingerprint(expand(1), kScene);
  EXPECT_EQ(study_fingerprint(expand(1, R"(, "description": "edited")"), kScene), base);
  EXPECT_NE(study_fingerprint(expand(2), kScene), base);  // every seed changes
  json scene = kScene;
  scene["particles"]["count"] = 3;
  EXPECT_NE(study_fingerprint(expand(1), scene), base);
}

using Store = TempDir;

TEST_F(Store, RecordsRunsRemovesPartsWhenDoneAndRefusesToOverwrite) {
  const StudySpec spec = expand(1);
  const StudyArchiveHeader h = make_archive_header(spec, "{}", "{}", kScene, Shard{});
  std::vector<std::string> reports;
  const auto report = [&](const std::string& s) { reports.push_back(s); };
  auto store = StudyStore::create(path("a.h5"), h, report);
  store->record(synthetic_record(spec.runs[0], true));
  store->record(synthetic_record(spec.runs[1], false));
  EXPECT_TRUE(fs::exists(path("a.h5.parts/000000.h5")));
  {
    Handle f(H5Fopen(path("a.h5").c_str(), H5F_ACC_RDONLY, archive_file_access()), H5Fclose, "o");
    const std::vector<ArchivedRun> runs = read_archived_runs(f, "a.h5");
    ASSERT_EQ(runs.size(), 2u);
    EXPECT_EQ(store->recorded().at(spec.runs[1].id), false);
  }
  store->finish();
  EXPECT_FALSE(fs::exists(path("a.h5.parts")));
  EXPECT_THROW(StudyStore::create(path("a.h5"), h, report), ArchiveRefused);
}

TEST_F(Store, ResumeRebuildsADamagedArchiveFromItsPartsAndKeepsTheDamagedOne) {
  const StudySpec spec = expand(1);
  const StudyArchiveHeader h = make_archive_header(spec, "{}", "{}", kScene, Shard{});
  const auto quiet = [](const std::string&) {};
  {
    auto store = StudyStore::create(path("a.h5"), h, quiet);
    store->record(synthetic_record(spec.runs[0], true));
    store->record(synthetic_record(spec.runs[2], true));
  }
  const auto size = fs::file_size(path("a.h5"));
  fs::resize_file(path("a.h5"), size / 3);  // cut short, as by a kill mid-write
  std::string said;
  auto store = StudyStore::resume(path("a.h5"), h, [&](const std::string& s) { said += s + "\n"; });
  EXPECT_NE(said.find("is damaged"), std::string::npos) << said;
  EXPECT_EQ(fs::file_size(path("a.h5.damaged")), size / 3);
  EXPECT_EQ(store->recorded().size(), 2u);
  Handle f(H5Fopen(path("a.h5").c_str(), H5F_ACC_RDONLY, archive_file_access()), H5Fclose, "o");
  EXPECT_EQ(read_archived_runs(f, "a.h5").size(), 2u);
}

TEST_F(Store, ResumeRefusesAnotherStudyAndChangesNothing) {
  const StudyArchiveHeader h = make_archive_header(expand(1), "{}", "{}", kScene, Shard{});
  const auto quiet = [](const std::string&) {};
  StudyStore::create(path("a.h5"), h, quiet);
  const auto before = fs::last_write_time(path("a.h5"));
  const StudyArchiveHeader other = make_archive_header(expand(2), "{}", "{}", kScene, Shard{});
  test_support::expect_error<ArchiveRefused>(
      [&] { StudyStore::resume(path("a.h5"), other, quiet); }, {"holds another study"});
  EXPECT_EQ(fs::last_write_time(path("a.h5")), before);
}

}  // namespace
}  // namespace ballast
