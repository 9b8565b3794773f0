#include "study/matrix/study_keys.hpp"

#include <algorithm>
#include <climits>
#include <cstdio>
#include <limits>
#include <vector>

#include "engine/clump_param_table.hpp"
#include "engine/contact_laws.hpp"
#include "study/matrix/study_error.hpp"

namespace ballast {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Readable one-line entries below.
constexpr KeyRange closed(double lo, double hi) {
  return {lo, hi, false, false};
}
constexpr KeyRange closed_open(double lo, double hi) {
  return {lo, hi, false, true};
}
constexpr KeyRange open_closed(double lo, double hi) {
  return {lo, hi, true, false};
}
constexpr KeyRange at_least(double lo) {
  return {lo, kInf, false, true};
}
constexpr KeyRange above(double lo) {
  return {lo, kInf, true, true};
}
constexpr KeyRange kAny = {-kInf, kInf, true, true};

constexpr StudyKey integer(std::string_view name, KeyRange range, std::string_view group,
                           std::string_view description) {
  return {name, KeyKind::kInteger, range, "", group, "", description};
}
constexpr StudyKey number(std::string_view name, KeyRange range, std::string_view group,
                          std::string_view description, std::string_view allowed = "") {
  return {name, KeyKind::kNumber, range, "", group, allowed, description};
}
constexpr StudyKey text(std::string_view name, std::string_view choices, std::string_view group,
                        std::string_view description) {
  return {name, KeyKind::kText, kAny, choices, group, "", description};
}

// The registry. Clump parameters (group "clump") come from the clump parameter table
// (engine/clump_param_table.hpp), with its names, ranges and meanings, so that a bad
// value is reported at its place in the file rather than later, in the middle of a
// run; n (p = n / directions) follows p. The other keys are listed here.
constexpr StudyKey kShapeKey = {
    "shape",
    KeyKind::kShape,
    kAny,
    "",
    "shape",
    "",
    "\"spheres\", or a clump preset whose fields the clump parameters below override"};
constexpr StudyKey kNKey =
    number("n", closed(0, 14), "clump",
           "expected number of used directions, p = n / directions (exclusive with p)",
           "a number in [0, directions]");
constexpr StudyKey kOtherKeys[] = {
    number("dt_safety", open_closed(0, 1), "numerics", "timestep = dt_safety x critical"),
    number(
        "dt", above(0), "numerics",
        "fixed timestep, s, instead of dt_safety x critical (above critical: warned, may blow up)"),
    text("rotation", "pfc|full", "numerics",
         "clump rotation: gyroscopic term dropped as PFC3D 3.x does (eq 17, [W] = 0) or kept"),
    text("mass_mode", "sum|paper|uniform", "numerics", "clump mass properties (docs/CLUMPS.md)"),
    number("local_damping", closed_open(0, 1), "numerics", "PFC local damping coefficient"),
    text("preset", "paper|balanced|fast", "numerics",
         "named numerics preset (docs/TRADEOFFS.md); the run's other keys win over it"),
    number("mass_scale", closed(1, 1e4), "numerics",
           "mass scaling: bodies this many times heavier, gravity as many times weaker"),
    integer("max_stage_steps", at_least(1000), "numerics",
            "step limit of each settling stage of the preparation"),
    {"contact_law", KeyKind::kLaw, kAny, "", "numerics", "",
     "the contact law: PFC's linear springs or Hertz–Mindlin (docs/BOX_TEST.md)"},
    integer("count", at_least(1), "sample",
            "particles: spheres, or clumps replacing them one for one (the paper's 1,936 "
            "spheres, 1,770 Sample 1 and 1,995 Sample 2 clumps)"),
    number("ball_stiffness", above(0), "materials",
           "N/m, kn = ks of the balls (the paper's 5.08e9); lower is cheaper: dt grows as "
           "1 / sqrt(k)"),
    number("wall_stiffness", above(0), "materials",
           "N/m, kn = ks of the box walls and the sleeper (the paper's 5.08e9)"),
    number("density", above(0), "materials",
           "kg/m^3, the particles' density (the paper's 2600); density scaling: dt grows as "
           "sqrt(density)"),
    number("box_length", above(0), "sample",
           "m, the box's length (the paper's 0.7); with count, the sample's scale"),
    number("levelling_pressure", closed(0, 1e6), "loading",
           "Pa, the levelling plate on the bed's top through compaction; 0: a free top"),
    number("gravity_factor", closed(1, 1000), "loading", "enhanced gravity while compacting, x g"),
    number("preload", above(0), "loading",
           "N, the sleeper's preload, where the load cycle starts and ends (the paper's 3 kN)"),
    integer("cycles", at_least(1), "loading", "load cycles of the sleeper"),
    number("frequency", above(0), "loading",
           "Hz, the sleeper's load cycle (the paper's 3; the scene asks for 20 timesteps a "
           "cycle at least)"),
};

StudyKey clump_key(const ClumpParamField& f) {
  const KeyRange range{f.lo, f.hi, f.lo_open, f.hi_open};
  switch (f.kind) {
    case ClumpParamKind::kInteger:
      return {f.name, KeyKind::kInteger, range, f.choices, "clump", "", f.description};
    case ClumpParamKind::kNumber:
      return {f.name, KeyKind::kNumber, range, "", "clump", "", f.description};
    case ClumpParamKind::kChoice:
      break;
  }
  return {f.name, KeyKind::kText, kAny, f.choices, "clump", "", f.description};
}

const std::vector<StudyKey>& all_keys() {
  static const std::vector<StudyKey> keys = [] {
    std::vector<StudyKey> k{kShapeKey};
    for (const ClumpParamField& f : clump_param_fields()) {
      if (!f.overridable) continue;
      k.push_back(clump_key(f));
      if (f.name == "p") k.push_back(kNKey);
    }
    k.insert(k.end(), std::begin(kOtherKeys), std::end(kOtherKeys));
    return k;
  }();
  return keys;
}

std::string format_bound(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

// "a", "a or b", "a, b or c".
std::string either(const std::vector<std::string>& items) {
  std::string s;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) s += i + 1 == items.size() ? " or " : ", ";
    s += items[i];
  }
  return s;
}

std::string range_text(const KeyRange& r) {
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on the
  // chain of operator+ that builds the same string.
  std::string text = r.hi == kInf ? (r.lo_open ? "> " : ">= ") : (r.lo_open ? "(" : "[");
  text += format_bound(r.lo);
  if (r.hi == kInf) return text;
  text += ", ";
  text += format_bound(r.hi);
  text += r.hi_open ? ")" : "]";
  return text;
}

bool in_range(const KeyRange& r, double x) {
  const bool lo_ok = r.lo_open ? x > r.lo : x >= r.lo;
  const bool hi_ok = r.hi_open ? x < r.hi : x <= r.hi;
  return lo_ok && hi_ok;
}

}  // namespace

std::span<const StudyKey> study_keys() {
  return all_keys();
}

const StudyKey* find_study_key(std::string_view name) {
  for (const StudyKey& k : all_keys()) {
    if (k.name == name) return &k;
  }
  return nullptr;
}

std::string study_key_names() {
  std::string s;
  for (const StudyKey& k : all_keys()) s += (s.empty() ? "" : ", ") + std::string(k.name);
  return s;
}

std::string allowed_values(const StudyKey& key, const std::vector<std::string>& presets) {
  if (!key.allowed.empty()) return std::string(key.allowed);
  switch (key.kind) {
    case KeyKind::kInteger:
      if (!key.choices.empty()) return either(split_choices(key.choices));
      return "an integer " + range_text(key.range);
    case KeyKind::kNumber:
      return "a number " + std::string(key.range.hi == kInf ? "" : "in ") + range_text(key.range);
    case KeyKind::kText: {
      std::vector<std::string> quoted;
      for (const std::string& c : split_choices(key.choices)) quoted.push_back('"' + c + '"');
      return either(quoted);
    }
    case KeyKind::kLaw: {
      std::vector<std::string> quoted;
      for (int law = 0; law < kContactLawCount; ++law)
        quoted.push_back('"' + std::string(contact_law_name(law)) + '"');
      return either(quoted);
    }
    case KeyKind::kShape: {
      std::string list;
      for (const std::string& p : presets) list += (list.empty() ? "" : ", ") + p;
      return "\"spheres\" or a clump preset: " + (list.empty() ? "(none found)" : list);
    }
  }
  return "";
}

nlohmann::json check_study_value(const StudyKey& key, const nlohmann::ordered_json& value,
                                 const std::string& origin, const std::string& path,
                                 const std::vector<std::string>& presets) {
  const std::string shown = std::string(key.name) + " = " + value.dump();
  auto reject = [&](const std::string& why) -> void {
    throw StudyError(origin, path, shown + " " + why, allowed_values(key, presets));
  };
  switch (key.kind) {
    case KeyKind::kInteger: {
      if (!value.is_number_integer()) reject("is not an integer");
      // Unsigned values above INT64_MAX and anything beyond 32 bits: no parameter of a
      // box test needs them, and ClumpParams holds ints.
      if (value.is_number_unsigned() && value.get<std::uint64_t>() > INT_MAX) {
        reject("does not fit in a 32-bit integer");
      }
      const std::int64_t v = value.get<std::int64_t>();
      if (v < INT_MIN || v > INT_MAX) reject("does not fit in a 32-bit integer");
      if (!key.choices.empty()) {
        const std::vector<std::string> c = split_choices(key.choices);
        if (std::find(c.begin(), c.end(), std::to_string(v)) == c.end()) reject("is not allowed");
      }
      if (!in_range(key.range, static_cast<double>(v))) reject("is out of range");
      return v;
    }
    case KeyKind::kNumber: {
      if (!value.is_number()) reject("is not a number");
      const double v = value.get<double>();
      if (!in_range(key.range, v)) reject("is out of range");
      return v;
    }
    case KeyKind::kText: {
      if (!value.is_string()) reject("is not a string");
      const std::vector<std::string> c = split_choices(key.choices);
      if (std::find(c.begin(), c.end(), value.get<std::string>()) == c.end()) {
        reject("is not a known value");
      }
      return value.get<std::string>();
    }
    case KeyKind::kLaw: {
      if (!value.is_string()) reject("is not a string");
      if (contact_law_index(value.get<std::string>()) < 0) reject("is not a known contact law");
      return value.get<std::string>();
    }
    case KeyKind::kShape: {
      if (!value.is_string()) reject("is not a string");
      const std::string s = value.get<std::string>();
      if (s != "spheres" && std::find(presets.begin(), presets.end(), s) == presets.end()) {
        reject("is not \"spheres\" or a known preset");
      }
      return s;
    }
  }
  reject("has an unknown kind");
  return {};
}

}  // namespace ballast
