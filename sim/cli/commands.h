// Subcommand registration. Each subcommand's options live in their own sim/cli/*.cpp, which
// registers it here: its callback fills the engine's plain options struct (sim/engines/,
// sim/regress/, sim/report/, sim/eda/) and stores the engine's exit code in `exit_code` (non-zero
// on a failed check); bad input throws std::exception, which main() reports as "shadesim: error:
// ...".
#pragma once

#include <CLI/CLI.hpp>

namespace shadesim {

void register_render(CLI::App& app, int& exit_code);
void register_report(CLI::App& app, int& exit_code);
void register_spec_error(CLI::App& app, int& exit_code);
void register_regress(CLI::App& app, int& exit_code);
void register_cycles(CLI::App& app, int& exit_code);
void register_config(CLI::App& app, int& exit_code);
void register_explore(CLI::App& app, int& exit_code);
void register_cosim(CLI::App& app, int& exit_code);
void register_area(CLI::App& app, int& exit_code);
void register_merge(CLI::App& app, int& exit_code);
void register_layout(CLI::App& app, int& exit_code);

inline void register_commands(CLI::App& app, int& exit_code) {
  register_render(app, exit_code);
  register_report(app, exit_code);
  register_spec_error(app, exit_code);
  register_regress(app, exit_code);
  register_cycles(app, exit_code);
  register_config(app, exit_code);
  register_explore(app, exit_code);
  register_cosim(app, exit_code);
  register_area(app, exit_code);
  register_merge(app, exit_code);
  register_layout(app, exit_code);
}

}  // namespace shadesim
