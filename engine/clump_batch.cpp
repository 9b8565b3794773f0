#include "engine/clump_batch.hpp"

#include <exception>

namespace ballast {

std::vector<ClumpTemplate> generate_clump_templates(const ClumpParams& params,
                                                    const ClumpMassOptions& mass, std::size_t count,
                                                    std::uint64_t seed) {
  validate_clump_params(params);
  validate_mass_options(mass);
  const long n = static_cast<long>(count);
  std::vector<ClumpTemplate> out(count);
  std::vector<std::exception_ptr> errors(count);
  // Dynamic schedule: clumps differ several-fold in cost (7 to 60 balls).
#pragma omp parallel for schedule(dynamic, 8)
  for (long i = 0; i < n; ++i) {
    try {
      std::mt19937_64 rng = clump_rng(seed, static_cast<std::uint64_t>(i));
      out[i] = make_clump_template(generate_clump(params, rng), mass);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  }
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  return out;
}

}  // namespace ballast
