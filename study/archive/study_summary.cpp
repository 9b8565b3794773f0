#include "study/archive/study_summary.hpp"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <numeric>
#include <ostream>

#include "study/archive/hdf5_read.hpp"
#include "study/archive/replicate_stats.hpp"
#include "study/archive/study_archive.hpp"

namespace ballast {

using namespace h5;

namespace {

SummaryRow read_row(hid_t g, const std::string& where) {
  const ArchivedRun a = read_archived_run(g, where);
  SummaryRow r;
  r.index = a.index;
  r.id = a.id;
  if (has_attribute(g, "sample")) r.sample = read_text_attribute(g, "sample");
  r.ok = a.ok;
  r.message = a.message;
  r.wall_seconds = read_double_attribute(g, "wall_seconds");
  if (!r.ok) return r;
  r.loaded = read_int_attribute(g, "loaded") != 0;
  r.porosity = read_double_attribute(g, "porosity_grid");
  r.balls_per_body =
      read_double_attribute(g, "balls") / std::max(1.0, read_double_attribute(g, "bodies"));
  Handle before(H5Gopen2(g, "contacts/before", H5P_DEFAULT), H5Gclose,
                "open contacts/before of " + where);
  r.contacts = read_int_attribute(before, "ball_contacts");
  if (has_link(g, "clumps/shape/sphericity")) {
    Handle shape(H5Gopen2(g, "clumps/shape", H5P_DEFAULT), H5Gclose, "open clumps/shape");
    const std::vector<double> s = read_double_dataset(shape, "sphericity");
    if (!s.empty()) r.sphericity = std::accumulate(s.begin(), s.end(), 0.0) / double(s.size());
  }
  r.rotation_deg = read_double_attribute(g, "rotation_loading_mean_deg");
  r.displacement_mm = read_double_attribute(g, "max_displacement_peak") * 1e3;
  r.settlement_mm = read_double_attribute(g, "settlement_peak") * 1e3;
  r.resilient_mm = read_double_attribute(g, "resilient_settlement") * 1e3;
  if (r.loaded && has_link(g, "contacts/peak")) {
    Handle peak(H5Gopen2(g, "contacts/peak", H5P_DEFAULT), H5Gclose,
                "open contacts/peak of " + where);
    if (has_attribute(peak, "sleeper_bodies"))
      r.sleeper_bodies = double(read_int_attribute(peak, "sleeper_bodies"));
  }
  if (r.loaded && has_link(g, "cycles")) {
    Handle cycles(H5Gopen2(g, "cycles", H5P_DEFAULT), H5Gclose, "open cycles of " + where);
    r.cycles = read_int_attribute(cycles, "count");
    r.permanent_mm = read_double_attribute(g, "permanent_settlement") * 1e3;
    r.log_slope_mm = read_double_attribute(cycles, "settlement_log_slope") * 1e3;
  }
  return r;
}

struct Column {
  const char* label;
  double SummaryRow::*field;
  const char* format;
};

// Per sample with two or more runs that `counts` takes: "mean ± half-width" of the
// 95 % interval of each column, under `title`.
void print_replicates(std::ostream& out, const std::vector<SummaryRow>& rows,
                      const std::function<bool(const SummaryRow&)>& counts,
                      const std::string& title, const std::vector<Column>& columns) {
  std::vector<std::string> samples;
  for (const SummaryRow& r : rows)
    if (counts(r) && std::find(samples.begin(), samples.end(), r.sample) == samples.end())
      samples.push_back(r.sample);
  bool header = false;
  char line[400], cell[64];
  for (const std::string& sample : samples) {
    std::vector<const SummaryRow*> runs;
    for (const SummaryRow& r : rows)
      if (counts(r) && r.sample == sample) runs.push_back(&r);
    if (runs.size() < 2) continue;
    if (!header) {
      out << "\n" << title << ": mean ± half-width of the 95 % interval (Student's t)\n";
      std::snprintf(line, sizeof line, "%-10s %3s", "sample", "n");
      out << line;
      for (const Column& c : columns) {
        std::snprintf(cell, sizeof cell, " %17s", c.label);
        out << cell;
      }
      out << "\n";
      header = true;
    }
    std::snprintf(line, sizeof line, "%-10s %3zu", sample.c_str(), runs.size());
    out << line;
    for (const Column& c : columns) {
      std::vector<double> v;
      for (const SummaryRow* r : runs) v.push_back(r->*(c.field));
      const ReplicateStats st = replicate_stats(v);
      std::snprintf(cell, sizeof cell, c.format, st.mean, st.half_width);
      std::snprintf(line, sizeof line, " %17s", cell);
      out << line;
    }
    out << "\n";
  }
}

void print_replicates(std::ostream& out, const std::vector<SummaryRow>& rows) {
  print_replicates(out, rows, [](const SummaryRow& r) { return r.ok && r.loaded; },
                   "over replicates",
                   {{"porosity", &SummaryRow::porosity, "%.3f ± %.3f"},
                    {"rot (deg)", &SummaryRow::rotation_deg, "%.3f ± %.3f"},
                    {"disp. (mm)", &SummaryRow::displacement_mm, "%.2f ± %.2f"},
                    {"settl. (mm)", &SummaryRow::settlement_mm, "%.3f ± %.3f"},
                    {"resil. (mm)", &SummaryRow::resilient_mm, "%.3f ± %.3f"},
                    {"bearing", &SummaryRow::sleeper_bodies, "%.1f ± %.1f"}});
  // Runs of several cycles, grouped by sample and cycle count together: the
  // settlement after N cycles and its growth per decade of N.
  std::vector<long long> counts;
  for (const SummaryRow& r : rows)
    if (r.ok && r.cycles >= 2 && std::find(counts.begin(), counts.end(), r.cycles) == counts.end())
      counts.push_back(r.cycles);
  for (long long n : counts)
    print_replicates(out, rows, [n](const SummaryRow& r) { return r.ok && r.cycles == n; },
                     "after " + std::to_string(n) + " load cycles",
                     {{"perm. (mm)", &SummaryRow::permanent_mm, "%.3f ± %.3f"},
                      {"mm/decade", &SummaryRow::log_slope_mm, "%.3f ± %.3f"}});
}

}  // namespace

std::vector<SummaryRow> read_summary(const std::string& archive) {
  quiet_errors();
  Handle fapl = archive_file_access();
  Handle file(H5Fopen(archive.c_str(), H5F_ACC_RDONLY, fapl), H5Fclose, "open " + archive);
  Handle runs(H5Gopen2(file, "runs", H5P_DEFAULT), H5Gclose, "open /runs in " + archive);
  std::vector<SummaryRow> rows;
  for (const std::string& name : link_names(runs)) {
    Handle g(H5Gopen2(runs, name.c_str(), H5P_DEFAULT), H5Gclose, "open run " + name);
    rows.push_back(read_row(g, archive + ":/runs/" + name));
  }
  std::sort(rows.begin(), rows.end(),
            [](const SummaryRow& a, const SummaryRow& b) { return a.index < b.index; });
  return rows;
}

void print_summary(std::ostream& out, const std::vector<SummaryRow>& rows) {
  std::size_t width = 4;
  for (const SummaryRow& r : rows) width = std::max(width, r.id.size());
  const int w = static_cast<int>(width);
  char line[400];
  std::snprintf(line, sizeof line, "%-*s %-6s %8s %8s %7s %6s %9s %9s %10s %8s\n", w, "run",
                "status", "porosity", "contacts", "balls", "spher.", "rot (deg)", "disp. (mm)",
                "settl. (mm)", "wall");
  out << line;
  for (const SummaryRow& r : rows) {
    if (!r.ok) {
      std::snprintf(line, sizeof line, "%-*s %-6s %8s %8s %7s %6s %9s %9s %10s %8s\n", w,
                    r.id.c_str(), "failed", "-", "-", "-", "-", "-", "-", "-",
                    std::to_string(std::lround(r.wall_seconds)).append(" s").c_str());
    } else {
      char sph[16] = "-";
      if (r.sphericity > 0.0) std::snprintf(sph, sizeof sph, "%.3f", r.sphericity);
      char rot[16] = "-", disp[16] = "-", settl[16] = "-";
      if (r.loaded) {
        std::snprintf(rot, sizeof rot, "%.3f", r.rotation_deg);
        std::snprintf(disp, sizeof disp, "%.2f", r.displacement_mm);
        std::snprintf(settl, sizeof settl, "%.3f", r.settlement_mm);
      }
      std::snprintf(line, sizeof line, "%-*s %-6s %8.3f %8lld %7.2f %6s %9s %9s %10s %6ld s\n", w,
                    r.id.c_str(), "ok", r.porosity, r.contacts, r.balls_per_body, sph, rot, disp,
                    settl, std::lround(r.wall_seconds));
    }
    out << line;
  }
  print_replicates(out, rows);
  bool any_failed = false;
  for (const SummaryRow& r : rows) {
    if (r.ok) continue;
    if (!any_failed) out << "\nfailed runs:\n";
    any_failed = true;
    out << "  " << r.id << ": " << r.message << "\n";
  }
}

}  // namespace ballast
