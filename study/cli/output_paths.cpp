#include "study/cli/output_paths.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "engine/errors.hpp"

namespace ballast {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void refuse(const std::string& option, const std::string& path,
                         const std::string& cause) {
  throw SetupError("cannot write " + option + " = '" + path + "': " + cause +
                   " (allowed: a path this user can write; nothing was run)");
}

// Creates and removes a file in `dir`; the cause when that fails, "" when it works.
std::string probe(const fs::path& dir) {
  const fs::path p = dir / (".ballast-write-probe-" + std::to_string(::getpid()));
  std::FILE* f = std::fopen(p.c_str(), "wx");
  if (!f) return std::strerror(errno);
  std::fclose(f);
  std::remove(p.c_str());
  return "";
}

}  // namespace

void check_writable_file(const std::string& option, const std::string& path) {
  const fs::path p(path);
  std::error_code ec;
  if (fs::is_directory(p, ec)) refuse(option, path, "it is a directory");
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(dir, ec)) refuse(option, path, "'" + dir.string() + "' is not a directory");
  const std::string cause = probe(dir);
  if (!cause.empty())
    refuse(option, path, "its directory does not take a new file (" + cause + ")");
}

void check_writable_directory(const std::string& option, const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) refuse(option, dir, ec.message());
  const std::string cause = probe(dir);
  if (!cause.empty()) refuse(option, dir, "it does not take a new file (" + cause + ")");
}

}  // namespace ballast
