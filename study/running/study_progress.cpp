#include "study/running/study_progress.hpp"

#include <algorithm>
#include <cstdio>

#include "cases/duration_text.hpp"
#include "study/running/run_log.hpp"

namespace ballast {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// "stage 3: compaction at 10 g, then 1 g" -> "3/4 compaction" (box_test_prepare.hpp's
// stages; 2 is the clumps', which spheres skip).
std::string stage_label(const std::string& stage) {
  static const char* const names[] = {"", "spheres", "clumps", "compaction", "loading"};
  const std::size_t colon = stage.find(':');
  if (stage.rfind("stage ", 0) != 0 || colon == std::string::npos) return stage;
  const std::string number = stage.substr(6, colon - 6);
  const int n = number.size() == 1 ? number[0] - '0' : 0;
  return n >= 1 && n <= 4 ? number + "/4 " + names[n] : stage.substr(0, colon);
}

}  // namespace

ProgressBoard::ProgressBoard(std::ostream& out, bool live, std::size_t to_do, std::size_t done,
                             int jobs)
    : out_(out), live_(live), to_do_(to_do), done_before_(done), jobs_(std::max(jobs, 1)) {}

// Mean wall time of the runs finished so far, for every run not finished: those not
// started in full, those in flight for what they have left, shared among the jobs.
std::string ProgressBoard::eta_text() const {
  if (finished_ == 0) return "ETA after the first run";
  const double mean = finished_seconds_ / double(finished_);
  const std::size_t queued = to_do_ - finished_ - active_.size();
  double left = double(queued) * mean;
  for (const auto& [id, a] : active_) left += std::max(0.0, mean - seconds_since(a.start));
  return "ETA " + duration_text(left / jobs_);
}

std::string ProgressBoard::counts_text() const {
  const std::size_t total = to_do_ + done_before_;
  std::string s = std::to_string(done_before_ + finished_) + "/" + std::to_string(total) + " done";
  if (failed_ > 0) s += " (" + std::to_string(failed_) + " failed)";
  return s;
}

void ProgressBoard::erase_block() {
  if (!live_ || block_lines_ == 0) return;
  // Cursor up to the block's first line, then clear to the end of the screen.
  out_ << "\033[" << block_lines_ << "F\033[J";
  block_lines_ = 0;
}

void ProgressBoard::draw_block() {
  if (!live_ || closed_) return;
  for (const auto& [id, a] : active_) {
    char line[256];
    std::snprintf(line, sizeof line, "  %-30s %8s  stage %-14s %9ld steps%s%s\n", id.c_str(),
                  duration_text(seconds_since(a.start)).c_str(), stage_label(a.stage).c_str(),
                  a.steps, a.step.empty() ? "" : ", last: ", a.step.c_str());
    out_ << line;
    ++block_lines_;
  }
  out_ << "  " << counts_text() << ", " << active_.size() << " running, " << eta_text() << "\n";
  ++block_lines_;
  out_.flush();
}

void ProgressBoard::started(const RunSpec& run, int threads) {
  std::lock_guard<std::mutex> lock(mutex_);
  active_[run.id] = Active{Clock::now(), "-", "", 0, threads};
  if (live_) {
    erase_block();
    draw_block();
  } else {
    out_ << "start  " << run.id << " (" << threads << " thread" << (threads == 1 ? "" : "s")
         << ", seed " << run.seed << ")\n"
         << std::flush;
  }
}

void ProgressBoard::log_line(const RunSpec& run, const std::string& line) {
  std::lock_guard<std::mutex> lock(mutex_);
  const LogProgress p = parse_log_line(line);
  const auto it = active_.find(run.id);
  if (it != active_.end()) {
    if (!p.stage.empty()) it->second.stage = p.stage;
    if (!p.step.empty()) {
      it->second.step = p.step;
      it->second.steps += p.step_count;
    }
  }
  if (!live_) out_ << "  " << run.id << " | " << line << "\n" << std::flush;
}

void ProgressBoard::finished(const RunRecord& r) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = active_.find(r.spec.id);
  // A finished box test knows its own time, including what it ran before a resume
  // (kept in its checkpoint); this board saw only the part since. The whole is what a
  // run costs, and what the ETA needs.
  const double seconds = r.ok && r.result      ? r.result->wall_seconds
                         : it != active_.end() ? seconds_since(it->second.start)
                                               : r.wall_seconds;
  if (it != active_.end()) active_.erase(it);
  ++finished_;
  failed_ += r.ok ? 0 : 1;
  finished_seconds_ += seconds;
  char head[160];
  std::snprintf(head, sizeof head, "%-6s %s in %s", r.ok ? "ok" : "FAILED", r.spec.id.c_str(),
                duration_text(seconds).c_str());
  std::string line = head;
  if (r.ok && r.result) {
    char more[160];
    std::snprintf(more, sizeof more, ": porosity %.3f, settlement %.3f mm at peak",
                  r.result->porosity_grid, r.result->settlement_peak * 1e3);
    line += more;
  } else if (!r.ok) {
    line += ": " + r.message;
  }
  line += "  [" + counts_text() + ", " + eta_text() + "]";
  erase_block();
  out_ << line << "\n";
  draw_block();
  out_.flush();
}

void ProgressBoard::note(const std::string& text) {
  std::lock_guard<std::mutex> lock(mutex_);
  erase_block();
  out_ << text << "\n";
  draw_block();
  out_.flush();
}

void ProgressBoard::redraw() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!live_ || closed_) return;
  erase_block();
  draw_block();
}

void ProgressBoard::close() {
  std::lock_guard<std::mutex> lock(mutex_);
  erase_block();
  closed_ = true;
  out_.flush();
}

std::size_t ProgressBoard::in_flight() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return active_.size();
}

}  // namespace ballast
