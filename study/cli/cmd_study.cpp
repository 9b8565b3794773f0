#include "study/cli/cmd_study.hpp"

#include <filesystem>
#include <memory>

#include "engine/errors.hpp"
#include "study/cli/checkpoint_options.hpp"
#include "study/cli/command_exit.hpp"
#include "study/cli/output_paths.hpp"
#include "study/running/study_runner.hpp"

namespace ballast {

void register_study_command(CLI::App& app) {
  auto o = std::make_shared<StudyOptions>();
  CLI::App* cmd = app.add_subcommand(
      "study", "Run every box test of a study file into one HDF5 archive (docs/STUDY.md)");
  cmd->add_option("study", o->study_file, "study file (cases/*_study.json)")->required();
  auto* output =
      cmd->add_option("-o,--output", o->output, "the archive to write (docs/ARCHIVE.md)");
  cmd->add_option("--jobs", o->jobs, "runs side by side (default: from the cores and the runs)")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--threads", o->threads, "OpenMP threads per run (default: cores / jobs)")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--shard", o->shard, "run only shard K of N: the runs whose index % N == K-1")
      ->capture_default_str();
  cmd->add_flag("--resume", o->resume,
                "complete the study in an existing archive (or its parts) without redoing "
                "finished runs");
  cmd->add_flag("--retry-failed", o->retry_failed, "with --resume: run the failed runs again");
  add_checkpoint_options(cmd, o->checkpoint_cycles, o->checkpoint_minutes,
                         "each run's ARCHIVE.parts/NNNNNN.checkpoint (which --resume continues)");
  auto* dry = cmd->add_flag("--dry-run", o->dry_run,
                            "check the study and every run's scene, list the runs, write nothing");
  cmd->add_option("--progress", o->progress, "auto: live on a terminal, plain lines otherwise")
      ->check(CLI::IsMember({"auto", "live", "plain"}))
      ->capture_default_str();
  cmd->callback([o, output, dry] {
    if (output->count() == 0 && dry->count() == 0) {
      throw SetupError(
          "missing -o ARCHIVE.h5 (allowed: -o with the archive to write, or "
          "--dry-run to check the study without running it)");
    }
    if (dry->count() == 0) {
      // Before any run: an archive that cannot be written would lose every run.
      const std::string folder = std::filesystem::path(o->output).parent_path().string();
      if (!folder.empty()) check_writable_directory("-o", folder);
      check_writable_file("-o", o->output);
    }
    const int code = run_study(*o);
    if (code != 0) throw CommandExit{code};
  });
}

}  // namespace ballast
