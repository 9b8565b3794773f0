// What a contact law costs, measured with Google Benchmark.
//
//   make bench      (or build/tests/bench/ballast_bench --benchmark_filter=ContactLaw)
//
// ContactLawEval: the law alone. 4,096 touching contacts of 36.25 mm granite-like
// spheres (overlaps 0.1-1 µm as in the settled bed under the linear law, 1-10 µm
// under Hertz–Mindlin, random normals and sliding velocities, stored shear forces
// of a sticking contact), each evaluated once per pass with friction and without
// dashpots, as in the box test's loading; contacts/s is the figure (its inverse the
// time per contact).
//
// ContactLawBed (below): the whole step of a settled bed under each law.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "cases/bed.hpp"
#include "dense_bed.hpp"
#include "engine/contact_laws.hpp"

using namespace ballast;

namespace {

template <class Law>
void ContactLawEval(benchmark::State& state) {
  const int n = 4096;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), v(0.0, 1.0);
  const Material m = box_test::ballast_material(0.5);
  const PairProperties p = Law::mix(m, m);
  const double small = Law::kUsesRadius ? 1e-6 : 1e-7;  // m, the law's typical overlap
  std::vector<ContactState> contacts(n);
  std::vector<V3> stored(n), shear(n);
  for (int k = 0; k < n; ++k) {
    ContactState& c = contacts[k];
    V3 d{u(rng), u(rng), u(rng)};
    const double len = std::sqrt(dot(d, d));
    c.normal = (1.0 / len) * d;
    c.overlap = small * (1.0 + 9.0 * v(rng));
    c.vrel = {1e-3 * u(rng), 1e-3 * u(rng), 1e-3 * u(rng)};
    c.radius = 0.25 * box_test::kSphereDiameter;
    c.dt = 0.7e-6;
    // A sticking contact's shear force: 10 % of the Coulomb limit, in the plane.
    const double fn = Law::template force<false, false>(c, p, shear[k]).normal_force;
    V3 t = cross(c.normal, V3{0.0, 0.0, 1.0});
    t = (0.05 * fn / std::sqrt(dot(t, t))) * t;
    stored[k] = t;
  }
  double sum = 0.0;
  for (auto _ : state) {
    for (int k = 0; k < n; ++k) {
      shear[k] = stored[k];  // every pass from the same state: sticking, not sliding
      sum += Law::template force<true, false>(contacts[k], p, shear[k]).normal_force;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.counters["contacts/s"] =
      benchmark::Counter(double(n) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(ContactLawEval<LinearLaw>)->Name("ContactLawEval/linear")->UseRealTime()->MinTime(1.0);
BENCHMARK(ContactLawEval<HertzMindlinLaw>)
    ->Name("ContactLawEval/hertz_mindlin")
    ->UseRealTime()
    ->MinTime(1.0);

// ContactLawBed: the settled bed's centres,
// built again under each law (box_test.hpp's granite moduli for Hertz–Mindlin) and
// settled for 3,000 steps into that law's overlaps, then stepped on one thread at
// one fixed dt (the linear law's automatic one, about 0.7 µs). The counter
// contact_steps/s counts touching contacts times steps; simd:0 keeps the linear
// law in the scalar pass that Hertz–Mindlin takes, so the two differ by the law.
void ContactLawBed(benchmark::State& state) {
  omp_set_num_threads(1);
  BedOptions o;
  o.centres = settled_dense_bed(BedOrder::kSpatial).balls().position;
  o.friction = 0.5;
  o.rubber_base = false;
  o.sim.contact_law = std::string(contact_law_name(static_cast<int>(state.range(0))));
  o.sim.simd_lanes = state.range(1) == 1 ? -1 : 0;
  o.sim.fixed_dt = 0.7e-6;
  Simulation sim = make_bed(o);
  sim.run(3000);
  const long steps_per_iteration = 200;
  for (auto _ : state) sim.run(steps_per_iteration);
  const ContactStats c = sim.contacts();
  const double contacts = double(c.ball_contacts + c.wall_contacts);
  state.counters["contacts"] = contacts;
  state.counters["contact_steps/s"] = benchmark::Counter(
      contacts * steps_per_iteration * state.iterations(), benchmark::Counter::kIsRate);
  omp_set_num_threads(omp_get_num_procs());
}
// First argument: the law's number in ContactLaws (0 linear, 1 Hertz–Mindlin).
BENCHMARK(ContactLawBed)
    ->Args({0, 0})
    ->Args({1, 0})
    ->Args({0, 1})
    ->ArgNames({"law", "simd"})
    ->UseRealTime()
    ->MinTime(3.0)
    ->Unit(benchmark::kMillisecond);

}  // namespace
