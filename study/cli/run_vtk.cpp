#include "study/cli/run_vtk.hpp"

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace ballast {

namespace {

std::ofstream open(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write VTK file '" + path + "'");
  out.precision(9);
  return out;
}

void write_contacts(const std::string& path, const ContactSnapshot& c) {
  std::ofstream out = open(path);
  const std::size_t n = c.force.size();
  out << "# vtk DataFile Version 3.0\nballast contact forces\nASCII\nDATASET POLYDATA\n";
  out << "POINTS " << 2 * n << " double\n";
  for (std::size_t k = 0; k < n; ++k)
    out << c.from[k].transpose() << "\n" << c.to[k].transpose() << "\n";
  out << "LINES " << n << " " << 3 * n << "\n";
  for (std::size_t k = 0; k < n; ++k) out << "2 " << 2 * k << " " << 2 * k + 1 << "\n";
  out << "CELL_DATA " << n << "\nSCALARS force double 1\nLOOKUP_TABLE default\n";
  for (double f : c.force) out << f << "\n";
}

// a − b per particle; zero where a has no value (a run stopped before loading).
void vectors(std::ofstream& out, const char* name, const std::vector<Vec3>& a,
             const std::vector<Vec3>& b) {
  out << "VECTORS " << name << " double\n";
  for (std::size_t k = 0; k < b.size(); ++k)
    out << (k < a.size() ? Vec3(a[k] - b[k]) : Vec3::Zero()).transpose() << "\n";
}

void scalars(std::ofstream& out, const char* name, const std::vector<double>& v, std::size_t n) {
  out << "SCALARS " << name << " double 1\nLOOKUP_TABLE default\n";
  for (std::size_t k = 0; k < n; ++k) out << (k < v.size() ? v[k] : 0.0) << "\n";
}

}  // namespace

void write_run_vtk(const std::string& dir, const BoxTestResult& r) {
  std::filesystem::create_directories(dir);
  write_contacts(dir + "/contacts_before.vtk", r.before);
  if (r.loaded) {
    write_contacts(dir + "/contacts_peak.vtk", r.at_peak);
    write_contacts(dir + "/contacts_after.vtk", r.after);
  }
  std::ofstream out = open(dir + "/particles.vtk");
  const std::size_t n = r.position_start.size();
  out << "# vtk DataFile Version 3.0\nballast particles\nASCII\nDATASET POLYDATA\n";
  out << "POINTS " << n << " double\n";
  for (const Vec3& x : r.position_start) out << x.transpose() << "\n";
  out << "VERTICES " << n << " " << 2 * n << "\n";
  for (std::size_t k = 0; k < n; ++k) out << "1 " << k << "\n";
  out << "POINT_DATA " << n << "\n";
  vectors(out, "displacement_peak", r.position_peak, r.position_start);
  vectors(out, "displacement_end", r.position_end, r.position_start);
  scalars(out, "rotation_loading", r.rotation_deg_loading, n);
  scalars(out, "rotation_unloading", r.rotation_deg_unloading, n);
  scalars(out, "rotation_cycle", r.rotation_deg_cycle, n);
}

}  // namespace ballast
