// The `ballast` command line. Each subcommand lives in its own cmd_*.cpp and
// registers itself here.
#include <hdf5.h>

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "engine/errors.hpp"
#include "study/cli/cmd_clump.hpp"
#include "study/cli/cmd_demo.hpp"
#include "study/cli/cmd_merge.hpp"
#include "study/cli/cmd_run.hpp"
#include "study/cli/cmd_study.hpp"
#include "study/cli/command_exit.hpp"
#include "tests/bench/bed/cmd_bench_bed.hpp"

int main(int argc, char** argv) {
  // HDF5's clean-up at exit closes what is still open; after a write that failed (a
  // full disk), that close crashed (libhdf5 1.10). Every file is closed by its owner,
  // so the clean-up has nothing to do that matters.
  H5dont_atexit();
  CLI::App app{"Ballast: DEM box tests of railway ballast (Lu & McDowell 2007)"};
  app.require_subcommand(1);
  // subcommands
  ballast::register_demo_command(app);
  ballast::register_clump_command(app);
  ballast::register_run_command(app);
  ballast::register_study_command(app);
  ballast::register_merge_command(app);
  ballast::register_bench_bed_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const ballast::CommandExit& e) {
    // The command has reported everything; its status says how it ended.
    std::cout.flush();
    return e.code;
  } catch (const ballast::SetupError& e) {
    // Bad input: nothing has run.
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
