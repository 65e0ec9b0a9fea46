#include "tool_runner.hpp"

namespace bearing_sim::test {

std::string bearing_tool_path() { return BEARING_TOOL_PATH; }

RunResult run_bearing_tool(const std::string& args) {
  // A run that should have been refused but started (a speed-dependent guard, say) must fail
  // the test, not hold up the whole test run.
  return run_command("'" + bearing_tool_path() + "' " + args, kToolTimeoutS);
}

}  // namespace bearing_sim::test
