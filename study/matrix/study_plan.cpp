#include "study/matrix/study_plan.hpp"

#include <algorithm>
#include <charconv>

#include "engine/errors.hpp"

namespace ballast {

namespace {

bool parse_int(std::string_view text, int& out) {
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size();
}

}  // namespace

Shard parse_shard(const std::string& text) {
  const std::size_t slash = text.find('/');
  Shard s;
  const bool ok = slash != std::string::npos &&
                  parse_int(std::string_view(text).substr(0, slash), s.index) &&
                  parse_int(std::string_view(text).substr(slash + 1), s.count) && s.count >= 1 &&
                  s.count <= 100000 && s.index >= 1 && s.index <= s.count;
  if (!ok) {
    throw SetupError("invalid --shard = \"" + text +
                     "\" (allowed: K/N with 1 <= K <= N <= 100000, e.g. 2/8: the runs whose "
                     "index % N == K - 1)");
  }
  return s;
}

std::vector<const RunSpec*> shard_runs(const StudySpec& spec, const Shard& shard) {
  std::vector<const RunSpec*> out;
  for (const RunSpec& r : spec.runs) {
    if (shard.contains(r.index)) out.push_back(&r);
  }
  return out;
}

Parallelism plan_parallelism(int cores, std::size_t runs, int jobs, int threads) {
  cores = std::max(cores, 1);
  const int run_count = static_cast<int>(
      std::min<std::size_t>(std::max<std::size_t>(runs, 1), static_cast<std::size_t>(cores)));
  Parallelism p;
  if (jobs > 0 && threads > 0) {
    p = {jobs, threads};
  } else if (jobs > 0) {
    p = {jobs, std::max(1, cores / jobs)};
  } else if (threads > 0) {
    p = {std::max(1, std::min(run_count, cores / threads)), threads};
  } else {
    p.jobs = run_count;
    p.threads = std::max(1, cores / p.jobs);
  }
  // More side by side than there are runs would only idle.
  p.jobs = std::min(
      p.jobs, static_cast<int>(std::min<std::size_t>(std::max<std::size_t>(runs, 1), 100000)));
  return p;
}

}  // namespace ballast
