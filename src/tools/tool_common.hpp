#pragma once
// Shared pieces of the bearing_tool subcommands: option helpers (comma-separated
// vectors with checked counts and finite values), model loading, JSON conversions
// and aligned text tables.
//
// A subcommand lives in its own command_<name>.cpp and exposes one
// `void register_<name>_command(CLI::App& app)`; bearing_tool_main.cpp calls it.
// Commands report bad input by throwing InputError (or a core error); the main maps
// exceptions to exit codes (see exit codes below).
#include <ostream>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim::tool {

// Exit codes of bearing_tool.
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;   // the run itself failed (divergence, I/O error)
constexpr int kExitBadInput = 2;  // bad options, bad bearing file, load not carried

// Bad command-line input found after parsing (inconsistent options, ...): exit 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A result that is not a finite number although every input passed its checks (inputs at
// the edge of what the model computes in double precision): exit 2, never printed.
class NonFiniteResultError : public InputError {
 public:
  using InputError::InputError;
};

// Throws NonFiniteResultError naming the first NaN or infinite number of `result` by its path
// (e.g. "stiffness[2][3]"). Keys listed in `may_be_infinite` may hold +-inf (not NaN), such as
// the level in dB of a ring at rest.
void require_finite_result(const nlohmann::json& result, const std::string& command,
                           const std::set<std::string>& may_be_infinite = {});

// --json: machine-readable output on stdout instead of the tables.
void add_json_flag(CLI::App* command, bool* json);

// --bearing FILE (required).
void add_bearing_option(CLI::App* command, std::string* path);

// An option taking exactly components.size() comma-separated finite numbers, for
// example "--force 6800,0,0". `values` holds the default (shown in --help). CLI11
// splits and counts; each element is checked to be a finite number.
CLI::Option* add_vector_option(CLI::App* command, const std::string& name, std::vector<double>* values,
                               const std::vector<std::string>& components, const std::string& description);

// --force FX,FY,FZ and --moment MX,MY: the load on the moving ring (static, simulate).
void add_load_options(CLI::App* command, std::vector<double>* force, std::vector<double>* moment);

// A single finite number, shown in --help as `type_name` (e.g. "RPM") with its default.
// Chain ->check(...) for a range (e.g. positive_number()).
CLI::Option* add_number_option(CLI::App* command, const std::string& name, double* value, const std::string& type_name,
                               const std::string& description);

// Validator: a finite number (rejects nan, inf and non-numbers).
const CLI::Validator& finite_number();
// Validators: a number > 0, a number >= 0 (CLI11's PositiveNumber and NonNegativeNumber say
// "Value 0 not in range 0.000000 to 1797693134862315708...", 300 digits of the largest double).
const CLI::Validator& positive_number();
const CLI::Validator& non_negative_number();

// Loads and validates the bearing file (throws ConfigError naming file and key), at a ring
// temperature difference (InputError naming --ring-temperature-difference-K when out of range).
BearingModel load_model(const std::string& path, double ring_temperature_difference_K = 0.0);

// --ring-temperature-difference-K: inner minus outer ring temperature, K (docs/model.md 3.7).
CLI::Option* add_ring_temperature_option(CLI::App* command, double* value, const std::string& description);

// (Fx, Fy, Fz, Mx, My) from --force and --moment.
Vector5 make_load(const std::vector<double>& force, const std::vector<double>& moment);

double rpm_to_rad_s(double rpm);
double rad_to_deg(double rad);
double deg_to_rad(double deg);
const char* rotating_ring_name(const BearingModel& model);

// JSON: vectors as arrays, matrices as arrays of rows.
nlohmann::json to_json(const Vector5& v);
template <typename Derived>
nlohmann::json matrix_to_json(const Eigen::MatrixBase<Derived>& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    rows.push_back(row);
  }
  return rows;
}
// Summary of the bearing file for the JSON outputs.
nlohmann::json bearing_json(const BearingModel& model, const std::string& path);

// Prints JSON (indented) to stdout.
void print_json(const nlohmann::json& j);

// Number formatting for the tables.
std::string fixed(double v, int decimals);         // 6.612
std::string general(double v, int digits = 4);     // 1.234e+08, 0.01234
std::string scientific(double v, int digits = 4);  // 1.2340e+08

// A text table with a header row, columns right-aligned (left for text columns).
class Table {
 public:
  explicit Table(std::vector<std::string> headers, std::vector<bool> left_aligned = {});
  void add_row(std::vector<std::string> cells);
  void print(std::ostream& out, const std::string& indent = "  ") const;

 private:
  std::vector<std::string> headers_;
  std::vector<bool> left_;
  std::vector<std::vector<std::string>> rows_;
};

// "Key: value" lines with the keys aligned.
class KeyValueList {
 public:
  void add(std::string key, std::string value);
  void print(std::ostream& out, const std::string& indent = "  ") const;

 private:
  std::vector<std::pair<std::string, std::string>> items_;
};

// Prints a warning to stderr ("bearing_tool: warning: ...").
void warn(const std::string& message);

}  // namespace bearing_sim::tool
