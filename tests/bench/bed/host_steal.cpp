#include "tests/bench/bed/host_steal.hpp"

#include <fstream>
#include <sstream>

namespace ballast {

std::optional<CpuTicks> parse_proc_stat(const std::string& text) {
  std::istringstream in(text);
  std::string label;
  if (!(in >> label) || label != "cpu") return std::nullopt;
  // user nice system idle iowait irq softirq steal (guest time is already in user).
  long long field[8];
  for (long long& f : field)
    if (!(in >> f) || f < 0) return std::nullopt;
  CpuTicks t;
  for (long long f : field) t.total += f;
  t.idle = field[3] + field[4];
  t.steal = field[7];
  return t;
}

std::optional<CpuTicks> read_cpu_ticks() {
  std::ifstream f("/proc/stat");
  std::string line;
  if (!f || !std::getline(f, line)) return std::nullopt;
  return parse_proc_stat(line);
}

void StealMeter::begin() {
  start_ = read_cpu_ticks();
}

void StealMeter::end() {
  const std::optional<CpuTicks> now = read_cpu_ticks();
  if (!start_ || !now) {
    failed_ = true;
    return;
  }
  wanted_ += (now->total - now->idle) - (start_->total - start_->idle);
  steal_ += now->steal - start_->steal;
  start_.reset();
}

std::optional<double> StealMeter::share() const {
  if (failed_ || wanted_ <= 0) return std::nullopt;
  return double(steal_) / double(wanted_);
}

}  // namespace ballast
