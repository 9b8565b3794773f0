#include "study/archive/file_image.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace ballast::h5 {

namespace {

// Memory grows in steps of this many bytes as the file is built.
constexpr std::size_t kGrowth = std::size_t(1) << 20;

hid_t core_access() {
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  if (fapl >= 0 && H5Pset_fapl_core(fapl, kGrowth, 0) < 0) {
    H5Pclose(fapl);
    return -1;
  }
  return fapl;
}

// HDF5 knows files by name, in memory too: each gets its own.
std::string memory_name(const std::string& what) {
  static std::atomic<unsigned long> count{0};
  return what + " (in memory #" + std::to_string(++count) + ")";
}

[[noreturn]] void fail(const std::string& path, int err, const std::string& tmp) {
  if (!tmp.empty()) ::unlink(tmp.c_str());
  throw std::runtime_error("cannot write " + path + ": " + std::strerror(err));
}

}  // namespace

MemoryFile::MemoryFile(std::string what)
    : fapl_(core_access(), H5Pclose, "set up an in-memory file for " + what),
      file_(H5Fcreate(memory_name(what).c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl_), H5Fclose,
            "create " + what + " in memory"),
      what_(std::move(what)) {}

void MemoryFile::save(const std::string& path) const {
  check(H5Fflush(file_, H5F_SCOPE_GLOBAL), "flush " + what_ + " in memory");
  const ssize_t size = H5Fget_file_image(file_, nullptr, 0);
  if (size < 0) throw std::runtime_error("HDF5: cannot take the image of " + what_);
  std::vector<char> image(static_cast<std::size_t>(size));
  if (H5Fget_file_image(file_, image.data(), image.size()) != size)
    throw std::runtime_error("HDF5: cannot take the image of " + what_);
  write_file_atomically(path, image.data(), image.size());
}

void write_file_atomically(const std::string& path, const void* data, std::size_t size) {
  const std::string tmp = path + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) fail(path, errno, "");
  const char* p = static_cast<const char*>(data);
  std::size_t left = size;
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : EIO;
      ::close(fd);
      fail(path, err, tmp);
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  // A full disk may show only here, when delayed blocks are allocated.
  if (::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    fail(path, err, tmp);
  }
  if (::close(fd) != 0) fail(path, errno, tmp);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) fail(path, errno, tmp);
  // The new name on disk too (power loss, not only a kill).
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  const int dfd = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
}

}  // namespace ballast::h5
