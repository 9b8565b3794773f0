#include "study/cli/clump_vtk.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace ballast {

std::string write_clump_vtk(const std::string& dir, const std::vector<ClumpTemplate>& clumps,
                            double virtual_radius, const std::string& title) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  const std::string path = (std::filesystem::path(dir) / "clumps.vtk").string();
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write VTK file '" + path + "'");

  std::size_t balls = 0;
  for (const ClumpTemplate& t : clumps) balls += t.radii.size();
  const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(clumps.size()))));
  const double spacing = 2.5 * virtual_radius;

  out.precision(9);
  // The title line may hold at most 256 characters and no newline.
  std::string head = "ballast clumps: " + title;
  for (char& ch : head) ch = ch == '\n' ? ' ' : ch;
  out << "# vtk DataFile Version 3.0\n" << head.substr(0, 255) << "\nASCII\nDATASET POLYDATA\n";
  out << "POINTS " << balls << " double\n";
  for (std::size_t i = 0; i < clumps.size(); ++i) {
    const Vec3 origin(spacing * static_cast<double>(i % columns),
                      spacing * static_cast<double>(i / columns), 0.0);
    for (const Vec3& o : clumps[i].offsets) {
      const Vec3 x = origin + o;
      out << x.x() << ' ' << x.y() << ' ' << x.z() << '\n';
    }
  }
  out << "VERTICES " << balls << ' ' << 2 * balls << '\n';
  for (std::size_t b = 0; b < balls; ++b) out << "1 " << b << '\n';
  out << "POINT_DATA " << balls << "\nSCALARS radius double 1\nLOOKUP_TABLE default\n";
  for (const ClumpTemplate& t : clumps) {
    for (double r : t.radii) out << r << '\n';
  }
  out << "SCALARS clump int 1\nLOOKUP_TABLE default\n";
  for (std::size_t i = 0; i < clumps.size(); ++i) {
    for (std::size_t b = 0; b < clumps[i].radii.size(); ++b) out << i << '\n';
  }
  if (!out) throw std::runtime_error("error while writing VTK file '" + path + "'");
  return path;
}

}  // namespace ballast
