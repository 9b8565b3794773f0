// Many clumps at once: the sample a packing or a statistics run draws from.
// Clump i always uses clump_rng(seed, i) and is written to slot i, so the result is
// bit-identical whatever the number of OpenMP threads.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/clump_generator.hpp"
#include "engine/clump_mass.hpp"
#include "engine/clump_template.hpp"

namespace ballast {

// Generates `count` clumps and their templates (mass properties per `mass`).
// Parameters are validated before any work; an error inside the loop (e.g. an
// integration that cannot reach its accuracy) is rethrown for the lowest index.
std::vector<ClumpTemplate> generate_clump_templates(const ClumpParams& params,
                                                    const ClumpMassOptions& mass, std::size_t count,
                                                    std::uint64_t seed);

}  // namespace ballast
