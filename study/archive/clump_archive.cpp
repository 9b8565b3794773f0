#include "study/archive/clump_archive.hpp"

#include <hdf5.h>

#include <stdexcept>

#include "engine/clump_param_table.hpp"
#include "study/archive/file_image.hpp"
#include "study/archive/hdf5_util.hpp"

namespace ballast {

using namespace h5;

void write_clump_sample(hid_t file, const ClumpArchiveHeader& h,
                        const std::vector<ClumpTemplate>& clumps,
                        const std::vector<ClumpShape>& shapes) {
  if (shapes.size() != clumps.size()) {
    throw std::invalid_argument("clump archive: " + std::to_string(shapes.size()) + " shapes for " +
                                std::to_string(clumps.size()) + " clumps");
  }
  const ClumpParams& q = h.params;
  string_attribute(file, "format", "ballast-clumps");
  number_attribute(file, "version", 1);
  string_attribute(file, "preset", h.preset);
  string_attribute(file, "source", h.source);
  number_attribute(file, "seed", h.seed);
  number_attribute(file, "count", static_cast<long long>(clumps.size()));
  string_attribute(file, "mass_mode", mass_mode_name(h.mass.mode));
  number_attribute(file, "density", h.mass.density);
  number_attribute(file, "accuracy", h.mass.accuracy);
  for (const ClumpParamField& f : clump_param_fields()) {  // every parameter, by its name
    const std::string name(f.name);
    if (f.kind == ClumpParamKind::kInteger)
      number_attribute(file, name.c_str(), static_cast<int>(f.value(q)));
    if (f.kind == ClumpParamKind::kNumber) number_attribute(file, name.c_str(), f.value(q));
    if (f.kind == ClumpParamKind::kChoice) string_attribute(file, name.c_str(), f.text(q));
  }
  number_attribute(file, "central_radius", central_ball_radius(q));
  number_attribute(file, "virtual_radius", virtual_sphere_radius(q));
  number_attribute(file, "expected_balls_per_clump", expected_ball_count(q));

  const hsize_t m = clumps.size();
  std::vector<double> radius, offset, mass, inertia, volume, error, centre, rotation;
  std::vector<int> owner, first, count;
  for (std::size_t i = 0; i < clumps.size(); ++i) {
    const ClumpTemplate& t = clumps[i];
    first.push_back(static_cast<int>(radius.size()));
    count.push_back(t.ball_count());
    for (int b = 0; b < t.ball_count(); ++b) {
      radius.push_back(t.radii[b]);
      for (int k = 0; k < 3; ++k) offset.push_back(t.offsets[b][k]);
      owner.push_back(static_cast<int>(i));
    }
    mass.push_back(t.mass);
    volume.push_back(t.volume);
    error.push_back(t.integration_error);
    for (int k = 0; k < 3; ++k) inertia.push_back(t.principal_inertia[k]);
    for (int k = 0; k < 3; ++k) centre.push_back(t.generation_centre[k]);
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) rotation.push_back(t.generation_rotation(r, c));
    }
  }
  const hsize_t n = radius.size();
  {
    Handle g(H5Gcreate2(file, "balls", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
             "create group balls");
    dataset(g, "radius", {n}, radius, "m");
    dataset(g, "offset", {n, 3}, offset, "m");
    dataset(g, "clump", {n}, owner, "1");
  }
  {
    Handle g(H5Gcreate2(file, "clumps", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
             "create group clumps");
    dataset(g, "first_ball", {m}, first, "1");
    dataset(g, "ball_count", {m}, count, "1");
    dataset(g, "mass", {m}, mass, "kg");
    dataset(g, "principal_inertia", {m, 3}, inertia, "kg m^2");
    dataset(g, "volume", {m}, volume, "m^3");
    dataset(g, "integration_error", {m}, error, "1");
    dataset(g, "generation_centre", {m, 3}, centre, "m");
    dataset(g, "generation_rotation", {m, 3, 3}, rotation, "1");
  }
  {
    std::vector<double> uv, area, sph, elong, flat, ratio, dims;
    for (const ClumpShape& s : shapes) {
      uv.push_back(s.union_volume);
      area.push_back(s.surface_area);
      sph.push_back(s.sphericity);
      elong.push_back(s.elongation);
      flat.push_back(s.flatness);
      ratio.push_back(s.volume_ratio);
      dims.insert(dims.end(), {s.a, s.b, s.c});
    }
    Handle g(H5Gcreate2(file, "shape", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
             "create group shape");
    dataset(g, "union_volume", {m}, uv, "m^3");
    dataset(g, "surface_area", {m}, area, "m^2");
    dataset(g, "sphericity", {m}, sph, "1");
    dataset(g, "elongation", {m}, elong, "1");
    dataset(g, "flatness", {m}, flat, "1");
    dataset(g, "volume_ratio", {m}, ratio, "1");
    dataset(g, "dimensions", {m, 3}, dims, "m");
  }
}

void write_clump_archive(const std::string& path, const ClumpArchiveHeader& h,
                         const std::vector<ClumpTemplate>& clumps,
                         const std::vector<ClumpShape>& shapes) {
  quiet_errors();
  MemoryFile file(path);
  write_clump_sample(file, h, clumps, shapes);
  file.save(path);
}

}  // namespace ballast
