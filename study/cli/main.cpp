// The `ballast` command line. Each subcommand lives in its own cmd_*.cpp and
// registers itself here.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "engine/errors.hpp"
#include "study/cmd_bench_bed.hpp"
#include "study/cmd_clump.hpp"
#include "study/cmd_demo.hpp"
#include "study/cmd_merge.hpp"
#include "study/cmd_run.hpp"
#include "study/cmd_study.hpp"
#include "study/command_exit.hpp"

int main(int argc, char** argv) {
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
