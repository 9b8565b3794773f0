// The error a study file raises when it must be refused before anything runs (see
// docs/STUDY.md, "Error messages"). It is a SetupError (bad input, engine/errors.hpp),
// with its parts kept apart so that the command line can map it to its own exit code
// and tests can check each part:
//
//   "<origin> at <path>: <problem> (allowed: <allowed>)"
//
// path is a JSON Pointer (RFC 6901) into the study file, e.g. /matrix/axes/p/2, and
// empty when the problem is the file as a whole (unreadable, not JSON).
#pragma once

#include <string>
#include <utility>

#include "engine/errors.hpp"

namespace ballast {

struct StudyError : SetupError {
  StudyError(std::string origin_, std::string path_, std::string problem_, std::string allowed_)
      : SetupError(compose(origin_, path_, problem_, allowed_)),
        origin(std::move(origin_)),
        path(std::move(path_)),
        problem(std::move(problem_)),
        allowed(std::move(allowed_)) {}

  std::string origin;   // the file (or what the caller named the JSON)
  std::string path;     // JSON Pointer to the offending value or key
  std::string problem;  // what is wrong, with the offending value
  std::string allowed;  // what would have been accepted

 private:
  static std::string compose(const std::string& origin, const std::string& path,
                             const std::string& problem, const std::string& allowed) {
    std::string s = origin;
    if (!path.empty()) s += " at " + path;
    s += ": " + problem;
    if (!allowed.empty()) s += " (allowed: " + allowed + ")";
    return s;
  }
};

// One reference token of a JSON Pointer: '~' and '/' escaped as RFC 6901 asks, so that
// a key such as "a/b" cannot be mistaken for two levels.
inline std::string json_pointer_token(const std::string& key) {
  std::string out;
  for (char ch : key) {
    if (ch == '~') {
      out += "~0";
    } else if (ch == '/') {
      out += "~1";
    } else {
      out += ch;
    }
  }
  return out;
}

// parent + "/" + escaped key, e.g. child_path("/matrix/axes", "p") = "/matrix/axes/p".
inline std::string child_path(const std::string& parent, const std::string& key) {
  return parent + "/" + json_pointer_token(key);
}
inline std::string child_path(const std::string& parent, std::size_t index) {
  return parent + "/" + std::to_string(index);
}

}  // namespace ballast
