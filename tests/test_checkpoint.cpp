// Checkpoints of the engine (Simulation::save_state / load_state, engine/state_io.hpp):
// a simulation loaded from a checkpoint steps on bit for bit as the one that wrote it,
// across neighbour builds, on one thread or two; writing changes nothing; a
// truncated checkpoint is refused. state_hash covers everything dynamic a run reports,
// so a field the field lists leave out and the next steps read shows here.
#include <gtest/gtest.h>

#include <sstream>

#include "cases/bed.hpp"
#include "engine/state_hash.hpp"
#include "engine/state_io.hpp"
#include "settling_clump_bed.hpp"
#include "test_helpers.hpp"

using namespace ballast;

namespace {

std::string checkpoint_of(const Simulation& sim) {
  std::ostringstream out;
  StateWriter w(out);
  sim.save_state(w);
  return out.str();
}

Simulation loaded(const std::string& bytes) {
  std::istringstream in(bytes);
  StateReader r(in, "test checkpoint");
  Simulation sim{SimulationSettings{}};
  sim.load_state(r);
  return sim;
}

// The bed is stepped to `split` s, saved, stepped on to `until` s; the saved state,
// loaded into a new simulation on `threads` threads, must reach the same end.
void expect_resume_bit_for_bit(const BedOptions& o, double split, double until, int threads) {
  Simulation sim = make_bed(o);
  while (sim.time() < split) sim.step();
  const long builds_at_split = sim.neighbour_builds();
  const std::string bytes = checkpoint_of(sim);
  EXPECT_EQ(checkpoint_of(sim), bytes) << "writing a checkpoint changed the state";
  const std::uint64_t at_split = state_hash(sim);
  while (sim.time() < until) sim.step();
  EXPECT_GT(sim.neighbour_builds(), builds_at_split + 3) << "the rest crossed too few builds";

  test_support::ScopedThreads team(threads);
  Simulation resumed = loaded(bytes);
  EXPECT_EQ(state_hash(resumed), at_split);
  while (resumed.time() < until) resumed.step();
  EXPECT_EQ(resumed.step_count(), sim.step_count());
  EXPECT_EQ(state_hash(resumed), state_hash(sim));
  EXPECT_EQ(resumed.neighbour_builds(), sim.neighbour_builds());
}

BedOptions sphere_bed() {
  BedOptions o;
  o.count = 300;
  o.length = 0.3;
  o.width = 0.15;
  o.friction = 0.4;
  o.sim.local_damping = 0.2;
  o.sim.gravity = Vec3(0, 0, -981.0);
  return o;
}

}  // namespace

// From 0.01 s to 0.02 s the bed crosses early builds of the rebuild policy, so a
// checkpoint without the policy's interval state is caught (tests/mutations.tsv); a
// shorter window (0.008 to 0.014 s) let that mutation through.
TEST(Checkpoint, ClumpBedResumesBitForBit) {
  expect_resume_bit_for_bit(settling_clump_bed_options(), 0.01, 0.02, 1);
}

TEST(Checkpoint, ClumpBedResumesBitForBitOnTwoThreads) {
  expect_resume_bit_for_bit(settling_clump_bed_options(), 0.008, 0.014, 2);
}

TEST(Checkpoint, SphereBedWithDashpotsResumesBitForBit) {
  BedOptions o = sphere_bed();
  o.sim.damping_ratio = 0.1;
  expect_resume_bit_for_bit(o, 0.01, 0.02, 1);
}

TEST(Checkpoint, SphereBedOnTheSimdKernelResumesBitForBit) {
  expect_resume_bit_for_bit(sphere_bed(), 0.01, 0.02, 1);
}

TEST(Checkpoint, ATruncatedCheckpointIsRefused) {
  Simulation sim = make_bed(settling_clump_bed_options());
  sim.run(10);
  const std::string bytes = checkpoint_of(sim);
  const std::string message =
      test_support::error_message([&] { loaded(bytes.substr(0, bytes.size() / 2)); });
  EXPECT_NE(message.find("test checkpoint is truncated"), std::string::npos) << message;
}
