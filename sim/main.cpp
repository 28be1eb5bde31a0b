// shadesim: one CLI, one subcommand per job.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "sim/commands.h"

int main(int argc, char** argv) {
  CLI::App app{
      "shadesim - cycle-accurate simulator of a hardware per-pixel Phong shading unit\n"
      "(Bishop & Weimer forward-difference Taylor shader; exponent LUT, Schlick divider and\n"
      "W_m shift-and-square specular units)"};
  app.require_subcommand(1);
  int exit_code = 0;
  shadesim::register_commands(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "shadesim: error: " << e.what() << '\n';
    return 2;
  }
  return exit_code;
}
