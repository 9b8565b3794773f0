// Small RAII and writing helpers over the HDF5 C API, shared by the archives.
// Every failure throws std::runtime_error naming what could not be done.
#pragma once

#include <hdf5.h>

#include <algorithm>
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
  Handle(Handle&& o) noexcept : id_(o.id_), close_(o.close_) { o.id_ = -1; }
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  operator hid_t() const { return id_; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// HDF5 prints its error stack to stderr unless told not to, and (in Debian's
// thread-safe build) the setting is per thread: every entry point that may run on a
// worker thread calls this first. Errors become exceptions instead.
inline void quiet_errors() {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

inline void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5: cannot " + what);
}

// A fixed-length string type of `size` bytes holding UTF-8 (ASCII is UTF-8).
inline Handle string_type(std::size_t size) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy string type");
  check(H5Tset_size(type, size == 0 ? 1 : size), "size string type");
  check(H5Tset_cset(type, H5T_CSET_UTF8), "set string type to UTF-8");
  return type;
}

inline void string_attribute(hid_t target, const char* name, const std::string& value) {
  Handle type = string_type(value.size());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create scalar space");
  Handle attr(H5Acreate2(target, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  const char* data = value.empty() ? "" : value.c_str();
  check(H5Awrite(attr, type, data), std::string("write attribute ") + name);
}

// Doubles for floating-point values, unsigned 64-bit for unsigned ones (seeds),
// signed 64-bit for the other integers.
template <class T>
void number_attribute(hid_t target, const char* name, T value) {
  const hid_t type = std::is_floating_point_v<T> ? H5T_NATIVE_DOUBLE
                     : std::is_unsigned_v<T>     ? H5T_NATIVE_ULLONG
                                                 : H5T_NATIVE_LLONG;
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create scalar space");
  Handle attr(H5Acreate2(target, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose,
              std::string("create attribute ") + name);
  if constexpr (std::is_floating_point_v<T>) {
    const double v = value;
    check(H5Awrite(attr, type, &v), std::string("write attribute ") + name);
  } else if constexpr (std::is_unsigned_v<T>) {
    const unsigned long long v = value;
    check(H5Awrite(attr, type, &v), std::string("write attribute ") + name);
  } else {
    const long long v = static_cast<long long>(value);
    check(H5Awrite(attr, type, &v), std::string("write attribute ") + name);
  }
}

// A dataset of doubles (or ints) with shape `dims`, row-major data, and its units.
// `creation`: dataset creation properties (chunking, filters); default none.
template <class T>
void dataset(hid_t group, const char* name, const std::vector<hsize_t>& dims,
             const std::vector<T>& data, const std::string& units, hid_t creation = H5P_DEFAULT) {
  const hid_t type = std::is_floating_point_v<T> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT;
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
               std::string("create space for ") + name);
  Handle set(H5Dcreate2(group, name, type, space, H5P_DEFAULT, creation, H5P_DEFAULT), H5Dclose,
             std::string("create dataset ") + name);
  if (!data.empty()) {
    check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()),
          std::string("write dataset ") + name);
  }
  string_attribute(set, "units", units);
}

// A 1-D dataset of doubles (or ints) stored in chunks and deflate-compressed: the
// per-cycle records and series that grow to 10^5 entries and more. Readers see an
// ordinary dataset. Empty data is stored as an empty plain dataset (a chunk cannot be
// empty).
template <class T>
void compressed_dataset(hid_t group, const char* name, const std::vector<T>& data,
                        const std::string& units) {
  if (data.empty()) return dataset(group, name, {0}, data, units);
  const hsize_t chunk = std::min<hsize_t>(data.size(), 8192);
  Handle plist(H5Pcreate(H5P_DATASET_CREATE), H5Pclose, "create dataset properties");
  check(H5Pset_chunk(plist, 1, &chunk), std::string("chunk dataset ") + name);
  // The shuffle filter groups the bytes of like significance: smooth series of
  // doubles compress about twice as well with it.
  check(H5Pset_shuffle(plist), std::string("shuffle dataset ") + name);
  check(H5Pset_deflate(plist, 4), std::string("compress dataset ") + name);
  dataset(group, name, {static_cast<hsize_t>(data.size())}, data, units, plist);
}

// A scalar string dataset (texts too long or too free-form for an attribute: logs).
inline void text_dataset(hid_t group, const char* name, const std::string& text) {
  Handle type = string_type(text.size());
  Handle space(H5Screate(H5S_SCALAR), H5Sclose, "create scalar space");
  Handle set(H5Dcreate2(group, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Dclose,
             std::string("create dataset ") + name);
  check(H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, text.empty() ? "" : text.c_str()),
        std::string("write dataset ") + name);
}

inline Handle create_group(hid_t parent, const std::string& name) {
  return Handle(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                "create group " + name);
}

}  // namespace ballast::h5
