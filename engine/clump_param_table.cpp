#include "engine/clump_param_table.hpp"

#include <cmath>
#include <limits>
#include <vector>

#include "engine/errors.hpp"

namespace ballast {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

constexpr ClumpParamField integer(std::string_view name, bool required, int ClumpParams::*m,
                                  double lo, double hi, std::string_view choices,
                                  std::string_view description) {
  return {name,     ClumpParamKind::kInteger,
          required, true,
          m,        nullptr,
          nullptr,  lo,
          hi,       false,
          false,    choices,
          "",       description};
}

constexpr ClumpParamField number(std::string_view name, bool required, bool overridable,
                                 double ClumpParams::*m, double lo, bool lo_open, double hi,
                                 bool hi_open, std::string_view unit,
                                 std::string_view description) {
  return {name,     ClumpParamKind::kNumber,
          required, overridable,
          nullptr,  m,
          nullptr,  lo,
          hi,       lo_open,
          hi_open,  "",
          unit,     description};
}

// In the order the docs list them. Ranges are those of the construction (docs/CLUMPS.md).
constexpr ClumpParamField kFields[] = {
    integer("directions", true, &ClumpParams::directions, 6, 14, "6|14",
            "candidate directions: 6 cube-face normals, 14 with the space diagonals"),
    number("p", true, true, &ClumpParams::p, 0, false, 1, false, "",
           "probability that a candidate direction is used"),
    integer("balls_per_direction", true, &ClumpParams::balls_per_direction, 0, kInf, "",
            "balls grown along a used direction"),
    number("c", true, true, &ClumpParams::c, 0, false, 1, true, "fraction of R",
           "largest radius reduction D4"),
    number("d3", true, true, &ClumpParams::d3, 0, false, kInf, true, "fraction of R",
           "clump extension D3 (eq 8)"),
    integer("edge_balls", true, &ClumpParams::edge_balls, 0, kInf, "",
            "balls on each edge between adjacent directions"),
    number("virtual_sphere_factor", true, true, &ClumpParams::virtual_sphere_factor, 0, true, kInf,
           true, "", "Rv / (nominal diameter / 2)"),
    {"adjacency", ClumpParamKind::kChoice, false, true, nullptr, nullptr, &ClumpParams::adjacency,
     0, 0, false, false, "hull|face_to_diagonal", "",
     "direction pairs joined by edge balls (docs/CLUMPS.md)"},
    number("nominal_diameter", false, false, &ClumpParams::nominal_diameter, 0, true, kInf, true,
           "m", "diameter of the sphere the clump stands for"),
    number("min_radius_fraction", false, false, &ClumpParams::min_radius_fraction, 0, true, 1, true,
           "fraction of R", "smallest radius a grown ball may have"),
};

std::string format(double x) {
  if (std::isinf(x)) return "inf";
  std::string s = std::to_string(x);
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s;
}

}  // namespace

std::vector<std::string> split_choices(std::string_view choices) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= choices.size()) {
    const std::size_t bar = std::min(choices.find('|', start), choices.size());
    out.emplace_back(choices.substr(start, bar - start));
    start = bar + 1;
  }
  return out;
}

bool ClumpParamField::allows(double x) const {
  if (kind == ClumpParamKind::kChoice) return false;
  if (!choices.empty()) {  // integers allowed by value: "6|14"
    for (const std::string& c : split_choices(choices))
      if (std::stod(c) == x) return true;
    return false;
  }
  if (std::isnan(x)) return false;
  if (kind == ClumpParamKind::kInteger && x != std::floor(x)) return false;
  const bool lo_ok = lo_open ? x > lo : x >= lo;
  const bool hi_ok = hi == kInf ? std::isfinite(x) : (hi_open ? x < hi : x <= hi);
  return lo_ok && hi_ok;
}

bool ClumpParamField::allows_text(std::string_view name) const {
  if (kind != ClumpParamKind::kChoice) return false;
  for (const std::string& c : split_choices(choices))
    if (c == name) return true;
  return false;
}

std::string ClumpParamField::allowed() const {
  std::string text;
  if (!choices.empty()) {
    const std::vector<std::string> c = split_choices(choices);
    for (std::size_t i = 0; i < c.size(); ++i) {
      if (i > 0) text += i + 1 == c.size() ? " or " : ", ";
      text += kind == ClumpParamKind::kChoice ? "\"" + c[i] + "\"" : c[i];
    }
  } else if (hi == kInf) {
    text = (lo_open ? "> " : ">= ") + format(lo);
  } else {
    text = std::string("in ") + (lo_open ? "(" : "[") + format(lo) + ", " + format(hi) +
           (hi_open ? ")" : "]");
  }
  if (!unit.empty()) text += " (" + std::string(unit) + ")";
  return text;
}

double ClumpParamField::value(const ClumpParams& q) const {
  switch (kind) {
    case ClumpParamKind::kInteger:
      return q.*int_member;
    case ClumpParamKind::kNumber:
      return q.*double_member;
    case ClumpParamKind::kChoice:
      return static_cast<double>(q.*choice_member);
  }
  return 0.0;
}

void ClumpParamField::set(ClumpParams& q, double x) const {
  if (kind == ClumpParamKind::kInteger) q.*int_member = static_cast<int>(x);
  if (kind == ClumpParamKind::kNumber) q.*double_member = x;
}

std::string ClumpParamField::text(const ClumpParams& q) const {
  return adjacency_name(q.*choice_member);
}

void ClumpParamField::set_text(ClumpParams& q, std::string_view name) const {
  q.*choice_member = parse_adjacency(name);
}

std::span<const ClumpParamField> clump_param_fields() {
  return kFields;
}

const ClumpParamField* find_clump_param(std::string_view name) {
  for (const ClumpParamField& f : kFields)
    if (f.name == name) return &f;
  return nullptr;
}

std::string clump_param_names(bool overridable_only) {
  std::string names;
  for (const ClumpParamField& f : kFields)
    if (f.overridable || !overridable_only)
      names += (names.empty() ? "" : ", ") + std::string(f.name);
  return names;
}

}  // namespace ballast
