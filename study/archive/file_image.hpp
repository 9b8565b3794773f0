// HDF5 files built in memory and written to disk in one go.
//
// Written in place, a file meets a full disk, a read-only file system or a lost
// permission in the middle of HDF5's own writes: HDF5 then fails to close the file,
// and (libhdf5 1.10) crashed at exit cleaning up after it, taking the study's last
// message with it. Built with the core driver (no backing store) instead, HDF5 never
// touches the disk; save() writes the finished image beside its path, syncs it and
// renames it over, so a file either is complete or is not there, and any failure is
// one POSIX call's, reported with its path and cause.
//
// For files written once and never appended to: run parts, `ballast run -o` and
// `ballast clump -o`. They keep HDF5's earliest superblock, because libhdf5 1.10
// clears the open-for-write flags of a newer one (superblock 2 and 3) in the image
// without updating its checksum, and the file then does not open. The study archive,
// which is appended to in place and relies on superblock 3's flags
// (docs/ARCHIVE.md), is created on disk.
#pragma once

#include <hdf5.h>

#include <string>

#include "study/archive/hdf5_util.hpp"

namespace ballast::h5 {

class MemoryFile {
 public:
  // `what` names the file in messages.
  explicit MemoryFile(std::string what);
  operator hid_t() const { return file_; }

  // Writes the image to `path` (through `path`.tmp, fsync, rename, fsync of the
  // directory). Throws std::runtime_error "cannot write PATH: CAUSE"; nothing is
  // left at `path` or beside it then.
  void save(const std::string& path) const;

 private:
  Handle fapl_;
  Handle file_;
  std::string what_;
};

// Writes `size` bytes to `path` as save() does.
void write_file_atomically(const std::string& path, const void* data, std::size_t size);

}  // namespace ballast::h5
