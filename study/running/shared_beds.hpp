// Runs of a study that prepare the same bed share it (docs/STUDY.md, "Shared beds"):
// runs whose scenes differ only in what the loading reads, on the same seed
// (cases/shared_bed.hpp), as a loading-rate axis on common seeds. The first of them to
// start writes the bed into the archive's parts folder when its preparation ends, and
// those that start after that begin there, bit for bit where their own preparation
// would have ended. A bed is removed with the last run that may use it (a full-scale
// Sample 2 bed is about 55 MB).
#pragma once

#include <cstddef>
#include <mutex>
#include <string>
#include <vector>

#include "cases/box_test_checkpoint.hpp"

namespace ballast {

class SharedBeds {
 public:
  // bed_texts: bed_defining_text of the runs to do, in the order they start; parts:
  // the archive's parts folder (a bed left there by a killed study is used too).
  SharedBeds(const std::vector<std::string>& bed_texts, const std::string& parts);

  // Fills run k's bed fields of `plan` (nothing for a run that shares no bed).
  void assign(std::size_t k, CheckpointPlan& plan) const;
  // Run k has ended, finished or failed: its bed goes once no run left may use it.
  void ended(std::size_t k);

  std::size_t beds() const { return beds_.size(); }
  // Runs that may start from a bed another run prepares.
  std::size_t receivers() const;

 private:
  struct Bed {
    std::string path, text;
    std::size_t writer = 0;  // the first of its runs to start
    std::size_t left = 0;    // its runs not yet ended
  };
  std::vector<long> bed_of_;  // per run: its index in beds_, or -1
  std::vector<Bed> beds_;
  std::mutex mutex_;
};

}  // namespace ballast
