#include "tool_runner.hpp"

#include <sys/wait.h>

#include <cstdio>
#include <sstream>

namespace bearing_sim::test {

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string bearing_tool_path() { return BEARING_TOOL_PATH; }

RunResult run_bearing_tool(const std::string& args, const std::string& scratch_dir) {
  const std::string err_path = scratch_dir + "/stderr.txt";
  // A run that should have been refused but started (a speed-dependent guard, say) must fail
  // the test, not hold up the whole test run: coreutils' timeout stops it.
  const std::string command = "timeout --kill-after=10 " + std::to_string(kToolTimeoutS) + " '" + bearing_tool_path() +
                              "' " + args + " 2>'" + err_path + "' </dev/null";
  RunResult r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = read_file(err_path);
  if (r.exit_code == 124 || r.exit_code == 137)
    r.err += "\n[tool_runner] bearing_tool " + args + " did not finish within " + std::to_string(kToolTimeoutS) +
             " s and was stopped\n";
  return r;
}

}  // namespace bearing_sim::test
