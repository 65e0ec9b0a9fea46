// bearing_tool: command-line front end of the bearing_sim core. Sets up the CLI11 app,
// registers the subcommands (one file each) and maps errors to exit codes:
// 0 success (and --help), 2 bad input (options, bearing file, a load the bearing cannot
// carry), 1 the run failed (divergence, I/O).
#include <exception>
#include <iostream>

#include <CLI/CLI.hpp>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/simd_info.hpp"
#include "commands.hpp"
#include "tool_common.hpp"

namespace {

using Register = void (*)(CLI::App&);
constexpr Register kCommands[] = {
    bearing_sim::tool::register_static_command,   bearing_sim::tool::register_frequencies_command,
    bearing_sim::tool::register_simulate_command, bearing_sim::tool::register_analyze_command,
    bearing_sim::tool::register_sweep_command,    bearing_sim::tool::register_modes_command,
    bearing_sim::tool::register_generate_command,
};

int fail(int code, const char* kind, const std::exception& e) {
  std::cerr << "bearing_tool: " << kind << ": " << e.what() << '\n';
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  namespace tool = bearing_sim::tool;
  CLI::App app{
      "bearing_tool: quasi-static, frequency and dynamic analysis of rolling bearings (bearing_sim).\n"
      "Run 'bearing_tool <command> --help' for the options of a command.",
      "bearing_tool"};
  app.require_subcommand(1);
  // Parse errors (missing or malformed options) in the same style as the other errors.
  app.failure_message([](const CLI::App* failed, const CLI::Error& e) {
    std::string where = "bearing_tool";
    for (const CLI::App* sub : failed->get_subcommands()) where += " " + sub->get_name();
    return "bearing_tool: invalid input: " + std::string(e.what()) + "\nRun '" + where + " --help' for the options.\n";
  });
  // Before the command: the kernels' SIMD target, for datasets that must be byte-identical
  // across machines (samples differ by rounding between targets) or a narrower target that
  // runs faster on some CPUs. Applied as it is parsed, before the command's callback.
  app.add_option_function<std::string>(
         "--simd-target",
         [](const std::string& name) {
           if (!bearing_sim::limit_simd_target(name))
             throw tool::InputError("--simd-target " + name + ": not a SIMD target this CPU runs (it runs: " +
                                    bearing_sim::runnable_simd_targets() + ")");
         },
         "Run the kernels on this SIMD target (default: the best this CPU runs; e.g. AVX2, SSE4, NEON)")
      ->type_name("NAME")
      ->trigger_on_parse();
  for (Register r : kCommands) r(app);

  try {
    app.parse(argc, argv);  // runs the chosen command's callback
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // prints the message and a hint to --help on stderr
    return tool::kExitBadInput;
  } catch (const bearing_sim::ConfigError& e) {
    return fail(tool::kExitBadInput, "bad configuration file", e);
  } catch (const bearing_sim::LoadNotCarriedError& e) {
    return fail(tool::kExitBadInput, "load not carried", e);
  } catch (const bearing_sim::InvalidInputError& e) {
    return fail(tool::kExitBadInput, "invalid input", e);
  } catch (const tool::InputError& e) {
    return fail(tool::kExitBadInput, "invalid input", e);
  } catch (const bearing_sim::DivergenceError& e) {
    return fail(tool::kExitFailure, "simulation diverged", e);
  } catch (const std::exception& e) {
    return fail(tool::kExitFailure, "error", e);
  }
  return tool::kExitOk;
}
