// The `ballast` command line. Each subcommand lives in its own cmd_*.cpp and
// registers itself here.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "study/cmd_bench_bed.hpp"
#include "study/cmd_clump.hpp"
#include "study/cmd_demo.hpp"
#include "study/cmd_run.hpp"
#include "engine/errors.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Ballast: DEM box tests of railway ballast (Lu & McDowell 2007)"};
  app.require_subcommand(1);
  // subcommands
  ballast::register_demo_command(app);
  ballast::register_clump_command(app);
  ballast::register_run_command(app);
  ballast::register_bench_bed_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
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
