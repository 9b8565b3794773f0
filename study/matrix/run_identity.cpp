#include "study/matrix/run_identity.hpp"

#include <algorithm>
#include <stdexcept>

#include "cases/clump_overrides.hpp"
#include "engine/clump_generator.hpp"
#include "study/matrix/study_error.hpp"
#include "study/matrix/study_keys.hpp"

namespace ballast {
namespace {

using nlohmann::json;

std::string id_text(const json& value) {
  const std::string raw = value.is_string() ? value.get<std::string>() : value.dump();
  std::string out;
  for (char ch : raw) {
    const bool safe = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                      (ch >= '0' && ch <= '9') || ch == '.' || ch == '_' || ch == '+' || ch == '-';
    out += safe ? ch : '_';
  }
  return out;
}

bool is_clump_key(const std::string& name) {
  const StudyKey* k = find_study_key(name);
  return k != nullptr && k->group == "clump";
}

[[noreturn]] void reject(const std::string& key, const std::string& problem,
                         const std::string& allowed) {
  // The origin is filled in by whoever knows which file the run came from.
  throw StudyError("run parameters", child_path("", key), problem, allowed);
}

}  // namespace

bool is_id_char(char ch) {
  return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
         ch == '.' || ch == '_' || ch == '+' || ch == '-';
}

bool is_safe_name(std::string_view name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), is_id_char);
}

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::string canonical_run_text(const json& params, int replicate) {
  return json{{"params", params}, {"replicate", replicate}}.dump();
}

std::uint64_t run_seed(std::uint64_t study_seed, const json& params, int replicate) {
  // Mixing the study seed first keeps nearby study seeds (1, 2, ...) far apart.
  return splitmix64(splitmix64(study_seed) ^ fnv1a64(canonical_run_text(params, replicate)));
}

std::string run_id(const std::string& sample, const json& varied, int replicate) {
  std::string id = sample;
  for (const auto& [key, value] : varied.items()) {
    id += (id.empty() ? "" : "-") + key + "=" + id_text(value);
  }
  return id + (id.empty() ? "" : "-") + "r" + std::to_string(replicate);
}

std::optional<ClumpPreset> resolve_run_clump(const json& params) {
  const std::string shape = params.value("shape", std::string());
  std::string first_clump_key;
  for (const auto& [key, value] : params.items()) {
    if (is_clump_key(key) && first_clump_key.empty()) first_clump_key = key;
  }
  if (shape == "spheres") {
    if (!first_clump_key.empty()) {
      reject(first_clump_key,
             "clump parameter " + first_clump_key + " = " + params.at(first_clump_key).dump() +
                 " does not apply to shape \"spheres\"",
             "clump parameters only where shape is a preset or absent");
    }
    return std::nullopt;
  }
  if (shape.empty() && first_clump_key.empty()) return std::nullopt;

  ClumpPreset preset;
  if (shape.empty()) {
    preset.name = "custom";
    preset.source = "ClumpParams defaults with the study's parameters";
  } else {
    preset = load_clump_preset(shape);
  }
  ClumpParams& q = preset.params;
  // The same route as a scene's /particles/clump (cases/clump_overrides.hpp); the
  // values were checked against the same table when the matrix was read.
  apply_clump_overrides(params, "/matrix", q);
  if (params.contains("n")) {
    const double n = params.at("n").get<double>();
    if (params.contains("p")) {
      reject(
          "n",
          "n = " + params.at("n").dump() + " and p = " + params.at("p").dump() + " are both given",
          "p or n in one run, not both; p = n / directions");
    }
    if (!(n >= 0.0 && n <= q.directions)) {
      reject(
          "n",
          "n = " + params.at("n").dump() + " exceeds directions = " + std::to_string(q.directions),
          "a number in [0, directions]");
    }
    q.p = n / q.directions;
  }
  try {
    validate_clump_params(q);
  } catch (const std::invalid_argument& e) {
    reject(first_clump_key.empty() ? "shape" : first_clump_key, e.what(),
           "the ranges of docs/CLUMPS.md");
  }
  return preset;
}

}  // namespace ballast
