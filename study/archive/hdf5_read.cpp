#include "study/archive/hdf5_read.hpp"

#include <algorithm>

#include "study/archive/hdf5_util.hpp"

namespace ballast::h5 {

namespace {

// The bytes of a string held in a fixed- or variable-length string type; `read`
// performs the H5Aread/H5Dread into the buffer it is given with the type it is given.
template <class Read>
std::string read_string(hid_t file_type, const std::string& what, Read read) {
  if (H5Tget_class(file_type) != H5T_STRING)
    throw std::runtime_error("HDF5: " + what + " is not text");
  // HDF5 converts between ASCII and UTF-8 in neither direction: read in the file's.
  const H5T_cset_t cset = H5Tget_cset(file_type);
  if (H5Tis_variable_str(file_type) > 0) {
    Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy string type");
    check(H5Tset_size(type, H5T_VARIABLE), "size string type");
    check(H5Tset_cset(type, cset), "set string type's character set");
    char* data = nullptr;
    check(read(type, &data), "read " + what);
    std::string out = data ? data : "";
    H5free_memory(data);
    return out;
  }
  const std::size_t size = H5Tget_size(file_type);
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose, "copy string type");
  check(H5Tset_size(type, size), "size string type");
  check(H5Tset_cset(type, cset), "set string type's character set");
  std::string out(size, '\0');
  check(read(type, out.data()), "read " + what);
  out.resize(out.find('\0') == std::string::npos ? size : out.find('\0'));
  return out;
}

Handle open_attribute(hid_t target, const char* name) {
  return Handle(H5Aopen(target, name, H5P_DEFAULT), H5Aclose,
                std::string("open attribute ") + name);
}

template <class T>
T read_scalar_attribute(hid_t target, const char* name, hid_t memory_type) {
  Handle attr = open_attribute(target, name);
  T value{};
  check(H5Aread(attr, memory_type, &value), std::string("read attribute ") + name);
  return value;
}

}  // namespace

bool has_attribute(hid_t target, const char* name) {
  return H5Aexists(target, name) > 0;
}

std::string read_text_attribute(hid_t target, const char* name) {
  Handle attr = open_attribute(target, name);
  Handle type(H5Aget_type(attr), H5Tclose, std::string("type of attribute ") + name);
  return read_string(type, std::string("attribute ") + name,
                     [&](hid_t memory, void* buffer) { return H5Aread(attr, memory, buffer); });
}

double read_double_attribute(hid_t target, const char* name) {
  return read_scalar_attribute<double>(target, name, H5T_NATIVE_DOUBLE);
}

long long read_int_attribute(hid_t target, const char* name) {
  return read_scalar_attribute<long long>(target, name, H5T_NATIVE_LLONG);
}

std::uint64_t read_uint64_attribute(hid_t target, const char* name) {
  return read_scalar_attribute<unsigned long long>(target, name, H5T_NATIVE_ULLONG);
}

std::string read_text_dataset(hid_t group, const char* name) {
  Handle set(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose, std::string("open dataset ") + name);
  Handle type(H5Dget_type(set), H5Tclose, std::string("type of dataset ") + name);
  return read_string(type, std::string("dataset ") + name, [&](hid_t memory, void* buffer) {
    return H5Dread(set, memory, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer);
  });
}

std::vector<double> read_double_dataset(hid_t group, const char* name, std::vector<hsize_t>* dims) {
  Handle set(H5Dopen2(group, name, H5P_DEFAULT), H5Dclose, std::string("open dataset ") + name);
  Handle space(H5Dget_space(set), H5Sclose, std::string("space of dataset ") + name);
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> shape(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(space, shape.data(), nullptr);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  std::vector<double> out(static_cast<std::size_t>(std::max<hssize_t>(n, 0)));
  if (!out.empty()) {
    check(H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()),
          std::string("read dataset ") + name);
  }
  if (dims) *dims = shape;
  return out;
}

bool has_link(hid_t where, const std::string& path) {
  // H5Lexists checks one level at a time: every intermediate link must exist first.
  std::size_t from = 0;
  while (true) {
    const std::size_t slash = path.find('/', from);
    const std::string prefix = path.substr(0, slash);
    if (H5Lexists(where, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
    if (slash == std::string::npos) return true;
    from = slash + 1;
  }
}

std::vector<std::string> link_names(hid_t group) {
  std::vector<std::string> names;
  const auto collect = [](hid_t, const char* name, const H5L_info_t*, void* data) -> herr_t {
    static_cast<std::vector<std::string>*>(data)->emplace_back(name);
    return 0;
  };
  hsize_t at = 0;
  check(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, &at, collect, &names), "list a group");
  return names;
}

std::string last_hdf5_error() {
  std::string message;
  const auto deepest = [](unsigned, const H5E_error2_t* e, void* data) -> herr_t {
    std::string& m = *static_cast<std::string*>(data);
    if (m.empty() && e->desc && *e->desc) m = e->desc;  // upward: the innermost first
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, deepest, &message);
  return message;
}

}  // namespace ballast::h5
