// The checkpoint options `ballast run` and `ballast study` share (docs/CYCLES.md,
// "Checkpoints"): a checkpoint after every K-th load cycle and every M wall minutes.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace ballast {

// `where`: the checkpoint file, as the command's help names it.
inline void add_checkpoint_options(CLI::App* cmd, long& cycles, double& minutes,
                                   const std::string& where) {
  cmd->add_option("--checkpoint-cycles", cycles,
                  "write " + where + " after every K-th load cycle (0: not by cycles)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--checkpoint-minutes", minutes,
                  "and at least this often during the load cycles, wall-clock minutes (0: not "
                  "by time)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
}

}  // namespace ballast
