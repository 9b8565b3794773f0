// Output paths checked before a run starts, so that a run of many minutes never ends
// with "cannot create" and its results lost (issue: an unwritable -o used to be found
// only after the simulation).
#pragma once

#include <string>

namespace ballast {

// Throws SetupError naming `option`, the path and the cause unless a file can be
// created at `path`: its directory exists and takes a new file (probed by creating and
// removing one beside it), and `path` itself is not a directory.
void check_writable_file(const std::string& option, const std::string& path);

// The same for a directory of output files: created if missing, then probed.
void check_writable_directory(const std::string& option, const std::string& dir);

}  // namespace ballast
