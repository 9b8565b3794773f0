// The hypervisor's share of the vCPUs' time while a benchmark runs, from the guest
// kernel's /proc/stat.
//
// On a shared virtual machine the host runs other tenants on the physical cores
// behind our vCPUs; the guest kernel counts the time a runnable vCPU waited for one
// as "steal" (proc(5): the eighth field of the cpu lines, in USER_HZ ticks). One
// thread loses what is stolen from its vCPU; two threads that meet at barriers every
// step both wait for what is stolen from either, while two independent copies each
// lose only their own. bench-bed --scaling reports the share beside the speed-up it
// measured, so that a figure can be read against the host (docs/PERFORMANCE.md,
// "The host's steal").
#pragma once

#include <optional>
#include <string>

namespace ballast {

// Cumulative ticks of all vCPUs together since boot.
struct CpuTicks {
  long long total = 0;  // user + nice + system + idle + iowait + irq + softirq + steal
  long long idle = 0;   // idle + iowait: no vCPU wanted to run
  long long steal = 0;  // a vCPU wanted to run and the host ran something else
};

// Parses the aggregate "cpu " line of /proc/stat (the first line). nullopt if the
// text does not start with one that has at least the eight fields up to steal.
std::optional<CpuTicks> parse_proc_stat(const std::string& text);

// The live counters; nullopt where /proc/stat is missing or unreadable (not Linux).
std::optional<CpuTicks> read_cpu_ticks();

// Accumulates the ticks that passed between begin() and end(), over many intervals.
class StealMeter {
 public:
  void begin();
  void end();
  // Stolen over the ticks in which a vCPU wanted to run (total − idle), in [0, 1]: a
  // one-thread run on a 2-vCPU guest leaves one vCPU idle, and this share is then
  // the busy one's. nullopt if the counters could not be read or no such tick passed.
  std::optional<double> share() const;

 private:
  std::optional<CpuTicks> start_;
  long long wanted_ = 0, steal_ = 0;
  bool failed_ = false;
};

}  // namespace ballast
