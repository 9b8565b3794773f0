#include "study/matrix/study_matrix.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <map>
#include <set>
#include <unordered_map>
#include <utility>

#include "cases/clump_presets.hpp"
#include "study/matrix/run_identity.hpp"
#include "study/matrix/study_factors.hpp"
#include "study/matrix/study_json.hpp"
#include "study/matrix/study_keys.hpp"

namespace ballast {
namespace {

using nlohmann::json;
using ojson = nlohmann::ordered_json;

class Expander {
 public:
  explicit Expander(std::string origin)
      : origin_(std::move(origin)), presets_(available_clump_presets()) {}

  StudySpec expand(const ojson& study) {
    if (!study.is_object()) {
      fail("", "the study is " + study.dump(), "a JSON object with name, scene, seed, matrix");
    }
    allow_only_keys(study, "", {"name", "scene", "seed", "matrix", "description", "notes"},
                    origin_);
    StudySpec spec;
    spec.source = study;
    const ojson& name = required_key(study, "", "name", origin_);
    if (!name.is_string() || !is_safe_name(name.get<std::string>())) {
      fail("/name", "name = " + name.dump(), kSafeNameRule);
    }
    spec.name = name.get<std::string>();
    spec.scene = nonempty_string(required_key(study, "", "scene", origin_), "/scene");
    spec.scene_path = spec.scene;
    spec.seed = study_seed(required_key(study, "", "seed", origin_));
    if (study.contains("description")) nonempty_string(study.at("description"), "/description");
    if (study.contains("notes")) notes(study.at("notes"));
    const MatrixFactors m =
        read_matrix_factors(required_key(study, "", "matrix", origin_), origin_, presets_);
    check_count(m.factors, m.replicates.size());
    spec.runs = product(m.factors, m.replicates, spec.seed, m.common_seeds);
    check_distinct(spec.runs);
    return spec;
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& problem,
                         const std::string& allowed) const {
    throw StudyError(origin_, path, problem, allowed);
  }

  // path is /scene or /description: the key is the path without its slash.
  std::string nonempty_string(const ojson& v, const std::string& path) const {
    if (!v.is_string() || v.get<std::string>().empty()) {
      fail(path, path.substr(1) + " = " + v.dump(), "a non-empty string");
    }
    return v.get<std::string>();
  }

  void notes(const ojson& v) const {
    const bool ok =
        v.is_string() ||
        (v.is_array() && std::all_of(v.begin(), v.end(), [](auto& x) { return x.is_string(); }));
    if (!ok) fail("/notes", "notes = " + v.dump(), "a string or a list of strings");
  }

  std::uint64_t study_seed(const ojson& v) const {
    if (!v.is_number_integer() || (!v.is_number_unsigned() && v.get<std::int64_t>() < 0)) {
      fail("/seed", "seed = " + v.dump(), "an unsigned integer below 2^64");
    }
    return v.get<std::uint64_t>();
  }

  void check_count(const std::vector<Factor>& factors, std::size_t replicates) const {
    std::size_t total = replicates;
    std::string sizes = std::to_string(replicates) + " replicates";
    for (const Factor& d : factors) {
      sizes = std::to_string(d.rows.size()) + " x " + sizes;
      // Divide rather than multiply so that the check itself cannot overflow.
      total = total > kMaxStudyRuns / d.rows.size() ? kMaxStudyRuns + 1 : total * d.rows.size();
    }
    if (total > kMaxStudyRuns) {
      fail("/matrix",
           "the matrix expands to more than " + std::to_string(kMaxStudyRuns) + " runs (" + sizes +
               ")",
           "at most " + std::to_string(kMaxStudyRuns) + " runs per study");
    }
  }

  // The product, first factor outermost, replicates innermost. Runs of spheres skip the
  // factors made only of clump parameters (they would be the same run again under
  // another id): such a run appears once, at the first combination that reaches it.
  std::vector<RunSpec> product(const std::vector<Factor>& factors,
                               const std::vector<int>& replicates, std::uint64_t study_seed,
                               bool common_seeds) {
    std::vector<RunSpec> runs;
    std::set<std::string> spheres_done;
    std::vector<std::size_t> at(factors.size(), 0);
    for (bool more = true; more; more = advance(at, factors)) {
      bool spheres = false;
      for (std::size_t d = 0; d < factors.size(); ++d) {
        for (const Setting& s : factors[d].rows[at[d]].settings) {
          spheres = spheres || (s.key == "shape" && s.value == "spheres");
        }
      }
      RunSpec base;
      base.params = json::object();
      json varied = json::object();
      std::map<std::string, std::string> where;  // key -> path, for run-level errors
      bool skipped = false;
      for (std::size_t d = 0; d < factors.size(); ++d) {
        if (spheres && factors[d].clump_only) {
          skipped = true;
          continue;
        }
        const FactorRow& row = factors[d].rows[at[d]];
        if (!factors[d].in_id) base.sample = row.sample;
        for (const Setting& s : row.settings) {
          base.params[s.key] = s.value;
          if (factors[d].in_id) varied[s.key] = s.value;
          where[s.key] = s.path;
        }
      }
      if (skipped && !spheres_done.insert(run_id(base.sample, varied, 0)).second) continue;
      for (int r : replicates) {
        RunSpec run = base;
        run.replicate = r;
        run.id = run_id(run.sample, varied, r);
        run.seed = run_seed(study_seed, common_seeds ? json::object() : run.params, r);
        run.index = runs.size();
        runs.push_back(std::move(run));
      }
      check_clump(runs[runs.size() - replicates.size()], where);
    }
    return runs;
  }

  // The next combination, last factor fastest; false after the last.
  static bool advance(std::vector<std::size_t>& at, const std::vector<Factor>& factors) {
    for (std::size_t d = factors.size(); d-- > 0;) {
      if (++at[d] < factors[d].rows.size()) return true;
      at[d] = 0;
    }
    return false;
  }

  // Cross-key rules (p with n, n against directions, clump keys with spheres) once per
  // distinct clump; a failure points at the key's place in the file.
  void check_clump(const RunSpec& run, const std::map<std::string, std::string>& where) {
    json clump = json::object();
    for (const auto& [key, value] : run.params.items()) {
      const StudyKey* k = find_study_key(key);
      if (k->group == "clump" || k->group == "shape") clump[key] = value;
    }
    if (!checked_clumps_.insert(clump.dump()).second) return;
    try {
      resolve_run_clump(run.params);
    } catch (const StudyError& e) {
      const auto it = where.find(e.path.substr(1));
      fail(it == where.end() ? "/matrix" : it->second, e.problem + " in run '" + run.id + "'",
           e.allowed);
    } catch (const SetupError& e) {
      // The preset file itself is broken: the study cannot run as written either.
      const auto it = where.find("shape");
      fail(it == where.end() ? "/matrix" : it->second,
           std::string("the preset cannot be used: ") + e.what(), "a valid preset file");
    }
  }

  void check_distinct(const std::vector<RunSpec>& runs) const {
    std::unordered_map<std::string, std::size_t> ids, contents;
    for (const RunSpec& run : runs) {
      const auto [id, new_id] = ids.try_emplace(run.id, run.index);
      if (!new_id) {
        fail("/matrix",
             "runs " + std::to_string(id->second) + " and " + std::to_string(run.index) +
                 " have the same id '" + run.id + "'",
             "values that stay distinct once made safe for file names");
      }
      const auto [same, new_run] =
          contents.try_emplace(canonical_run_text(run.params, run.replicate), run.index);
      if (!new_run) {
        fail("/matrix/samples",
             "runs '" + runs[same->second].id + "' and '" + run.id +
                 "' have the same parameters and replicate",
             "samples that differ in at least one parameter");
      }
    }
  }

  std::string origin_;
  std::vector<std::string> presets_;
  std::set<std::string> checked_clumps_;  // clump keys of runs already checked
};

}  // namespace

StudySpec expand_study(const nlohmann::ordered_json& study, const std::string& origin) {
  return Expander(origin).expand(study);
}

StudySpec expand_study(const nlohmann::json& study, const std::string& origin) {
  return expand_study(nlohmann::ordered_json::parse(study.dump()), origin);
}

StudySpec load_study_file(const std::string& path) {
  StudySpec spec = expand_study(parse_study_json(read_study_text(path), path), path);
  namespace fs = std::filesystem;
  spec.scene_path = (fs::path(path).parent_path() / spec.scene).lexically_normal().generic_string();
  return spec;
}

}  // namespace ballast
