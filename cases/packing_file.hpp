// Packing files: the plain-text exchange format for beds of spheres and clumps, so
// that packings move between Ballast, LAMMPS, YADE and whatever a user has.
//
// Whitespace-separated numbers in SI units (m), one ball per line:
//     x y z r          spheres (4 columns), every line a body of its own
//     body x y z r     clumps (5 columns): consecutive lines with the same integer
//                      body id form one rigid clump
// '#' starts a comment (to the end of the line); blank lines are ignored. A file is
// all spheres or all clumps: every data line has the same column count.
//
// Written with 17 significant digits, which every IEEE double survives exactly: at
// the benchmark's stiffness the overlaps in a settled bed are about 1e-9 m, and six
// digits (1e-7 m at 0.1 m) would turn the bed into an explosion. No velocities,
// orientations or contact history: a packing is a start state at rest.
//
// No JSON, no HDF5: the reader is plain C++ so that anything can link it.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "engine/types.hpp"

namespace ballast {

struct Packing {
  bool clumps = false;         // the file had a body column
  std::vector<Vec3> centre;    // ball centres, m
  std::vector<double> radius;  // m
  // Bodies as ball ranges: body k owns balls [body_first[k], body_first[k + 1]).
  // Spheres: one ball each. Size bodies + 1.
  std::vector<Index> body_first{0};
  std::vector<long> body_id;  // the id written in the file (clumps); k for spheres
  std::vector<long> line;     // line of each ball in the file it came from (0: not from a file)
  std::string source;         // file name the packing came from, for error messages

  Index balls() const { return static_cast<Index>(radius.size()); }
  Index bodies() const { return static_cast<Index>(body_first.size()) - 1; }
  Index ball_count(Index body) const { return body_first[body + 1] - body_first[body]; }
  // "bed.txt:12" for ball k, for messages that point back into the file.
  std::string where(Index ball) const;

  // Appends one body of balls (a sphere when it has one ball and the packing is not
  // a clump packing).
  void add_body(long id, const std::vector<Vec3>& centres, const std::vector<double>& radii);
};

// Reads a packing; SetupError names file:line, the value and what is allowed.
Packing read_packing_file(const std::string& path);
Packing parse_packing(std::istream& in, const std::string& name);

// Writes x y z r (spheres) or body x y z r (clumps) with 17 significant digits, after
// a '#' header: `comment` (one line, may be empty) and the column legend. Body ids
// are written as 0, 1, 2... in body order.
void write_packing(std::ostream& out, const Packing& p, const std::string& comment);
void write_packing_file(const std::string& path, const Packing& p, const std::string& comment);

}  // namespace ballast
