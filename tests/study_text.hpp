// Studies written inside a test: JSON text in, the StudySpec `ballast study` would run
// out. One place for what the study tests used to write each for themselves.
#pragma once

#include <cstdint>
#include <string>

#include "study/matrix/study_json.hpp"
#include "study/matrix/study_matrix.hpp"

namespace ballast::study_text {

// The study file's name in messages ("t.json at /matrix/...: ...").
inline const std::string kFile = "t.json";

// A study of `scene` with the given "matrix" object (JSON text) and seed; `extra` adds
// top-level members and starts with a comma.
inline std::string with_matrix(const std::string& matrix, const std::string& scene = "s.json",
                               std::uint64_t seed = 2007, const std::string& extra = "") {
  return R"({"name": "t", "scene": ")" + scene + R"(", "seed": )" + std::to_string(seed) + extra +
         R"(, "matrix": )" + matrix + "}";
}

// Parses and expands study text as `ballast study` does with a file named kFile.
inline StudySpec expand(const std::string& text) {
  return expand_study(parse_study_json(text, kFile), kFile);
}

}  // namespace ballast::study_text
