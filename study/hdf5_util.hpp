// Small RAII and writing helpers over the HDF5 C API, shared by the archives.
// Every failure throws std::runtime_error naming what could not be done.
#pragma once

#include <hdf5.h>

#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace ballast::h5 {

// Owns one HDF5 identifier and closes it with the matching function.
class Handle {
 public:
  Handle(hid_t id, herr_t (*close)(hid_t), const std::string& what) : id_(id), close_(close) {
    if (id_ < 0) throw std::runtime_error("HDF5: cannot " + what);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { close_(id_); }
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

inline void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5: cannot " + what);
}

inline void string_attribute(hid_t target, const char* name, const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy string type");
  check(H5Tset_size(type, value.empty() ? 1 : value.size()), "size string type");
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create scalar space");
  Handle attr(H5Acreate2(target, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  const char* data = value.empty() ? "" : value.c_str();
  check(H5Awrite(attr, type, data), std::string("write attribute ") + name);
}

template <class T>
void number_attribute(hid_t target, const char* name, T value) {
  const hid_t type = std::is_floating_point_v<T> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_LLONG;
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create scalar space");
  Handle attr(H5Acreate2(target, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  if constexpr (std::is_floating_point_v<T>) {
    const double v = value;
    check(H5Awrite(attr, type, &v), std::string("write attribute ") + name);
  } else {
    const long long v = static_cast<long long>(value);
    check(H5Awrite(attr, type, &v), std::string("write attribute ") + name);
  }
}

// A dataset of doubles (or ints) with shape `dims`, row-major data, and its units.
template <class T>
void dataset(hid_t group, const char* name, const std::vector<hsize_t>& dims,
             const std::vector<T>& data, const std::string& units) {
  const hid_t type = std::is_floating_point_v<T> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT;
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
               std::string("create space for ") + name);
  Handle set(H5Dcreate2(group, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
             std::string("create dataset ") + name);
  if (!data.empty()) {
    check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
          std::string("write dataset ") + name);
  }
  string_attribute(set, "units", units);
}

}  // namespace ballast::h5
