// Reading back what hdf5_util.hpp writes: attributes, text datasets, the names in a
// group. Used by the study archive (resume, merge, summary) and its tests. Every
// failure throws std::runtime_error naming the object and what could not be read.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <vector>

namespace ballast::h5 {

bool has_attribute(hid_t target, const char* name);
// A string attribute (fixed or variable length), as its bytes.
std::string read_text_attribute(hid_t target, const char* name);
// Numeric attributes, converted by HDF5 from whatever integer or float type they hold.
double read_double_attribute(hid_t target, const char* name);
long long read_int_attribute(hid_t target, const char* name);
std::uint64_t read_uint64_attribute(hid_t target, const char* name);

// A scalar string dataset (text_dataset()).
std::string read_text_dataset(hid_t group, const char* name);
// A dataset of doubles, flattened row-major, and its shape.
std::vector<double> read_double_dataset(hid_t group, const char* name,
                                        std::vector<hsize_t>* dims = nullptr);

// Whether `path` (relative to `where`) names a link, and the names of the links in a
// group in name order.
bool has_link(hid_t where, const std::string& path);
std::vector<std::string> link_names(hid_t group);

// The innermost message on HDF5's error stack ("file is already open for write ..."),
// for reports after a failed call; empty when the stack is empty.
std::string last_hdf5_error();

}  // namespace ballast::h5
