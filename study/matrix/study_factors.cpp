#include "study/matrix/study_factors.hpp"

#include <cstdint>
#include <map>
#include <utility>

#include "study/matrix/run_identity.hpp"
#include "study/matrix/study_error.hpp"
#include "study/matrix/study_json.hpp"
#include "study/matrix/study_keys.hpp"
#include "study/matrix/study_matrix.hpp"

namespace ballast {
namespace {

using nlohmann::json;
using ojson = nlohmann::ordered_json;

bool only_clump_keys(const Factor& factor) {
  for (const Setting& s : factor.rows.front().settings) {
    if (find_study_key(s.key)->group != "clump") return false;
  }
  return true;
}

class MatrixReader {
 public:
  MatrixReader(const std::string& origin, const std::vector<std::string>& presets)
      : origin_(origin), presets_(presets) {}

  MatrixFactors read(const ojson& matrix) {
    if (!matrix.is_object()) fail("/matrix", "matrix = " + matrix.dump(), "a JSON object");
    allow_only_keys(matrix, "/matrix",
                    {"axes", "zip", "samples", "replicates", "seeds", "common_seeds"}, origin_);
    MatrixFactors m;
    // Samples first: they are the outermost factor.
    if (matrix.contains("samples")) m.factors.push_back(samples(matrix.at("samples")));
    if (matrix.contains("axes")) axes(matrix.at("axes"), m.factors);
    if (matrix.contains("zip")) zip(matrix.at("zip"), m.factors);
    m.replicates = replicate_numbers(matrix);
    if (matrix.contains("common_seeds")) {
      const ojson& c = matrix.at("common_seeds");
      if (!c.is_boolean())
        fail("/matrix/common_seeds", "common_seeds = " + c.dump(), "true or false");
      m.common_seeds = c.get<bool>();
    }
    return m;
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& problem,
                         const std::string& allowed) const {
    throw StudyError(origin_, path, problem, allowed);
  }

  // A parameter key written at `path` in `place` ("axes", "samples", or the zip group's path):
  // known, and in one place only, so that no run is left with two candidate values.
  const StudyKey& claim(const std::string& key, const std::string& path, const std::string& place,
                        const char* extra_allowed = "") {
    const StudyKey* k = find_study_key(key);
    if (k == nullptr) {
      fail(path, "unknown key \"" + key + "\"", extra_allowed + study_key_names());
    }
    const auto [it, fresh] = claims_.try_emplace(key, place, path);
    if (!fresh && it->second.first != place) {
      fail(path, "key \"" + key + "\" is also given at " + it->second.second,
           "each key in only one of axes, one zip group or samples");
    }
    return *k;
  }

  Setting setting(const StudyKey& key, const ojson& value, const std::string& path) const {
    return {std::string(key.name), check_study_value(key, value, origin_, path, presets_), path};
  }

  // A non-empty list of values for one key of an axis or zip group.
  void value_list(const std::string& key, const ojson& list, const std::string& path) const {
    if (!list.is_array()) fail(path, key + " = " + list.dump() + " is not a list", "a list");
    if (list.empty()) fail(path, key + " = [] is an empty list", "a list of at least one value");
  }

  Factor samples(const ojson& list) {
    const std::string path = "/matrix/samples";
    if (!list.is_array() || list.empty()) {
      fail(path, "samples = " + list.dump(), "a non-empty list of objects with a \"name\"");
    }
    Factor factor;
    factor.in_id = false;
    std::map<std::string, std::string> names;  // name -> where first given
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string here = child_path(path, i);
      const ojson& s = list[i];
      if (!s.is_object()) fail(here, "sample = " + s.dump(), "an object with a \"name\"");
      FactorRow row;
      const ojson& name = required_key(s, here, "name", origin_);
      if (!name.is_string() || !is_safe_name(name.get<std::string>())) {
        fail(here + "/name", "name = " + name.dump(), kSafeNameRule);
      }
      row.sample = name.get<std::string>();
      const auto [it, fresh] = names.try_emplace(row.sample, here + "/name");
      if (!fresh) {
        fail(here + "/name", "name = \"" + row.sample + "\" repeats " + it->second,
             "a different name for each sample");
      }
      for (const auto& [key, value] : s.items()) {
        if (key == "name") continue;
        const std::string p = child_path(here, key);
        row.settings.push_back(setting(claim(key, p, "samples", "name, "), value, p));
      }
      factor.rows.push_back(std::move(row));
    }
    return factor;
  }

  void axes(const ojson& axes, std::vector<Factor>& factors) {
    if (!axes.is_object()) fail("/matrix/axes", "axes = " + axes.dump(), "a JSON object");
    for (const auto& [key, list] : axes.items()) {
      const std::string path = child_path("/matrix/axes", key);
      const StudyKey& k = claim(key, path, "axes");
      Factor factor;
      value_list(key, list, path);
      for (std::size_t i = 0; i < list.size(); ++i) {
        factor.rows.push_back(FactorRow{"", {setting(k, list[i], child_path(path, i))}});
      }
      reject_repeated_rows(factor, "distinct values in one axis");
      factor.clump_only = only_clump_keys(factor);
      factors.push_back(std::move(factor));
    }
  }

  void zip(const ojson& groups, std::vector<Factor>& factors) {
    if (!groups.is_array()) {
      fail("/matrix/zip", "zip = " + groups.dump(), "a list of objects of equal-length lists");
    }
    for (std::size_t g = 0; g < groups.size(); ++g) {
      const std::string here = child_path("/matrix/zip", g);
      const ojson& group = groups[g];
      if (!group.is_object() || group.empty()) {
        fail(here, "zip group = " + group.dump(), "a non-empty object of equal-length lists");
      }
      Factor factor;
      std::string first_key;
      for (const auto& [key, list] : group.items()) {
        const std::string path = child_path(here, key);
        const StudyKey& k = claim(key, path, here);
        value_list(key, list, path);
        if (first_key.empty()) {
          first_key = key;
          factor.rows.resize(list.size());
        } else if (list.size() != factor.rows.size()) {
          fail(path,
               key + " has " + std::to_string(list.size()) + " values but " + first_key + " (" +
                   child_path(here, first_key) + ") has " + std::to_string(factor.rows.size()),
               "lists of equal length within a zip group");
        }
        for (std::size_t i = 0; i < list.size(); ++i) {
          factor.rows[i].settings.push_back(setting(k, list[i], child_path(path, i)));
        }
      }
      reject_repeated_rows(factor, "distinct rows in one zip group");
      factor.clump_only = only_clump_keys(factor);
      factors.push_back(std::move(factor));
    }
  }

  // Two equal rows would give two runs with the same id.
  void reject_repeated_rows(const Factor& factor, const char* allowed) const {
    std::map<std::string, std::size_t> seen;
    for (std::size_t i = 0; i < factor.rows.size(); ++i) {
      json values = json::object();
      for (const Setting& s : factor.rows[i].settings) values[s.key] = s.value;
      const auto [it, fresh] = seen.try_emplace(values.dump(), i);
      if (!fresh) {
        const std::string& first = factor.rows[it->second].settings.front().path;
        const std::string& again = factor.rows[i].settings.front().path;
        fail(again, values.dump() + " repeats " + first, allowed);
      }
    }
  }

  std::vector<int> replicate_numbers(const ojson& matrix) const {
    if (matrix.contains("replicates") && matrix.contains("seeds")) {
      fail("/matrix/seeds", "both replicates and seeds are given", "one of replicates or seeds");
    }
    std::vector<int> numbers;
    if (matrix.contains("seeds")) {
      const ojson& seeds = matrix.at("seeds");
      if (!seeds.is_array() || seeds.empty()) {
        fail("/matrix/seeds", "seeds = " + seeds.dump(), "a non-empty list of replicate numbers");
      }
      std::map<int, std::size_t> first_index;  // replicate number -> where first given
      for (std::size_t i = 0; i < seeds.size(); ++i) {
        const ojson& s = seeds[i];
        const std::string path = child_path("/matrix/seeds", i);
        if (!s.is_number_integer() || s.get<std::int64_t>() < 0 ||
            s.get<std::int64_t>() > INT32_MAX) {
          fail(path, "seed = " + s.dump(), "an integer in [0, 2147483647]");
        }
        const auto [it, fresh] = first_index.try_emplace(s.get<int>(), i);
        if (!fresh) {
          fail(path, "seed = " + s.dump() + " repeats " + child_path("/matrix/seeds", it->second),
               "distinct replicate numbers");
        }
        numbers.push_back(s.get<int>());
      }
      return numbers;
    }
    int count = 1;
    if (matrix.contains("replicates")) {
      const ojson& r = matrix.at("replicates");
      if (!r.is_number_integer() || r.get<std::int64_t>() < 1 ||
          r.get<std::int64_t>() > static_cast<std::int64_t>(kMaxStudyRuns)) {
        fail("/matrix/replicates", "replicates = " + r.dump(),
             "an integer in [1, " + std::to_string(kMaxStudyRuns) + "]");
      }
      count = r.get<int>();
    }
    for (int k = 1; k <= count; ++k) numbers.push_back(k);
    return numbers;
  }

  const std::string& origin_;
  const std::vector<std::string>& presets_;
  std::map<std::string, std::pair<std::string, std::string>> claims_;  // key -> place, path
};

}  // namespace

MatrixFactors read_matrix_factors(const ojson& matrix, const std::string& origin,
                                  const std::vector<std::string>& presets) {
  return MatrixReader(origin, presets).read(matrix);
}

}  // namespace ballast
