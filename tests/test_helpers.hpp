// Small scene builders shared by the verification tests.
#pragma once

#include <gtest/gtest.h>
#include <omp.h>

#include <initializer_list>
#include <string>

#include "engine/errors.hpp"
#include "engine/simulation.hpp"

namespace ballast::scenes {

// An empty simulation in a cube [-L, L]³ with no gravity and no damping: tests
// switch on exactly what they verify.
inline SimulationSettings bare_settings(double half_size = 1.0) {
  SimulationSettings s;
  s.domain_lo = Vec3::Constant(-half_size);
  s.domain_hi = Vec3::Constant(half_size);
  s.gravity = Vec3::Zero();
  s.local_damping = 0.0;
  s.damping_ratio = 0.0;
  return s;
}

inline double sphere_volume(double r) {
  return 4.0 / 3.0 * kPi * r * r * r;
}  // m³

inline double sphere_mass(double r, double density) {
  return density * sphere_volume(r);
}

inline Wall plane_wall(const Vec3& point, const Vec3& normal, const Material& m) {
  Wall w;
  w.name = "plane";
  w.point = point;
  w.normal = normal.normalized();
  w.material = m;
  return w;
}

}  // namespace ballast::scenes

namespace ballast::test_support {

// The OpenMP team size for one scope, restored to what it was when the scope ends
// (tests run in one process, and a test that left two threads behind made the next
// one spin two threads on ctest's one-core share). Tests named "...Threads" start
// several; CMake runs those alone (tests/CMakeLists.txt).
class ScopedThreads {
 public:
  explicit ScopedThreads(int threads) : before_(omp_get_max_threads()) {
    omp_set_num_threads(threads);
  }
  ~ScopedThreads() { omp_set_num_threads(before_); }
  ScopedThreads(const ScopedThreads&) = delete;
  ScopedThreads& operator=(const ScopedThreads&) = delete;
  void set(int threads) { omp_set_num_threads(threads); }

 private:
  int before_;
};

// Runs f and expects it to throw E (SetupError unless named) with a message that
// contains every fragment: the field, the value, what is allowed. Passes nothing
// when f returns normally or throws something else.
template <class E = SetupError, class F>
void expect_error(F&& f, std::initializer_list<std::string> fragments) {
  try {
    f();
    ADD_FAILURE() << "nothing was thrown";
  } catch (const E& e) {
    for (const std::string& frag : fragments)
      EXPECT_NE(std::string(e.what()).find(frag), std::string::npos)
          << "message '" << e.what() << "' lacks '" << frag << "'";
  }
}

// The message of the E that f throws, or "(accepted)" when it returns normally: for
// tests that compare several refusals' messages.
template <class E = SetupError, class F>
std::string error_message(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace ballast::test_support
