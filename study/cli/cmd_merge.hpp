#pragma once

#include <CLI/CLI.hpp>

namespace ballast {

// `ballast merge A.h5 B.h5 ... -o ALL.h5`: the shards of one study in one archive.
// Exit 0 when every run of the study is there, 4 when some are missing (listed; the
// archive is written anyway and `ballast study --resume -o ALL.h5` completes it), 2
// when refused (another study, a run in two inputs, a damaged input, -o exists).
void register_merge_command(CLI::App& app);

}  // namespace ballast
