// The headline numbers of a box-test run, as JSON (`ballast run --json`, the study
// archive's comparison table) and as a table for people.
#pragma once

#include <iosfwd>
#include <nlohmann/json.hpp>

#include "cases/box_test_result.hpp"

namespace ballast {

nlohmann::json run_summary_json(const BoxTestResult& r);
void print_run_summary(std::ostream& out, const BoxTestResult& r);

}  // namespace ballast
