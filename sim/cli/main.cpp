// shadesim: one CLI, one subcommand per job.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "sim/cli/commands.h"

#ifndef SHADESIM_VERSION
#define SHADESIM_VERSION "unknown"
#endif
#ifndef SHADESIM_GIT_COMMIT
#define SHADESIM_GIT_COMMIT ""
#endif

namespace {

// "shadesim 0.1.0 (git c2dd1d0a1b2c)": the project version and the commit this build was
// configured at, when it was configured in a git checkout.
std::string version_text() {
  std::string v = std::string("shadesim ") + SHADESIM_VERSION;
  if (*SHADESIM_GIT_COMMIT != '\0') v += std::string(" (git ") + SHADESIM_GIT_COMMIT + ")";
  return v;
}

// The subcommand a usage error belongs to ("" for the top level), for its message and hint.
std::string failing_subcommand(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) return sub->get_name();
  return "";
}

bool is_subcommand(const CLI::App& app, const std::string& name) {
  return !app.get_subcommands([&](const CLI::App* s) { return s->check_name(name); }).empty();
}

}  // namespace

// Outside the try: building the CLI, which throws only on a programming error (CLI11 on a
// duplicate option name), where the uncaught exception's abort names it best, and the printing
// of a caught error.
int main(int argc, char** argv) {  // NOLINT(bugprone-exception-escape): see above
  CLI::App app{
      "shadesim - cycle-accurate simulator of a hardware per-pixel Phong shading unit\n"
      "(Bishop & Weimer forward-difference Taylor shader; exponent LUT, Schlick divider and\n"
      "W_m shift-and-square specular units)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", version_text(), "print shadesim's version and exit");
  int exit_code = 0;
  shadesim::register_commands(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version: printed by CLI11, exit 0.
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success)) return app.exit(e);
    // Every usage error exits 2 (as getopt-style tools do), naming the option it is about.
    const std::string sub = failing_subcommand(app);
    std::string what = e.what();
    if (sub.empty() && argc > 1 && argv[1][0] != '-' && !is_subcommand(app, argv[1])) {
      what = std::string("unknown subcommand '") + argv[1] + "'";
    }
    std::cerr << "shadesim" << (sub.empty() ? "" : " " + sub) << ": usage error: " << what
              << "\nRun `shadesim" << (sub.empty() ? "" : " " + sub)
              << " --help` for the options.\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "shadesim: error: " << e.what() << '\n';
    return 2;
  }
  return exit_code;
}
