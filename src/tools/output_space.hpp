#pragma once
// Whether bearing_tool's output files fit on their disks, checked before a run starts: a long
// `simulate --csv` once filled a 252 GB disk with a 76 GB CSV. An output fits when its
// estimated size (output_size.hpp), 5 % more for what the estimate leaves out, still leaves
// 100 MB free on its filesystem (docs/bearing_tool.md "Before a dynamic run").
#include <cstdint>
#include <string>
#include <vector>

namespace bearing_sim::tool {

// What kOutputSpaceMargin adds to an estimate, and the space every run leaves free.
constexpr double kOutputSpaceMargin = 0.05;
constexpr double kOutputSpaceReserveBytes = 100e6;

struct PlannedOutput {
  std::string what;    // how a refusal names it: the option and its value, e.g. "--csv '/tmp/a.csv'"
  std::string path;    // the file (or the stem of the files)
  double bytes = 0.0;  // its estimated size
  // The files it overwrites, when they are not `path` itself (generate's files of a stem):
  // their space comes back.
  std::vector<std::string> replaces = {};
};

// The disk space the files at `paths` take (their allocated blocks, what removing or truncating
// them frees: less than the size of a sparse file); 0 for a path that is not a regular file.
double allocated_bytes(const std::vector<std::string>& paths);

// "12.4 GB", "830 kB": decimal units (1 GB = 1e9 bytes), three significant digits.
std::string byte_size_text(double bytes);

// Refuses (InputError) `needed_bytes` of output at `what` (the options and paths) on the
// filesystem of `directory`, which has `available_bytes` free, unless needed_bytes with the
// margin still leaves kOutputSpaceReserveBytes free. E.g. "--csv '/tmp/a.csv': 12.4 GB needed
// (estimate), 3.1 GB free on /tmp; ...".
void check_output_space(const std::string& what, double needed_bytes, const std::string& directory,
                        double available_bytes);

// The same for files on disk: outputs on one filesystem are added up, against the space
// std::filesystem::space gives for the nearest existing directory of each path, plus the
// space of the files the output would replace (allocated_bytes).
void check_output_space(const std::vector<PlannedOutput>& outputs);

}  // namespace bearing_sim::tool
