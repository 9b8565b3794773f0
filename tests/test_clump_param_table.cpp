// The clump parameter table (engine/clump_param_table.hpp) covers ClumpParams
// member for member, and everything that reads parameters by name reads the table:
// the preset files, a scene's /particles/clump, the study keys.
#include <gtest/gtest.h>

#include <cstddef>
#include <limits>
#include <set>
#include <string>

#include "cases/clump_overrides.hpp"
#include "cases/clump_presets.hpp"
#include "engine/clump_param_table.hpp"
#include "study/matrix/study_keys.hpp"
#include "test_helpers.hpp"

namespace ballast {
namespace {

// Converts to anything: brace-initialising an aggregate with k of these succeeds
// exactly while k is at most its number of members.
struct AnyValue {
  template <class T>
  constexpr operator T() const;  // never defined: used in unevaluated contexts only
};

template <class T, class... Given>
constexpr std::size_t member_count() {
  if constexpr (requires { T{Given{}..., AnyValue{}}; })
    return member_count<T, Given..., AnyValue>();
  else
    return sizeof...(Given);
}

// A member added to ClumpParams without its row would be read by no preset, scene,
// study or archive.
TEST(ClumpParamTable, EveryMemberHasARow) {
  EXPECT_EQ(member_count<ClumpParams>(), clump_param_fields().size());
  std::set<std::string> names;
  for (const ClumpParamField& f : clump_param_fields())
    EXPECT_TRUE(names.insert(std::string(f.name)).second) << f.name;
}

// Each row reaches its own member: a value set through the row is the member's, and
// no other member changes.
TEST(ClumpParamTable, EachRowSetsItsOwnMember) {
  for (const ClumpParamField& f : clump_param_fields()) {
    SCOPED_TRACE(std::string(f.name));
    ClumpParams q;
    if (f.kind == ClumpParamKind::kChoice) {
      f.set_text(q, "face_to_diagonal");
      EXPECT_EQ(q.adjacency, EdgeAdjacency::kFaceToDiagonal);
      EXPECT_EQ(f.text(q), "face_to_diagonal");
      continue;
    }
    const double v = f.kind == ClumpParamKind::kInteger ? 7.0 : 0.123;
    f.set(q, v);
    EXPECT_EQ(f.value(q), v);
    for (const ClumpParamField& g : clump_param_fields()) {
      if (&g == &f || g.kind == ClumpParamKind::kChoice) continue;
      EXPECT_EQ(g.value(q), g.value(ClumpParams{})) << g.name;
    }
  }
}

TEST(ClumpParamTable, DefaultsAreAllowedAndRangesSayWhatTheyAllow) {
  const ClumpParams defaults;
  for (const ClumpParamField& f : clump_param_fields()) {
    if (f.kind == ClumpParamKind::kChoice) continue;
    EXPECT_TRUE(f.allows(f.value(defaults))) << f.name;
  }
  EXPECT_EQ(find_clump_param("p")->allowed(), "in [0, 1]");
  EXPECT_EQ(find_clump_param("c")->allowed(), "in [0, 1) (fraction of R)");
  EXPECT_EQ(find_clump_param("directions")->allowed(), "6 or 14");
  EXPECT_EQ(find_clump_param("edge_balls")->allowed(), ">= 0");
  EXPECT_EQ(find_clump_param("adjacency")->allowed(), "\"hull\" or \"face_to_diagonal\"");
  EXPECT_FALSE(find_clump_param("directions")->allows(8));
  EXPECT_FALSE(find_clump_param("balls_per_direction")->allows(1.5));
  EXPECT_FALSE(find_clump_param("d3")->allows(std::numeric_limits<double>::infinity()));
}

// The study's clump keys are the table's overridable rows, with its ranges.
TEST(ClumpParamTable, StudyKeysAreTheOverridableRows) {
  std::set<std::string> study, table;
  for (const StudyKey& k : study_keys())
    if (k.group == "clump" && k.name != "n") study.insert(std::string(k.name));
  for (const ClumpParamField& f : clump_param_fields())
    if (f.overridable) table.insert(std::string(f.name));
  EXPECT_EQ(study, table);
  EXPECT_EQ(find_study_key("c")->range.hi, 1.0);
  EXPECT_TRUE(find_study_key("c")->range.hi_open);
}

// A scene's overrides go through the table, each checked by its row.
TEST(ClumpParamTable, OverridesAreReadAndCheckedByTheTable) {
  ClumpParams q;
  const nlohmann::json ok = {{"c", 0.4}, {"edge_balls", 3}, {"adjacency", "face_to_diagonal"}};
  JsonFields fields(ok, "/particles/clump");
  read_clump_overrides(fields, q);
  fields.finish();
  EXPECT_EQ(q.c, 0.4);
  EXPECT_EQ(q.edge_balls, 3);
  EXPECT_EQ(q.adjacency, EdgeAdjacency::kFaceToDiagonal);
  const nlohmann::json bad = {{"c", 1.0}};
  JsonFields bad_fields(bad, "/particles/clump");
  test_support::expect_error([&] { read_clump_overrides(bad_fields, q); },
                             {"/particles/clump/c", "in [0, 1) (fraction of R)"});
  // nominal_diameter is the scene's /particles/diameter, not an override.
  const nlohmann::json not_here = {{"nominal_diameter", 0.05}};
  JsonFields not_here_fields(not_here, "/particles/clump");
  read_clump_overrides(not_here_fields, q);
  EXPECT_THROW(not_here_fields.finish(), SetupError);
}

}  // namespace
}  // namespace ballast
