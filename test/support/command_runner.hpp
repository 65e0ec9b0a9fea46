#pragma once
// Runs a shell command for the tests (bearing_tool, the scenario player, the LCM consumer)
// so that a child that hangs fails its test instead of holding up the whole test run.
#include <string>

namespace bearing_sim::test {

struct CommandResult {
  int exit_code = -1;  // the command's exit status; 128 + N when signal N ended it; -1: it did not start
  std::string out;     // its stdout
  std::string err;     // its stderr
};

// `command` (a /bin/sh command line) with stdin from /dev/null, stdout and stderr captured
// apart. After `timeout_s` coreutils' timeout sends its process group SIGTERM, 10 s later
// SIGKILL: the result is then exit 124 (or 137) and `err` ends with a line saying that the
// command was stopped.
CommandResult run_command(const std::string& command, int timeout_s);

}  // namespace bearing_sim::test
