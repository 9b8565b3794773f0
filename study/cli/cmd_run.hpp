#pragma once
#include <CLI/CLI.hpp>

namespace ballast {
// `ballast run SCENE.json -o RUN.h5`: one box test (cases/box_test_load.hpp).
void register_run_command(CLI::App& app);
}  // namespace ballast
