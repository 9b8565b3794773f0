#include "study/running/shared_beds.hpp"

#include <cstdio>
#include <filesystem>
#include <map>

#include "engine/fnv1a.hpp"

namespace ballast {

SharedBeds::SharedBeds(const std::vector<std::string>& bed_texts, const std::string& parts)
    : bed_of_(bed_texts.size(), -1) {
  std::map<std::string, std::vector<std::size_t>> runs_of;
  for (std::size_t k = 0; k < bed_texts.size(); ++k) runs_of[bed_texts[k]].push_back(k);
  for (auto& [text, runs] : runs_of) {
    char name[40];
    std::snprintf(name, sizeof name, "/bed-%016llx.checkpoint",
                  static_cast<unsigned long long>(fnv1a64(text)));
    const std::string path = parts.empty() ? std::string() : parts + name;
    // One run alone uses a bed only when an earlier, killed study left it.
    if (runs.size() < 2 && (path.empty() || !std::filesystem::exists(path))) continue;
    for (std::size_t k : runs) bed_of_[k] = static_cast<long>(beds_.size());
    beds_.push_back({path, text, runs.front(), runs.size()});
  }
}

void SharedBeds::assign(std::size_t k, CheckpointPlan& plan) const {
  if (bed_of_[k] < 0) return;
  const Bed& b = beds_[static_cast<std::size_t>(bed_of_[k])];
  plan.bed_path = b.path;
  plan.bed_text = b.text;
  plan.bed_writer = b.writer == k;
}

void SharedBeds::ended(std::size_t k) {
  if (bed_of_[k] < 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  Bed& b = beds_[static_cast<std::size_t>(bed_of_[k])];
  if (--b.left > 0 || b.path.empty()) return;
  std::error_code ignored;  // the study's end clears the parts folder anyway
  std::filesystem::remove(b.path, ignored);
}

std::size_t SharedBeds::receivers() const {
  std::size_t n = 0;
  for (long b : bed_of_) n += b >= 0 ? 1 : 0;
  return n - beds_.size();
}

}  // namespace ballast
