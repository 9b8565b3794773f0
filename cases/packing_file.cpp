#include "cases/packing_file.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <istream>
#include <map>
#include <ostream>
#include <sstream>

#include "engine/errors.hpp"

namespace ballast {

namespace {

const char* const kSphereColumns[] = {"x", "y", "z", "r"};
const char* const kClumpColumns[] = {"body", "x", "y", "z", "r"};

std::vector<std::string> split_fields(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream s(text);
  for (std::string f; s >> f;) out.push_back(f);
  return out;
}

// One line of the file being read: its fields and where it is, for messages.
struct Line {
  const std::string& name;
  long number;
  std::vector<std::string> fields;

  [[noreturn]] void fail(const std::string& what) const {
    throw SetupError(name + ":" + std::to_string(number) + ": " + what);
  }

  // std::from_chars is correctly rounded, so 17 written digits read back bit for bit.
  double number_at(std::size_t k, const char* column) const {
    const std::string& f = fields[k];
    double v = 0.0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec != std::errc() || end != f.data() + f.size())
      fail(std::string("column ") + std::to_string(k + 1) + " (" + column + ") = '" + f +
           "' is not a number (allowed: a decimal number in SI units, e.g. 0.018125 or 1.8e-2)");
    if (!std::isfinite(v))
      fail(std::string("column ") + std::to_string(k + 1) + " (" + column + ") = '" + f +
           "' (allowed: a finite number)");
    return v;
  }

  long body_id() const {
    const std::string& f = fields[0];
    long v = 0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec != std::errc() || end != f.data() + f.size() || v < 0)
      fail("column 1 (body) = '" + f + "' (allowed: a non-negative integer body id)");
    return v;
  }
};

}  // namespace

std::string Packing::where(Index ball) const {
  const long l = ball >= 0 && ball < static_cast<Index>(line.size()) ? line[ball] : 0;
  if (source.empty()) return "ball " + std::to_string(ball);
  return l > 0 ? source + ":" + std::to_string(l) : source + " ball " + std::to_string(ball);
}

void Packing::add_body(long id, const std::vector<Vec3>& centres,
                       const std::vector<double>& radii) {
  for (std::size_t k = 0; k < radii.size(); ++k) {
    centre.push_back(centres[k]);
    radius.push_back(radii[k]);
    line.push_back(0);
  }
  body_first.push_back(balls());
  body_id.push_back(id);
}

Packing parse_packing(std::istream& in, const std::string& name) {
  Packing p;
  p.source = name;
  std::size_t columns = 0;  // of the first data line; every other line must match
  long first_data_line = 0;
  std::map<long, long> seen;  // body id -> line it first appeared on (closed bodies)
  long current = -1, current_line = 0;
  std::string text;
  for (long number = 1; std::getline(in, text); ++number) {
    const auto hash = text.find('#');
    Line line{name, number, split_fields(hash == std::string::npos ? text : text.substr(0, hash))};
    if (line.fields.empty()) continue;
    const std::size_t n = line.fields.size();
    if (columns == 0) {
      if (n != 4 && n != 5)
        line.fail(std::to_string(n) +
                  " columns (allowed: 4 for spheres, x y z r, or 5 for "
                  "clumps, body x y z r)");
      columns = n;
      first_data_line = number;
      p.clumps = n == 5;
    } else if (n != columns) {
      line.fail(std::to_string(n) + " columns, but line " + std::to_string(first_data_line) +
                " has " + std::to_string(columns) +
                " (allowed: the same on every line; a file holds spheres, x y z r, or clumps, "
                "body x y z r)");
    }
    const std::size_t o = p.clumps ? 1 : 0;
    const char* const* names = p.clumps ? kClumpColumns : kSphereColumns;
    const Vec3 x(line.number_at(o, names[o]), line.number_at(o + 1, names[o + 1]),
                 line.number_at(o + 2, names[o + 2]));
    const double r = line.number_at(o + 3, names[o + 3]);
    if (!(r > 0.0)) line.fail("radius r = " + line.fields[o + 3] + " (allowed: > 0 m)");
    if (!p.clumps) {
      p.body_id.push_back(p.bodies());
    } else {
      const long id = line.body_id();
      if (id != current) {
        if (const auto it = seen.find(id); it != seen.end())
          line.fail("body " + std::to_string(id) + " reappears after body " +
                    std::to_string(current) + " (allowed: a body's balls on consecutive lines; " +
                    "body " + std::to_string(id) + " started on line " +
                    std::to_string(it->second) + ")");
        if (current >= 0) {
          seen.emplace(current, current_line);
          p.body_first.push_back(p.balls());
        }
        current = id;
        current_line = number;
        p.body_id.push_back(id);
      }
    }
    p.centre.push_back(x);
    p.radius.push_back(r);
    p.line.push_back(number);
    if (!p.clumps) p.body_first.push_back(p.balls());
  }
  if (in.bad()) throw SetupError(name + ": read error");
  if (p.balls() == 0)
    throw SetupError(name +
                     ": no particles (allowed: one ball per line, x y z r for spheres or "
                     "body x y z r for clumps; '#' comments)");
  if (p.clumps) p.body_first.push_back(p.balls());
  return p;
}

Packing read_packing_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SetupError("cannot read packing file '" + path + "'");
  return parse_packing(in, path);
}

void write_packing(std::ostream& out, const Packing& p, const std::string& comment) {
  if (!comment.empty()) out << "# " << comment << "\n";
  out << "# " << p.bodies() << " bodies, " << p.balls()
      << " balls; SI units (m); columns: " << (p.clumps ? "body x y z r" : "x y z r") << "\n";
  char buffer[128];
  for (Index b = 0; b < p.bodies(); ++b) {
    for (Index k = p.body_first[b]; k < p.body_first[b + 1]; ++k) {
      const Vec3& x = p.centre[k];
      // %.17g: the shortest format that gives back every double exactly.
      if (p.clumps)
        std::snprintf(buffer, sizeof buffer, "%d %.17g %.17g %.17g %.17g\n", b, x.x(), x.y(), x.z(),
                      p.radius[k]);
      else
        std::snprintf(buffer, sizeof buffer, "%.17g %.17g %.17g %.17g\n", x.x(), x.y(), x.z(),
                      p.radius[k]);
      out << buffer;
    }
  }
}

void write_packing_file(const std::string& path, const Packing& p, const std::string& comment) {
  std::ofstream out(path);
  if (!out) throw SetupError("cannot write packing file '" + path + "'");
  write_packing(out, p, comment);
  out.flush();
  if (!out) throw SetupError("error while writing packing file '" + path + "'");
}

}  // namespace ballast
