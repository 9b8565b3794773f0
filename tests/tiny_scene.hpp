// tests/data/study/tiny.json, the smallest box test: 40 spheres in a 150 × 120 mm
// box, a preparation of a few thousand steps and one 100 Hz load cycle. For the
// tests that load a bed end to end; they define BALLAST_TEST_DATA (tests/CMakeLists.txt).
#pragma once

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace ballast::test_support {

inline nlohmann::json tiny_scene() {
  std::ifstream in(std::string(BALLAST_TEST_DATA) + "/study/tiny.json");
  return nlohmann::json::parse(in);
}

}  // namespace ballast::test_support
