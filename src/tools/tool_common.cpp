#include "tool_common.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <sstream>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"

namespace bearing_sim::tool {
namespace {
std::string join(const std::vector<std::string>& parts, const std::string& sep) {
  std::string out;
  for (const auto& p : parts) out += (out.empty() ? "" : sep) + p;
  return out;
}

std::string format(const char* fmt, int digits, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, digits, v);
  return buf;
}
}  // namespace

namespace {
// The path of the first number of j that is NaN (or infinite where not allowed), "" if none.
std::string non_finite_path(const nlohmann::json& j, const std::string& path,
                            const std::set<std::string>& may_be_infinite, const std::string& key) {
  if (j.is_number_float()) {
    const double v = j.get<double>();
    if (std::isnan(v) || (std::isinf(v) && !may_be_infinite.count(key))) return path.empty() ? "(result)" : path;
    return "";
  }
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      const std::string found =
          non_finite_path(it.value(), path.empty() ? it.key() : path + "." + it.key(), may_be_infinite, it.key());
      if (!found.empty()) return found;
    }
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) {
      const std::string found = non_finite_path(j[i], path + "[" + std::to_string(i) + "]", may_be_infinite, key);
      if (!found.empty()) return found;
    }
  }
  return "";
}
}  // namespace

void require_finite_result(const nlohmann::json& result, const std::string& command,
                           const std::set<std::string>& may_be_infinite) {
  const std::string path = non_finite_path(result, "", may_be_infinite, "");
  if (!path.empty())
    throw NonFiniteResultError(command + ": the result '" + path +
                               "' is not a finite number: the inputs (load, speed, bearing values) are beyond what "
                               "the model computes in double precision; nothing was printed");
}

namespace {
// The number the whole of `text` spells, else nullopt. strtod, not stod: a number too small
// for a double (5e-324, 1e-400) is still a number (denormal or 0, refused or carried on by the
// checks of its option); stod throws on it as if it were text.
std::optional<double> parse_number(const std::string& text) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin || *end != '\0') return std::nullopt;
  return value;
}

// A validator of a number that `ok` accepts; `rule` says what it must be ("> 0").
CLI::Validator number_that(bool (*ok)(double), const std::string& rule) {
  return CLI::Validator(
      [ok, rule](std::string& text) -> std::string {
        const std::optional<double> value = parse_number(text);
        if (!value) return "'" + text + "' is not a number";
        return ok(*value) ? std::string() : "'" + text + "' must be " + rule;
      },
      "");
}
}  // namespace

const CLI::Validator& finite_number() {
  static const CLI::Validator validator = number_that([](double v) { return std::isfinite(v); }, "a finite number");
  return validator;
}

const CLI::Validator& positive_number() {
  static const CLI::Validator validator = number_that([](double v) { return v > 0.0; }, "> 0");
  return validator;
}

const CLI::Validator& non_negative_number() {
  static const CLI::Validator validator = number_that([](double v) { return v >= 0.0; }, ">= 0");
  return validator;
}

void add_json_flag(CLI::App* command, bool* json) {
  command->add_flag("--json", *json, "Print machine-readable JSON on stdout instead of tables");
}

void add_bearing_option(CLI::App* command, std::string* path) {
  command->add_option("--bearing", *path, "Bearing file (YAML, see docs/bearing_file.md)")
      ->required()
      ->type_name("FILE");
}

void add_load_options(CLI::App* command, std::vector<double>* force, std::vector<double>* moment) {
  add_vector_option(command, "--force", force, {"FX", "FY", "FZ"},
                    "Force on the moving ring in the bearing frame, N (z along the axis)");
  add_vector_option(command, "--moment", moment, {"MX", "MY"}, "Moment on the moving ring about x and y, N*m");
}

CLI::Option* add_vector_option(CLI::App* command, const std::string& name, std::vector<double>* values,
                               const std::vector<std::string>& components, const std::string& description) {
  const std::size_t n = components.size();
  std::string defaults;
  for (double v : *values) defaults += (defaults.empty() ? "" : ",") + general(v, 6);
  const std::string shape = join(components, ",");
  // One argument, split here: CLI11's own splitting drops empty fields and then takes the next
  // argument (`--force ,, --json` complained that '--json' is not a number).
  return command
      ->add_option_function<std::string>(
          name,
          [values, n, name, shape](const std::string& text) {
            std::vector<std::string> fields;
            std::size_t start = 0;
            for (;;) {
              const std::size_t comma = text.find(',', start);
              fields.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
              if (comma == std::string::npos) break;
              start = comma + 1;
            }
            if (fields.size() != n)
              throw CLI::ValidationError(name, "expected " + std::to_string(n) + " comma-separated numbers " + shape +
                                                   ", got " + std::to_string(fields.size()) + " in '" + text + "'");
            std::vector<double> parsed;
            for (std::string field : fields) {
              const std::string problem = finite_number()(field);
              if (!problem.empty()) throw CLI::ValidationError(name, problem + " (in '" + text + "')");
              parsed.push_back(*parse_number(field));
            }
            *values = parsed;
          },
          description + "; " + std::to_string(n) + " comma-separated numbers [default: " + defaults + "]")
      ->type_name(shape);
}

CLI::Option* add_number_option(CLI::App* command, const std::string& name, double* value, const std::string& type_name,
                               const std::string& description) {
  return command->add_option(name, *value, description)
      ->type_name(type_name)
      ->check(finite_number())
      ->capture_default_str();
}

BearingModel load_model(const std::string& path, double ring_temperature_difference_K) {
  BearingConfig config = load_bearing_config(path);
  config.ring_temperature_difference_K = ring_temperature_difference_K;
  try {
    return BearingModel(config);
  } catch (const ConfigError& e) {  // a defect that does not fit: the model names the bearing, not the file
    throw ConfigError(path + ": " + e.what());
  } catch (const InvalidInputError& e) {  // the clearance at that temperature difference
    throw InputError("--ring-temperature-difference-K with " + path + ": " + e.what());
  }
}

CLI::Option* add_ring_temperature_option(CLI::App* command, double* value, const std::string& description) {
  return add_number_option(command, "--ring-temperature-difference-K", value, "K", description);
}

Vector5 make_load(const std::vector<double>& force, const std::vector<double>& moment) {
  if (force.size() != 3) throw InputError("--force: expected 3 values FX,FY,FZ");
  if (moment.size() != 2) throw InputError("--moment: expected 2 values MX,MY");
  Vector5 load;
  load << force[0], force[1], force[2], moment[0], moment[1];
  return load;
}

double rpm_to_rad_s(double rpm) { return rpm * 2.0 * kPi / 60.0; }
double rad_to_deg(double rad) { return rad * 180.0 / kPi; }
double deg_to_rad(double deg) { return deg * kPi / 180.0; }

const char* rotating_ring_name(const BearingModel& model) {
  return model.config().rotating_ring == RotatingRing::Outer ? "outer" : "inner";
}

nlohmann::json to_json(const Vector5& v) {
  nlohmann::json a = nlohmann::json::array();
  for (int i = 0; i < 5; ++i) a.push_back(v[i]);
  return a;
}

nlohmann::json bearing_json(const BearingModel& model, const std::string& path) {
  const auto& c = model.config();
  return {{"file", path},
          {"name", c.name},
          {"rows", c.rows},
          {"balls_per_row", c.balls_per_row},
          {"contact_angle_deg", rad_to_deg(c.contact_angle_rad)},
          {"rotating_ring", rotating_ring_name(model)},
          {"ring_temperature_difference_K", c.ring_temperature_difference_K},
          {"operating_clearance_um", model.clearance_m() * 1e6},
          {"contact_damping_Ns_per_m", c.contact_damping_Ns_per_m}};
}

void print_json(const nlohmann::json& j) { std::cout << j.dump(2) << '\n'; }

std::string fixed(double v, int decimals) {
  std::string s = format("%.*f", decimals, v);
  // "-0.0000": a value that rounds to zero is shown without a sign.
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}
std::string general(double v, int digits) { return format("%.*g", digits, v); }
std::string scientific(double v, int digits) { return format("%.*e", digits, v); }

Table::Table(std::vector<std::string> headers, std::vector<bool> left_aligned)
    : headers_(std::move(headers)), left_(std::move(left_aligned)) {
  left_.resize(headers_.size(), false);
}

void Table::add_row(std::vector<std::string> cells) {
  cells.resize(headers_.size());
  rows_.push_back(std::move(cells));
}

void Table::print(std::ostream& out, const std::string& indent) const {
  std::vector<std::size_t> width(headers_.size());
  for (std::size_t c = 0; c < headers_.size(); ++c) {
    width[c] = headers_[c].size();
    for (const auto& row : rows_) width[c] = std::max(width[c], row[c].size());
  }
  auto line = [&](const std::vector<std::string>& cells) {
    std::string s = indent;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const std::string pad(width[c] - cells[c].size(), ' ');
      if (c > 0) s += "  ";
      s += left_[c] ? cells[c] + pad : pad + cells[c];
    }
    while (!s.empty() && s.back() == ' ') s.pop_back();
    out << s << '\n';
  };
  line(headers_);
  std::vector<std::string> rule;
  for (std::size_t w : width) rule.emplace_back(w, '-');
  line(rule);
  for (const auto& row : rows_) line(row);
}

void KeyValueList::add(std::string key, std::string value) { items_.emplace_back(std::move(key), std::move(value)); }

void KeyValueList::print(std::ostream& out, const std::string& indent) const {
  std::size_t w = 0;
  for (const auto& kv : items_) w = std::max(w, kv.first.size());
  for (const auto& kv : items_)
    out << indent << kv.first << ':' << std::string(w - kv.first.size() + 1, ' ') << kv.second << '\n';
}

void warn(const std::string& message) { std::cerr << "bearing_tool: warning: " << message << '\n'; }

}  // namespace bearing_sim::tool
