// The clump parameters (ClumpParams, clump_generator.hpp) in one table: name, member,
// unit, allowed values and meaning. Everything that reads or writes them by name
// goes through it: validation (validate_clump_params), the preset files
// (cases/clump_presets.cpp), the scene's /particles/clump overrides
// (cases/clump_overrides.cpp, also the study's route), the study keys
// (study/matrix/study_keys.cpp), the archive (study/archive/clump_archive.cpp) and `ballast clump
// --json`. Adding a parameter is a member in ClumpParams, its row here and its use
// in the generator; ClumpParamTable.EveryMemberHasARow fails while the row is
// missing.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/clump_generator.hpp"

namespace ballast {

enum class ClumpParamKind {
  kInteger,  // an int member
  kNumber,   // a double member
  kChoice,   // an enum member written as one of `choices`
};

struct ClumpParamField {
  std::string_view name;  // as files and the archive write it
  ClumpParamKind kind;
  bool required_in_presets;            // a preset file must give it (else the default stands)
  bool overridable;                    // a scene's /particles/clump and a study may set it
  int ClumpParams::*int_member;        // kInteger
  double ClumpParams::*double_member;  // kNumber
  EdgeAdjacency ClumpParams::*choice_member;  // kChoice
  double lo, hi;                              // kInteger, kNumber: the range
  bool lo_open, hi_open;                      // whether lo, hi themselves are excluded
  std::string_view choices;                   // "6|14" (integers allowed), "hull|face_to_diagonal"
  std::string_view unit;                      // "" (a count or a probability), "fraction of R", "m"
  std::string_view description;

  bool allows(double x) const;
  bool allows_text(std::string_view name) const;  // kChoice: one of `choices`
  // "in [0, 1]", ">= 0", "6 or 14", "\"hull\" or \"face_to_diagonal\"".
  std::string allowed() const;
  // kInteger, kNumber: the member's value; kChoice: the enum's value (its position in
  // `choices`).
  double value(const ClumpParams& q) const;
  // kInteger, kNumber: sets the member (no range check: validate_clump_params does).
  void set(ClumpParams& q, double x) const;
  // kChoice: the member's name, and the member from a name (throws SetupError).
  std::string text(const ClumpParams& q) const;
  void set_text(ClumpParams& q, std::string_view name) const;
};

// The values of a choices string: "6|14" -> {"6", "14"}.
std::vector<std::string> split_choices(std::string_view choices);

// Every clump parameter, in the order the docs list them.
std::span<const ClumpParamField> clump_param_fields();
// nullptr for a name no parameter has.
const ClumpParamField* find_clump_param(std::string_view name);
// "directions, p, ...", for error messages: every parameter, or the overridable ones.
std::string clump_param_names(bool overridable_only);

}  // namespace ballast
