// The clump generator of Lu & McDowell 2007, section 2: a central ball, balls grown
// along randomly chosen cube-face / space-diagonal directions (eqs 1-9), and edge
// balls joining the outermost balls of adjacent directions (Fig. 6). Every choice the
// paper leaves open is documented in docs/CLUMPS.md and tested in
// tests/test_clump_generator.cpp.
//
// Lengths: c and d3 are fractions of the central ball radius R (as in Table 1);
// everything else is in metres.
#pragma once

#include <cstdint>
#include <random>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/types.hpp"

namespace ballast {

// Which pairs of used directions are joined by edge balls ("adjacent directions",
// which the paper does not define).
enum class EdgeAdjacency {
  // Edges of the convex hull of the candidate directions on the unit sphere: the
  // 12 orthogonal pairs for 6 directions (octahedron); for 14 directions each face
  // normal with its 4 nearest diagonals (24) plus each diagonal with the 3 diagonals
  // that differ in one sign (12), 36 in all (tetrakis hexahedron). Matches Table 2.
  kHull,
  // Like kHull without the diagonal-diagonal pairs: 12 pairs for 6 directions, 24 for
  // 14. Matches the averages printed in Fig. 7.
  kFaceToDiagonal,
};

// "hull", "face_to_diagonal".
const char* adjacency_name(EdgeAdjacency adjacency);
// Inverse of adjacency_name; throws std::invalid_argument listing the names.
EdgeAdjacency parse_adjacency(std::string_view name);

struct ClumpParams {
  int directions = 6;           // candidate directions: 6 (cube faces) or 14 (+ diagonals)
  double p = 0.5;               // probability that a candidate direction is used, [0, 1]
  int balls_per_direction = 2;  // balls grown along each used direction (fixed), >= 0
  double c = 0.2;               // maximum radius reduction D4 per ball, fraction of R, [0, 1)
  double d3 = 0.2;              // clump extension D3 (eq 8), fraction of R, >= 0
  int edge_balls = 1;           // balls inserted on each edge, >= 0
  EdgeAdjacency adjacency = EdgeAdjacency::kHull;
  double nominal_diameter = 0.03625;    // m, the paper's sphere diameter
  double virtual_sphere_factor = 1.26;  // Rv / (nominal_diameter / 2), > 0
  // Smallest radius a grown ball may have, fraction of R, (0, 1). Only matters when
  // balls_per_direction·c >= 1 - min_radius_fraction (see docs/CLUMPS.md).
  double min_radius_fraction = 0.05;
};

// Throws std::invalid_argument naming the field, its value and what is allowed.
void validate_clump_params(const ClumpParams& params);

// The largest D3 for these parameters: the central ball, Rv / (1 + n·D3), at least
// min_radius_fraction of the virtual sphere's radius. Far below it every ball is tiny
// beside its particle, and the neighbour skin and the timestep shrink with it: a box
// test with D3 = 100 had not finished growing 40 clumps after 5 minutes.
double largest_d3(const ClumpParams& params);

// Rv = virtual_sphere_factor · nominal_diameter / 2, m.
double virtual_sphere_radius(const ClumpParams& params);
// R = Rv / (1 + n·d3): the largest central ball for which every grown ball fits in
// the virtual sphere by construction (a ball's far surface lies R + k·D3 from the
// centre, whatever D4 was), m.
double central_ball_radius(const ClumpParams& params);

// Unit candidate directions in their fixed order: +x, -x, +y, -y, +z, -z, then (for
// 14) the diagonals (sx, sy, sz)/√3 with signs in binary order +++, ++-, +-+, +--,
// -++, -+-, --+, ---. The order fixes which random number decides which direction.
const std::vector<Vec3>& candidate_directions(int directions);
// Adjacent pairs (i < j, lexicographic order) of candidate direction indices.
std::vector<std::pair<int, int>> adjacent_direction_pairs(int directions, EdgeAdjacency adjacency);

// Mean number of balls per clump: 1 + p·N·n + p²·E·m, with N candidate directions,
// n balls per direction, E adjacent pairs and m edge balls (no edges when n = 0).
double expected_ball_count(const ClumpParams& params);

enum class BallKind : std::uint8_t { kCentral, kDirection, kEdge };

// Where a ball came from, so that tests and plots can check the construction.
struct BallOrigin {
  BallKind kind = BallKind::kCentral;
  int direction = -1;        // kDirection: candidate index; kEdge: first end's direction
  int other_direction = -1;  // kEdge: second end's direction
  int index = 0;             // kDirection: step k = 1..n outwards; kEdge: j = 1..m
};

// A clump as generated: central ball at the origin of the generation frame.
struct ClumpGeometry {
  std::vector<Vec3> centres;  // m
  std::vector<double> radii;  // m
  std::vector<BallOrigin> origins;
  std::vector<int> used_directions;  // candidate indices, ascending
  double central_radius = 0.0;       // R, m
  double virtual_radius = 0.0;       // Rv, m
  double nominal_radius = 0.0;       // nominal_diameter / 2, m
};

// Generates one clump. Draws, in this order: one number per candidate direction
// (used if u <= p, u uniform on (0, 1]), then for each used direction in ascending
// order n numbers for D4 = c·R·u, u uniform on [0, 1).
ClumpGeometry generate_clump(const ClumpParams& params, std::mt19937_64& rng);

// The random number generator of clump `index` of a sample drawn with `seed`:
// independent of how clumps are shared among threads.
std::mt19937_64 clump_rng(std::uint64_t seed, std::uint64_t index);

// Uniform doubles from 53 random bits, identical on every platform (unlike
// std::uniform_real_distribution, whose algorithm is implementation-defined).
inline double uniform_closed_open(std::mt19937_64& rng) {  // [0, 1)
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}
inline double uniform_open_closed(std::mt19937_64& rng) {  // (0, 1]
  return static_cast<double>((rng() >> 11) + 1) * 0x1.0p-53;
}

}  // namespace ballast
