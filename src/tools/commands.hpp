#pragma once
// The bearing_tool subcommands. Each registers itself (options, help text and the
// callback that runs it) on the top-level CLI11 app. To add one: write
// command_<name>.cpp with register_<name>_command, declare it here, list it in
// kCommands in bearing_tool_main.cpp and in the bearing_sim_tool target of CMakeLists.txt.
#include <CLI/CLI.hpp>

namespace bearing_sim::tool {

void register_static_command(CLI::App& app);
void register_frequencies_command(CLI::App& app);
void register_simulate_command(CLI::App& app);
void register_analyze_command(CLI::App& app);
void register_sweep_command(CLI::App& app);
void register_modes_command(CLI::App& app);
void register_generate_command(CLI::App& app);

}  // namespace bearing_sim::tool
