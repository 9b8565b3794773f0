// The parameters a study may vary, in one registry: each key's kind, the values it
// accepts and what it means. The clump parameters come from the clump parameter
// table (engine/clump_param_table.hpp); any other key is one line in kOtherKeys
// (study_keys.cpp), its scene key in study_scene.cpp, and one row in docs/STUDY.md;
// the matrix expansion and its error messages follow.
#pragma once

#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace ballast {

enum class KeyKind {
  kInteger,  // a JSON integer that fits in 32 bits (1.0 is refused, as in the presets)
  kNumber,   // any JSON number; integers are stored as doubles
  kText,     // one of a fixed list of strings
  kShape,    // "spheres" or the name of a clump preset (cases/presets)
  kLaw,      // the name of a contact law (engine/contact_laws.hpp)
};

// An interval of numbers; open ends exclude the bound, infinite ends are unbounded.
struct KeyRange {
  double lo, hi;
  bool lo_open, hi_open;
};

struct StudyKey {
  std::string_view name;
  KeyKind kind;
  KeyRange range;            // kInteger, kNumber
  std::string_view choices;  // kText, or a kInteger's only values: "pfc|full", "6|14"
  std::string_view group;  // "clump" (a clump parameter), "shape", "sample", "numerics", "loading"
  std::string_view allowed;  // shown instead of the text made from range/choices if set
  std::string_view description;
};

// Every key, in the order of docs/STUDY.md's table.
std::span<const StudyKey> study_keys();
// nullptr when the key is unknown.
const StudyKey* find_study_key(std::string_view name);
// "directions, p, n, ..." for error messages.
std::string study_key_names();
// What a key accepts, as the error messages print it: "a number in [0, 1]",
// "\"pfc\" or \"full\"", "\"spheres\" or a preset: table1/sample1, ...".
std::string allowed_values(const StudyKey& key, const std::vector<std::string>& presets);

// Checks one value written at `path` and returns it in canonical form (integers as
// int64, numbers as double, so that 1 and 1.0 are the same value of a number key).
// Throws StudyError naming origin, path, the key, the value and allowed_values().
nlohmann::json check_study_value(const StudyKey& key, const nlohmann::ordered_json& value,
                                 const std::string& origin, const std::string& path,
                                 const std::vector<std::string>& presets);

}  // namespace ballast
