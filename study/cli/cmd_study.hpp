#pragma once

#include <CLI/CLI.hpp>

namespace ballast {

// `ballast study STUDY.json -o ARCHIVE.h5 [--jobs J] [--threads T] [--shard K/N]
// [--resume [--retry-failed]] [--dry-run] [--progress auto|live|plain]`.
void register_study_command(CLI::App& app);

}  // namespace ballast
