// The factors of a study's product, read from its "matrix": the samples, each axis,
// each zip group, and the replicate numbers. Every value is checked against the key
// registry (study_keys.hpp) as it is read, so that an error points at the value in the
// file; how the factors combine into runs is study_matrix.cpp's business.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace ballast {

// One key's value, in canonical form, and the JSON Pointer where it was written.
struct Setting {
  std::string key;
  nlohmann::json value;
  std::string path;
};

// One choice along a factor: the settings it brings (and, for samples, the name).
struct FactorRow {
  std::string sample;
  std::vector<Setting> settings;
};

// The samples, one axis or one zip group. Axis and zip keys appear in run ids; a
// sample is named by its name instead.
struct Factor {
  std::vector<FactorRow> rows;  // never empty
  bool in_id = true;
  bool clump_only = false;  // every key a clump parameter, so it does not apply to spheres
};

struct MatrixFactors {
  std::vector<Factor> factors;  // samples (if any), axes as written, zip groups as written
  std::vector<int> replicates;  // replicate numbers in the order written
  // "common_seeds": true: a replicate's seed depends on its number only, so that every
  // sample and axis value of replicate k starts from the same bed generator stream
  // (common random numbers: a variant's difference from a reference is then not the
  // difference between two realisations as well).
  bool common_seeds = false;
};

// Reads and checks the "matrix" object found at /matrix: unknown keys, types and ranges,
// empty lists, zip lists of unequal length, keys given in two places, repeated values,
// sample names. `presets` are the known clump presets. Throws StudyError.
MatrixFactors read_matrix_factors(const nlohmann::ordered_json& matrix, const std::string& origin,
                                  const std::vector<std::string>& presets);

}  // namespace ballast
