// The ball–ball and ball–plane contacts of a sphere-only scene, evaluated several at
// a time in the lanes of SIMD registers (AVX2: 4 contacts, AVX-512: 8), and its leapfrog.
//
// Why: the scalar force pass spends most of its time waiting along each contact's
// chain of dependent operations (partner load, distance, square root, division,
// normal, shear turn, Coulomb cap); the out-of-order window overlaps too few
// contacts to hide it (docs/PERFORMANCE.md, "What bought what"). Lanes evaluate
// independent contacts side by side, so one chain's latency serves four or eight.
//
// The lanes take the live candidates a register's width at a time from one flat
// sequence (ContactList::flat_c, remade only when the live lists are), with no loop
// per ball: a loop that ends after a variable count at every ball mispredicts about
// once a ball, which is what the pass is short of.
//
// Same bits as the scalar pass (forces.cpp): every lane performs the scalar law's
// IEEE operations in the scalar order (no FMA: the kernel files are built without
// it and with -ffp-contract=off), the law's two branches become selects computed
// only when a lane needs them, and each ball's side-a wrench is summed from zero in
// contact order, as the scalar pass does. tests/test_sphere_kernel.cpp holds every
// width to the scalar pass's state hash.
//
// This header is plain C++ on purpose (no Eigen, no std::vector): the kernels are
// compiled with -mavx2 / -mavx512f, and an inline function from a shared header
// compiled there could be picked by the linker for the baseline code too.
#pragma once

#include <cstdint>

namespace ballast {

// Raw views of the arrays the kernel reads and writes.
// Ball k is body k. Vectors are three doubles (x, y, z), wrenches six (force, then
// torque); indices are the engine's 32-bit Index.
struct SphereKernelView {
  const double* position;          // m, per ball
  const double* radius;            // m, per ball
  const double* velocity;          // m/s, per ball (half step)
  const double* angular_velocity;  // rad/s, per ball (half step)
  const std::int32_t* material;    // per ball
  const double* pair;              // kn, ks (N/m), mu per material pair (PairProperties)
  std::int32_t materials;          // ball materials; pair[(mi·materials + mj)·3 ...]
  double dt;                       // s
  // the ball–ball candidate list (contact_list.hpp) and its flat live sequence
  const std::int32_t* b;
  const std::int32_t* flat_c;
  const std::int32_t* flat_a;
  const std::int32_t* flat_first;
  double* shear_force;   // N, 3 per contact; null in a frictionless scene
  double* b_wrench;      // 6 per contact
  double* normal_force;  // N, per contact
  double* slip_total;    // J, per contact; null: no energy ledger
  std::uint8_t* active;  // per contact
  double* a_side;        // 6 per ball: set here to the sum of its side-a ball–ball wrenches
};

// The ball–wall candidates of a sphere-only scene whose walls are planes (walls.hpp),
// several contacts at a time. Walls of another shape are left to the scalar pass:
// their candidates are skipped here.
struct SpherePlaneView {
  const double* position;          // m, per ball
  const double* radius;            // m, per ball
  const double* velocity;          // m/s, per ball (half step)
  const double* angular_velocity;  // rad/s, per ball (half step)
  const std::int32_t* material;    // per ball
  const double* pair;              // kn, ks (N/m), mu per (ball material, wall): PairTable::wall
  std::int32_t walls;              // pair[(mi·walls + w)·3 ...]
  // Per wall, kPlaneRow doubles: its unit normal, a point on it (m) and its velocity
  // (m/s); is_plane[w] says whether wall w is a plane (the others' rows are zeros).
  const double* plane;
  const std::uint8_t* is_plane;
  double dt;  // s
  // the ball–wall candidate list (contact_list.hpp): side a is the ball, b the wall
  const std::int32_t* a;
  const std::int32_t* b;
  double* shear_force;   // N, 3 per contact; null in a frictionless scene
  double* b_wrench;      // 6 per contact: −F, and a zero torque the kernel leaves alone
  double* normal_force;  // N, per contact
  double* slip_total;    // J, per contact; null: no energy ledger
  std::uint8_t* active;  // per contact
  double* a_side;        // 6 per ball: each plane contact's wrench is added to it
};
constexpr int kPlaneRow = 9;

// The leapfrog of consecutive spheres (integrator.cpp's update_body, after the
// gather has stored each body's resultant), several bodies per pass. Ball k is body
// k; vectors are three doubles per body.
struct SphereUpdateView {
  const double* force;         // N, the resultant before damping (gather_body_force)
  const double* torque;        // N·m
  double* velocity;            // m/s, half step
  double* angular_velocity;    // rad/s, half step
  double* position;            // m, the body's centre
  double* ball_position;       // m, its ball's centre (the same point)
  double* rotation;            // rad, Σ ω·dt
  const double* reference;     // m, ball positions at the last neighbour build
  const double* mass;          // kg
  const double* inv_mass;      // 1/kg
  const double* inv_inertia;   // 1/(kg·m²), principal (equal for a sphere)
  double* gravity_work;        // J
  double* damping_dissipated;  // J
  double dt;                   // s
  double local_damping;        // PFC α (0: off)
  double gravity[3];           // m/s²
  double max_speed;            // m/s
  bool ledger;                 // book gravity work and damping (the energy ledger)
};

// What the update saw: the largest squared move since the reference (m²) and the
// lowest body that went non-finite or too fast (INT32_MAX if none).
struct SphereUpdateReport {
  double shift2 = 0.0;
  std::int32_t bad = INT32_MAX;
};

// Whether this CPU runs the kernel of `lanes` lanes (4: AVX2, 8: AVX-512F/DQ).
bool sphere_kernel_supported(int lanes);
// The widest kernel this CPU runs, 0 if none; the environment variable BALLAST_SIMD
// (off, avx2, avx512) narrows it, to compare kernels on one machine.
int sphere_kernel_best_lanes();
// "avx512", "avx2" or "scalar" for 8, 4 or 0 lanes.
const char* sphere_kernel_name(int lanes);

// Evaluates the live ball–ball candidates of balls [lo, hi) (ContactList::flat_c...)
// with the kernel of `lanes` lanes, which must be supported, and sets a_side of those
// balls to the sum of their side-a wrenches (from zero, in contact order). The scene
// has no contact dashpots.
void sphere_kernel_ball_ball(const SphereKernelView& v, std::int32_t lo, std::int32_t hi,
                             int lanes);

// Evaluates the ball–wall candidates [first, last) whose wall is a plane with the
// kernel of `lanes` lanes and adds each one's wrench to its ball's a_side, in
// candidate order, as the scalar pass does after the ball–ball contacts. The scene
// has no contact dashpots.
void sphere_kernel_ball_plane(const SpherePlaneView& v, std::int32_t first, std::int32_t last,
                              int lanes);

// Updates bodies [lo, lo + n·lanes) for the largest such n with lo + n·lanes <= hi,
// folding into `report`, and returns lo + n·lanes: the caller updates the rest.
std::int32_t sphere_kernel_update(const SphereUpdateView& v, std::int32_t lo, std::int32_t hi,
                                  int lanes, SphereUpdateReport& report);

// The kernels, one per instruction set (sphere_kernel_avx2.cpp, sphere_kernel_avx512.cpp).
void sphere_kernel_ball_ball_avx2(const SphereKernelView& v, std::int32_t lo, std::int32_t hi);
void sphere_kernel_ball_ball_avx512(const SphereKernelView& v, std::int32_t lo, std::int32_t hi);
void sphere_kernel_ball_plane_avx2(const SpherePlaneView& v, std::int32_t first, std::int32_t last);
void sphere_kernel_ball_plane_avx512(const SpherePlaneView& v, std::int32_t first,
                                     std::int32_t last);
std::int32_t sphere_kernel_update_avx2(const SphereUpdateView& v, std::int32_t lo, std::int32_t hi,
                                       SphereUpdateReport& report);
std::int32_t sphere_kernel_update_avx512(const SphereUpdateView& v, std::int32_t lo,
                                         std::int32_t hi, SphereUpdateReport& report);

}  // namespace ballast
