#pragma once
// Runs the built bearing_tool for the tool tests (tool_runner.cpp, compiled once with its path).
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "command_runner.hpp"
#include "test_support.hpp"  // read_text

namespace bearing_sim::test {

using RunResult = CommandResult;

// The built bearing_tool's path.
std::string bearing_tool_path();

// The longest a bearing_tool run of a test may take before it is stopped: 15 min, far above
// any test's run even on a loaded machine.
constexpr int kToolTimeoutS = 900;

// bearing_tool with `args` (shell words) through run_command: stdout and stderr captured
// apart, stdin empty. A run stopped at kToolTimeoutS exits 124 (or 137) and its stderr says so.
RunResult run_bearing_tool(const std::string& args);

// A test with a scratch directory of its own (removed afterwards) to write inputs into and
// run bearing_tool in.
class ToolScratchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/bearing_tool_test_XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // Writes `text` to `name` in the scratch directory; returns its path.
  std::string write(const std::string& name, const std::string& text) {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path) << text;
    return path;
  }
  RunResult run(const std::string& args) { return run_bearing_tool(args); }

  std::string dir_;
};

}  // namespace bearing_sim::test
