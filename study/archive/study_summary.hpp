// The comparison table printed at the end of `ballast study` and `ballast merge`,
// read back from the archive so that it covers every run it holds, those of earlier
// (resumed) sessions included.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace ballast {

struct SummaryRow {
  long long index = 0;
  std::string id;
  std::string sample;  // the matrix sample the run belongs to (its replicates share it)
  bool ok = false;
  bool loaded = false;  // ran the load cycle (not stopped after preparation)
  std::string message;
  double porosity = 0.0;         // 5 mm grid under the sleeper, before loading
  long long contacts = 0;        // ball-ball contacts before loading
  double balls_per_body = 0.0;   // 1 for spheres
  double sphericity = 0.0;       // mean over the clump templates; 0 for spheres
  double rotation_deg = 0.0;     // mean rotation during loading
  double displacement_mm = 0.0;  // largest displacement at peak load
  double settlement_mm = 0.0;    // sleeper settlement at peak load
  double resilient_mm = 0.0;     // settlement at peak less the permanent settlement
  double sleeper_bodies = 0.0;   // particles touching the sleeper at peak load (a count)
  long long cycles = 0;          // load cycles recorded (0: not loaded, or an older archive)
  double permanent_mm = 0.0;     // sleeper settlement after the last cycle
  double log_slope_mm = 0.0;     // its growth per decade of cycles (least squares on log10 N)
  double wall_seconds = 0.0;
};

// Every run in the archive, in study order.
std::vector<SummaryRow> read_summary(const std::string& archive);
// The table, then, for every sample with two or more loaded runs, the mean and 95 %
// confidence interval over its replicates (and, for runs of several load cycles, of
// the settlement after N cycles and its slope against log N), then the failed runs
// with their messages.
void print_summary(std::ostream& out, const std::vector<SummaryRow>& rows);

}  // namespace ballast
