// Walls: rigid boundaries that balls touch but that are not integrated as bodies.
// Two shapes cover the box test:
//  - Plane: infinite and one-sided; `normal` points to the side where balls live.
//  - Box: a solid axis-aligned box (the sleeper); balls stay outside it. One
//    closest-point test per ball, so edges and corners never give double contacts
//    (a box made of six rectangles would). Its edges and corners may be rounded
//    (edge_radius): the box is then the points within edge_radius of a smaller core
//    box, as a sleeper with chamfered or worn edges. The contact laws see every wall
//    as flat there too (Hertz–Mindlin's radius is the ball's alone).
// Each wall has its own stiffness and friction and moves with a velocity that is
// fixed (zero), prescribed by the user, or set every step by a servo.
#pragma once

#include <string>
#include <vector>

#include "engine/material.hpp"
#include "engine/types.hpp"

namespace ballast {

enum class WallShape { Plane, Box };
enum class WallMotion { Fixed, Prescribed, Servo };

struct Wall {
  std::string name;
  WallShape shape = WallShape::Plane;
  // Plane: a point on it and its unit normal. Box: lower and upper corners.
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
  double edge_radius = 0.0;  // m; Box only: 0 is sharp, else below half the smallest side
  Material material;
  WallMotion motion = WallMotion::Fixed;
  Vec3 velocity = Vec3::Zero();      // m/s; must stay zero while Fixed
  Vec3 displacement = Vec3::Zero();  // m, total since the start
};

// Where a ball (centre x, radius r) touches a wall, if it does.
struct WallTouch {
  double overlap;  // m, > 0 when touching
  Vec3 normal;     // unit, from the wall towards the ball centre
  Vec3 point;      // contact point on the wall surface
};

// Distance-based test shared by the neighbour search (with a skin) and the force
// loop (skin = 0). Returns overlap = r + skin - distance, so > 0 means "within".
WallTouch touch_wall(const Wall& w, const Vec3& x, double r);

// Ball–wall candidates: every (ball, wall) with the ball within its radius + skin
// of the wall, in ball order then wall order (so the keys come sorted). Built in
// parallel, the same lists on any number of threads.
void find_wall_candidates(const std::vector<Wall>& walls, const std::vector<Vec3>& positions,
                          const std::vector<double>& radii, double skin,
                          std::vector<Index>& out_ball, std::vector<Index>& out_wall);

// Moves the wall by velocity·dt.
void advance_wall(Wall& w, double dt);

// The inward-facing planes of an axis-aligned container [lo, hi]. With open_top the
// +z face is left out (the box test is open above the ballast). Faces are named
// "xmin", "xmax", "ymin", "ymax", "base" (z min) and "lid" (z max).
std::vector<Wall> box_container(const Vec3& lo, const Vec3& hi, const Material& sides,
                                const Material& base, bool open_top);

// Refuses a wall whose geometry or material (the parameters contact law number
// `law` reads, contact_laws.hpp) is out of range.
void validate_wall(const Wall& w, int law);

}  // namespace ballast
