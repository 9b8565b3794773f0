// What one run of a study is made of, apart from how the matrix produced it: its id,
// its seed, and the clump its parameters describe. See docs/STUDY.md, "Ids and seeds".
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "cases/clump_presets.hpp"
#include "engine/fnv1a.hpp"  // fnv1a64: a run's text into its seed

namespace ballast {

// Letters, digits and "._+-": what ids and the names in them are made of, so that an id
// is a safe file name everywhere.
bool is_id_char(char ch);
// Non-empty and only id characters: study and sample names.
bool is_safe_name(std::string_view name);
inline constexpr const char* kSafeNameRule = "a non-empty string of letters, digits and . _ + -";

// One step of splitmix64 (Steele, Lea & Flood 2014): a bijective 64-bit mixer.
std::uint64_t splitmix64(std::uint64_t x);

// The text a run's seed is hashed from: {"params":{...},"replicate":k} with keys sorted
// and no spaces (nlohmann::json's dump(); Python's json.dumps(..., sort_keys=True,
// separators=(",", ":")) gives the same bytes for the values a study holds).
std::string canonical_run_text(const nlohmann::json& params, int replicate);

// splitmix64(splitmix64(study_seed) ^ fnv1a64(canonical_run_text(params, replicate))).
// Depends on nothing but the run itself, so adding runs to a study leaves it unchanged.
std::uint64_t run_seed(std::uint64_t study_seed, const nlohmann::json& params, int replicate);

// "<sample>-<key>=<value>-...-r<replicate>": the sample's name (left out when empty),
// then the keys the matrix varies (axes and zip groups) in sorted order, then the
// replicate. Characters other than letters, digits and "._+-" become '_', so an id is
// a safe file name: shape=table2/sample1 reads "shape=table2_sample1".
std::string run_id(const std::string& sample, const nlohmann::json& varied, int replicate);

// The clump a run's parameters describe: the preset named by "shape" (or ClumpParams'
// defaults when there is no shape but clump parameters are given), with the clump
// parameters overriding its fields and n turned into p = n / directions. nullopt when
// the run has no clumps ("shape": "spheres", or no shape and no clump parameter: the
// scene decides). Throws StudyError whose path points into params ("/n") when p and
// n are both given, n exceeds directions, or clump parameters come with "spheres".
std::optional<ClumpPreset> resolve_run_clump(const nlohmann::json& params);

}  // namespace ballast
