// run_command (command_runner.hpp), the tests' runner of child processes: a command that
// outlives its time-out is stopped with exit 124 and says so; stdout, stderr and the exit
// status come back apart; stdin is empty.
#include <gtest/gtest.h>

#include "command_runner.hpp"

using bearing_sim::test::CommandResult;
using bearing_sim::test::run_command;

TEST(RunCommand, ACommandLongerThanItsTimeOutIsStoppedAndSaysSo) {
  // 1 s against a 30 s sleep: stopped on any machine, however loaded.
  const CommandResult r = run_command("sleep 30", 1);
  EXPECT_EQ(r.exit_code, 124) << r.err;
  EXPECT_NE(r.err.find("sleep 30: did not finish within 1 s and was stopped"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST(RunCommand, StdoutStderrAndTheExitStatusComeBackApart) {
  const CommandResult r = run_command("echo out; echo err >&2; exit 3", 300);
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.out, "out\n");
  EXPECT_EQ(r.err, "err\n");  // no time-out line: it was not stopped
}

TEST(RunCommand, AnExitStatusOf124BeforeTheTimeOutIsNotCalledStopped) {
  const CommandResult r = run_command("exit 124", 300);
  EXPECT_EQ(r.exit_code, 124);
  EXPECT_EQ(r.err, "");
}

TEST(RunCommand, StdinIsEmpty) {
  // cat ends at once on /dev/null; on an inherited terminal or pipe it would wait.
  const CommandResult r = run_command("cat; echo end", 300);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "end\n");
}

TEST(RunCommand, OutputLargerThanAPipeBufferOnBothStreams) {
  // 1 MB on each stream, interleaved: a runner reading one stream to its end before the
  // other would deadlock with the child blocked on the full pipe (64 kB), until the time-out.
  const CommandResult r = run_command(
      "i=0; while [ $i -lt 16 ]; do head -c 65536 /dev/zero | tr '\\0' o; head -c 65536 /dev/zero | tr '\\0' e >&2; "
      "i=$((i+1)); done",
      300);
  EXPECT_EQ(r.exit_code, 0) << r.err.substr(r.err.size() > 200 ? r.err.size() - 200 : 0);
  EXPECT_EQ(r.out, std::string(1u << 20, 'o'));
  EXPECT_EQ(r.err, std::string(1u << 20, 'e'));
}

TEST(RunCommand, ACommandThatCannotBeFoundExits127) {
  const CommandResult r = run_command("/nonexistent/bearing_sim_program", 300);
  EXPECT_EQ(r.exit_code, 127);
  EXPECT_NE(r.err.find("/nonexistent/bearing_sim_program"), std::string::npos) << r.err;
}
