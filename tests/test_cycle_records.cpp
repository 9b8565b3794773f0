// Many load cycles (cases/cycle_recorder.hpp): the log-N fit, the default snapshot
// cycles, the scene's refusals, and a tiny box test loaded four times, whose
// per-cycle records must agree with what the run reports and with its own
// load–deformation series.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "cases/box_test_load.hpp"
#include "cases/cycle_recorder.hpp"
#include "test_helpers.hpp"

using namespace ballast;
using nlohmann::json;

namespace {

// tests/data/study/tiny.json: 40 spheres, a few seconds for four 100 Hz cycles.
json tiny_scene() {
  return json::parse(R"({
    "name": "tiny",
    "particles": {"shape": "spheres", "count": 40, "diameter": 0.03625, "seed": 1},
    "box": {"length": 0.15, "width": 0.12, "height": 0.25},
    "preparation": {"initial_porosity": 0.5, "expansion_speed": 0.25, "gravity_factor": 10,
                    "equilibrium_ratio": 0.02, "max_stage_steps": 10000},
    "sleeper": {"length": 0.08, "height": 0.04, "preload": 200, "peak_load": 2000,
                "frequency": 100, "cycles": 4, "max_speed": 0.5},
    "measurement": {"series_every": 1, "snapshot_cycles": [1, 2, 3, 4]}
  })");
}

}  // namespace

TEST(CycleRecords, LogSlopeRecoversALogLaw) {
  // s(N) = 1 mm + 0.2 mm per decade: the fit returns the 0.2 mm exactly.
  std::vector<double> s;
  for (int n = 1; n <= 300; ++n) s.push_back(1e-3 + 2e-4 * std::log10(double(n)));
  EXPECT_NEAR(settlement_log_slope(s), 2e-4, 1e-15);
  // Two cycles: the line through both points, (s2 − s1) / log10 2.
  EXPECT_NEAR(settlement_log_slope({1e-3, 1.3e-3}), 3e-4 / std::log10(2.0), 1e-15);
  EXPECT_EQ(settlement_log_slope({1e-3}), 0.0);
}

TEST(CycleRecords, DefaultSnapshotsArePowersOfTenAndTheLast) {
  BoxTestScene s;
  s.cycles = 250;
  EXPECT_EQ(snapshot_cycles_of(s), (std::vector<long>{1, 10, 100, 250}));
  s.cycles = 1;
  EXPECT_EQ(snapshot_cycles_of(s), (std::vector<long>{1}));
  s.cycles = 1000;
  EXPECT_EQ(snapshot_cycles_of(s), (std::vector<long>{1, 10, 100, 1000}));
  s.snapshot_cycles = {5, 2, 5};
  EXPECT_EQ(snapshot_cycles_of(s), (std::vector<long>{2, 5}));
}

TEST(CycleRecords, SceneRefusesSnapshotsBeyondTheCycles) {
  json j = tiny_scene();
  j["measurement"]["snapshot_cycles"] = {1, 5};
  const std::string e = test_support::error_message([&] { parse_box_test_scene(j); });
  EXPECT_NE(e.find("/measurement/snapshot_cycles"), std::string::npos) << e;
  EXPECT_NE(e.find("[1,5]"), std::string::npos) << e;
  EXPECT_NE(e.find("/sleeper/cycles = 4"), std::string::npos) << e;
  j["measurement"]["snapshot_cycles"] = json::array();
  EXPECT_NE(test_support::error_message([&] { parse_box_test_scene(j); }).find("non-empty"),
            std::string::npos);
}

TEST(CycleRecords, TinyBoxTestRecordsEveryCycle) {
  const BoxTestScene s = parse_box_test_scene(tiny_scene());
  const BoxTestResult r = run_box_test(s, nullptr);
  const CycleRecords& c = r.cycles;
  ASSERT_EQ(c.count(), 4u);
  ASSERT_EQ(c.settlement_peak.size(), 4u);
  // The first peak and the last end are the run's own settlement_peak and permanent.
  EXPECT_EQ(c.settlement_peak.front(), r.settlement_peak);
  EXPECT_EQ(c.settlement_trough.back(), r.permanent_settlement);
  EXPECT_EQ(c.settlement_peak.back() - c.settlement_trough.back(), r.resilient_settlement);
  ASSERT_EQ(c.snapshots.size(), 4u);
  EXPECT_EQ(c.snapshots.back().cycle, 4);
  EXPECT_EQ(c.snapshots.back().position, r.position_end);
  EXPECT_EQ(c.snapshots.back().settlement, r.permanent_settlement);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_GT(c.sleeper_bodies[k], 0) << "cycle " << k + 1;
    EXPECT_GE(c.sleeper_contacts[k], c.sleeper_bodies[k]);
    EXPECT_GT(c.porosity_under[k], 0.2);
    EXPECT_LT(c.porosity_under[k], 0.7);
  }
  // Accumulated rotation since the start of loading: its mean at the last end is the
  // run's whole-loading mean.
  EXPECT_NEAR(c.rotation_mean_deg.back(), r.rotation_cycle.mean_deg,
              1e-12 * r.rotation_cycle.mean_deg);

  // The sleeper's work, cycle by cycle, against the trapezoid rule over the series
  // (sampled every step in every cycle here), which starts one step after loading.
  double series_work = 0.0;
  for (std::size_t k = 1; k < r.settlement.size(); ++k)
    series_work += 0.5 * (r.sleeper_force[k] + r.sleeper_force[k - 1]) *
                   (r.settlement[k] - r.settlement[k - 1]);
  double recorded = 0.0;
  for (double w : c.sleeper_work) recorded += w;
  EXPECT_NEAR(recorded, series_work, 0.01 * std::abs(recorded));
  // Each cycle's work: at most the peak force times the sleeper's travel down to the
  // peak (unloading gives some back), and positive, since the bed dissipates and
  // settles: a lost sign or a lost reset breaks one of the two.
  double before = 0.0;
  for (std::size_t k = 0; k < 4; ++k) {
    const double travel = c.settlement_peak[k] - before;
    EXPECT_GT(c.sleeper_work[k], 0.0) << "cycle " << k + 1;
    EXPECT_LT(c.sleeper_work[k], 1.05 * s.peak_load * std::max(travel, 0.0) + 1e-6)
        << "cycle " << k + 1;
    before = c.settlement_trough[k];
  }
  // The series covers all four cycles: from the first step to the last.
  const double period = 1.0 / s.frequency;
  EXPECT_LT(r.time.front(), 0.01 * period);
  EXPECT_GT(r.time.back(), 3.99 * period);
}

TEST(CycleRecords, SeriesIsSampledOnlyInSnapshotCycles) {
  json j = tiny_scene();
  j["measurement"]["snapshot_cycles"] = {2};
  const BoxTestScene s = parse_box_test_scene(j);
  const BoxTestResult r = run_box_test(s, nullptr);
  const double period = 1.0 / s.frequency;
  ASSERT_FALSE(r.time.empty());
  // Cycle 2 runs from the first step after t = P to the step that passes 2P.
  for (double t : r.time) {
    EXPECT_GT(t, period);
    EXPECT_LE(t, 2.0 * period + r.dt * (1.0 + 1e-9));
  }
  EXPECT_LT(r.time.front(), period + 2.0 * r.dt);
  EXPECT_GT(r.time.back(), 2.0 * period);
  ASSERT_EQ(r.cycles.snapshots.size(), 1u);
  EXPECT_EQ(r.cycles.snapshots[0].cycle, 2);
  EXPECT_EQ(r.cycles.count(), 4u);
}
