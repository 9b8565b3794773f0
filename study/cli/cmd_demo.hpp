#pragma once
#include <CLI/CLI.hpp>

namespace ballast {
// `ballast demo`: the settling demo (cases/settling_demo.hpp).
void register_demo_command(CLI::App& app);
}  // namespace ballast
