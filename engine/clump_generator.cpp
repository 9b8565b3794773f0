#include "engine/clump_generator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "engine/clump_param_table.hpp"
#include "engine/errors.hpp"

namespace ballast {
namespace {

// "clump parameter 'p' = 1.5 is outside [0, 1]"
template <class T>
[[noreturn]] void reject(const char* field, T value, const std::string& what) {
  std::ostringstream s;
  s << "clump parameter '" << field << "' = " << value << " is " << what;
  throw SetupError(s.str());
}

std::vector<Vec3> make_directions(int count) {
  std::vector<Vec3> d = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                         Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
  if (count == 14) {
    const double s = 1.0 / std::sqrt(3.0);
    for (int bits = 0; bits < 8; ++bits) {  // bit 2 -> x sign, bit 1 -> y, bit 0 -> z; 0 = +
      d.emplace_back((bits & 4) ? -s : s, (bits & 2) ? -s : s, (bits & 1) ? -s : s);
    }
  }
  return d;
}

}  // namespace

const char* adjacency_name(EdgeAdjacency adjacency) {
  return adjacency == EdgeAdjacency::kHull ? "hull" : "face_to_diagonal";
}

EdgeAdjacency parse_adjacency(std::string_view name) {
  for (EdgeAdjacency a : {EdgeAdjacency::kHull, EdgeAdjacency::kFaceToDiagonal}) {
    if (name == adjacency_name(a)) return a;
  }
  std::string quoted(1, '\'');
  quoted.append(name);
  quoted.push_back('\'');
  reject("adjacency", quoted, "not one of: hull, face_to_diagonal");
}

void validate_clump_params(const ClumpParams& q) {
  // Every range is the table's (clump_param_table.cpp); the adjacency, an enum, is
  // valid by construction.
  for (const ClumpParamField& f : clump_param_fields()) {
    if (f.kind == ClumpParamKind::kChoice || f.allows(f.value(q))) continue;
    reject(std::string(f.name).c_str(), f.value(q), "not allowed (allowed: " + f.allowed() + ")");
  }
  if (q.d3 > largest_d3(q)) {
    std::ostringstream allowed;
    allowed << "too large with balls_per_direction = " << q.balls_per_direction
            << " (allowed: d3 <= " << largest_d3(q) << ", so that the central ball is at least "
            << q.min_radius_fraction << " of the virtual sphere's radius)";
    reject("d3", q.d3, allowed.str());
  }
}

double largest_d3(const ClumpParams& q) {
  return (1.0 / q.min_radius_fraction - 1.0) / std::max(1, q.balls_per_direction);
}

double virtual_sphere_radius(const ClumpParams& q) {
  return q.virtual_sphere_factor * 0.5 * q.nominal_diameter;
}

double central_ball_radius(const ClumpParams& q) {
  return virtual_sphere_radius(q) / (1.0 + q.balls_per_direction * q.d3);
}

const std::vector<Vec3>& candidate_directions(int directions) {
  static const std::vector<Vec3> six = make_directions(6);
  static const std::vector<Vec3> fourteen = make_directions(14);
  if (directions == 6) return six;
  if (directions == 14) return fourteen;
  reject("directions", directions, "not allowed (6 cube-face normals or 14 with diagonals)");
}

std::vector<std::pair<int, int>> adjacent_direction_pairs(int directions, EdgeAdjacency adjacency) {
  const std::vector<Vec3>& d = candidate_directions(directions);
  const int n = static_cast<int>(d.size());
  std::vector<std::pair<int, int>> pairs;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const bool face_i = i < 6, face_j = j < 6;
      const double cosine = d[i].dot(d[j]);
      bool adjacent = false;
      if (face_i && face_j) {
        // Orthogonal face normals are hull edges of the octahedron, but with the
        // diagonals present the diagonal between them lies further out (their chord
        // passes inside the hull), so they are only adjacent among 6 directions.
        adjacent = directions == 6 && std::abs(cosine) < 0.5;
      } else if (face_i != face_j) {
        // Face normal and diagonal: nearest neighbours share the face's sign,
        // cosine 1/√3; the others have cosine -1/√3.
        adjacent = cosine > 0.0;
      } else {
        // Two diagonals differing in one sign: cosine 1/3 (cube edge). Others: -1/3, -1.
        adjacent = adjacency == EdgeAdjacency::kHull && cosine > 0.0;
      }
      if (adjacent) pairs.emplace_back(i, j);
    }
  }
  return pairs;
}

double expected_ball_count(const ClumpParams& q) {
  validate_clump_params(q);
  const double n_dirs = q.directions;
  const double edges =
      static_cast<double>(adjacent_direction_pairs(q.directions, q.adjacency).size());
  const double edge_balls = q.balls_per_direction > 0 ? q.edge_balls : 0.0;
  return 1.0 + q.p * n_dirs * q.balls_per_direction + q.p * q.p * edges * edge_balls;
}

ClumpGeometry generate_clump(const ClumpParams& q, std::mt19937_64& rng) {
  validate_clump_params(q);
  const std::vector<Vec3>& dirs = candidate_directions(q.directions);
  ClumpGeometry g;
  g.nominal_radius = 0.5 * q.nominal_diameter;
  g.virtual_radius = virtual_sphere_radius(q);
  g.central_radius = central_ball_radius(q);
  const double big_r = g.central_radius;
  const double d3 = q.d3 * big_r;                      // D3, m
  const double max_d4 = q.c * big_r;                   // c, m
  const double floor = q.min_radius_fraction * big_r;  // smallest grown radius, m
  const int n = q.balls_per_direction;

  g.centres.push_back(Vec3::Zero());
  g.radii.push_back(big_r);
  g.origins.push_back(BallOrigin{});

  // Step 3: one draw per candidate direction, all drawn before any ball is grown.
  for (int i = 0; i < static_cast<int>(dirs.size()); ++i) {
    if (uniform_open_closed(rng) <= q.p) g.used_directions.push_back(i);
  }

  // Step 4: grow n balls along each used direction. outermost[i] = ball index.
  std::vector<int> outermost(dirs.size(), -1);
  for (int i : g.used_directions) {
    double x = 0.0, r = big_r;
    for (int k = 1; k <= n; ++k) {
      // D4 ~ U[0, c·R), clamped so that the radius never drops below the floor
      // (the max() guards against r - floor rounding to a hair below zero).
      const double d4 =
          std::clamp(max_d4 * uniform_closed_open(rng), 0.0, std::max(r - floor, 0.0));
      x += d3 + d4;                 // eq 8: x_k = x_{k-1} + D3 + D4
      r = std::max(r - d4, floor);  // eq 6: R_k = R_{k-1} - D4
      g.centres.push_back(x * dirs[i]);
      g.radii.push_back(r);
      g.origins.push_back(BallOrigin{BallKind::kDirection, i, -1, k});
    }
    if (n > 0) outermost[i] = static_cast<int>(g.radii.size()) - 1;
  }

  // Step 6: edges between the outermost balls of adjacent used directions, with m
  // equally spaced balls at t = j/(m+1) and radii linear in t (Fig. 6).
  const int m = q.edge_balls;
  if (n > 0 && m > 0) {
    for (auto [a, b] : adjacent_direction_pairs(q.directions, q.adjacency)) {
      if (outermost[a] < 0 || outermost[b] < 0) continue;
      const Vec3 ca = g.centres[outermost[a]], cb = g.centres[outermost[b]];
      const double ra = g.radii[outermost[a]], rb = g.radii[outermost[b]];
      for (int j = 1; j <= m; ++j) {
        const double t = static_cast<double>(j) / (m + 1);
        g.centres.push_back((1.0 - t) * ca + t * cb);
        g.radii.push_back((1.0 - t) * ra + t * rb);
        g.origins.push_back(BallOrigin{BallKind::kEdge, a, b, j});
      }
    }
  }
  // Step 5 (virtual sphere) holds by construction: grown balls reach R + k·D3 <= Rv,
  // and an edge ball's far point is a convex combination of its ends' far points.
  return g;
}

std::mt19937_64 clump_rng(std::uint64_t seed, std::uint64_t index) {
  // std::seed_seq's mixing is specified by the standard, so this is portable.
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(index), static_cast<std::uint32_t>(index >> 32)};
  return std::mt19937_64(seq);
}

}  // namespace ballast
