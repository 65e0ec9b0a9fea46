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
  const std::string command = "'" + bearing_tool_path() + "' " + args + " 2>'" + err_path + "'";
  RunResult r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = read_file(err_path);
  return r;
}

}  // namespace bearing_sim::test
