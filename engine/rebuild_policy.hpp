// When to rebuild the neighbour list before the half-skin rule requires it.
//
// Between two builds the force pass evaluates the live candidates (contact_list.hpp,
// "Live candidates"): those touching and those whose gap at the build is within a
// cover above 2 × the largest shift of any ball since the build. One ball that moves
// (a rattler, the bed under a sleeper, a bed relaxing from 10 g to 1 g) raises that
// bound for every pair, and a bed that settles for tens of thousands of steps between
// two half-skin builds ends up evaluating most of its candidates, and every candidate
// live costs the Sample 1 bench bed 1.6 times the step (`ballast bench-bed` with and
// without --test-all-candidates; docs/PERFORMANCE.md, "Rebuilding when it pays").
//
// A build resets the bound to zero and the live list to the touching candidates, and
// costs a few tens of steps (RebuildPolicy::kBuildCostPerBall and
// kBuildCostPerCandidate). Whether it pays is
// a renewal problem: with build cost C and the excess live candidates w(t) at step t
// of an interval, the mean cost per step over T steps is (C + W(T)) / T, W the sum
// of w; it stops falling when w(T) · T ≥ C + W(T), and the policy rebuilds there. A bed
// whose excess jumps to its maximum at once (a falling cloud) never meets the rule,
// since w · T < C + w · T: it keeps the half-skin builds and pays nothing more.
//
// Every quantity is a count of candidates, never a clock reading, so the decision is
// the same on any number of threads; and a build changes no bits of the motion (a
// touching pair keeps its state across it, an open one holds nothing), so with a
// fixed timestep the trajectory is the same with and without the policy. With the
// automatic timestep each build also re-estimates dt (Simulation::rebuild_neighbours).
#pragma once

namespace ballast {

class RebuildPolicy {
 public:
  // One build (cell list, candidate search, history merge, build gaps, wall
  // candidates) costs about as much as evaluating this many live candidates per ball
  // plus this many per candidate in the list. On the Xeon VM one extra live candidate
  // cost about 14 ns a step on one thread (the Sample 1 bench bed, 3,000 steps with and
  // without --test-all-candidates: 2.97 and 1.84 ms a step), and the neighbour search,
  // most of a build, 23 ms for the benchmark's clump bed of 19,242 balls and 50,485
  // candidates (`ballast_bench --benchmark_filter=NeighbourSearch`): 1.6 million
  // evaluations, against 2.0 million by these constants. The mean cost per step is
  // flat near the optimum, so a factor of 2 off changes little
  // (docs/PERFORMANCE.md, "Rebuilding when it pays").
  static constexpr double kBuildCostPerBall = 50.0;
  static constexpr double kBuildCostPerCandidate = 20.0;

  // A build has just been made for `balls` balls with `candidates` ball–ball candidates.
  void start(long balls, long candidates) {
    cost_ = kBuildCostPerBall * double(balls) + kBuildCostPerCandidate * double(candidates);
    base_ = -1;
    live_ = 0;
    steps_ = 0;
    excess_sum_ = 0.0;
  }

  // The live lists were remade and now hold `live` candidates. The first count after
  // a build is the interval's base: what the bed needs with no bound at all.
  void live_count(long live) {
    if (base_ < 0) base_ = live;
    live_ = live;
  }

  // A step has been taken with the current live lists; true when a build now
  // minimises the mean cost per step of this interval.
  bool step_taken() {
    if (base_ < 0) return false;
    ++steps_;
    const double excess = double(live_ - base_);
    excess_sum_ += excess;
    return excess > 0.0 && excess * double(steps_) >= cost_ + excess_sum_;
  }

  double build_cost() const { return cost_; }  // in live-candidate evaluations
  long steps_since_build() const { return steps_; }

 private:
  double cost_ = 0.0;        // one build, in live-candidate evaluations
  long base_ = -1;           // live candidates at the first refresh after the build
  long live_ = 0;            // live candidates now
  long steps_ = 0;           // steps since the build
  double excess_sum_ = 0.0;  // Σ (live − base) over those steps
};

}  // namespace ballast
