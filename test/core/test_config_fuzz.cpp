// Bounded fuzzing of the files a user edits (bearing, sensor, scenario): the shipped files
// mutated as a careless user or a broken disk would (flipped bytes, truncation, numbers at the
// edges of floating point and of int, keys written twice, lines lost, swapped or garbage).
// Every case must either load into a usable model whose numbers are all finite, or throw
// ConfigError naming the file; it must not crash, hang or throw anything else. Each case runs
// in a forked child so that a crash or a hang is seen and reported as that case's failure.
#include <gtest/gtest.h>

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <random>
#include <regex>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

constexpr std::uint64_t kSeed = 20261123;
constexpr int kCasesPerFile = 100;  // 6 files: 600 cases, a few seconds
// Far above the few milliseconds a load takes, even under a sanitizer on a loaded machine.
constexpr int kCaseTimeLimitMs = 20000;

using test::config_path;
using test::read_text;

// What happened to one case.
struct Outcome {
  enum Kind { Loaded, ConfigErrorThrown, OtherException, Crashed, TimedOut } kind = Crashed;
  std::string detail;  // Loaded: "" or what is wrong with the model; else the message
};

// Runs `body` in a forked child; body returns "" for a good model or what is wrong with it.
Outcome run_isolated(const std::function<std::string()>& body) {
  int fds[2];
  if (pipe(fds) != 0) return {Outcome::Crashed, "pipe() failed"};
  const pid_t pid = fork();
  if (pid < 0) return {Outcome::Crashed, "fork() failed"};
  if (pid == 0) {
    close(fds[0]);
    std::string message;
    try {
      message = "L" + body();
    } catch (const ConfigError& e) {
      message = std::string("C") + e.what();
    } catch (const std::exception& e) {
      message = std::string("X") + typeid(e).name() + ": " + e.what();
    } catch (...) {
      message = "Xunknown exception";
    }
    std::size_t written = 0;
    while (written < message.size()) {
      const ssize_t n = write(fds[1], message.data() + written, message.size() - written);
      if (n <= 0) break;
      written += static_cast<std::size_t>(n);
    }
    close(fds[1]);
    _exit(0);
  }
  close(fds[1]);
  std::string message;
  bool timed_out = false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kCaseTimeLimitMs);
  char buffer[4096];
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = poll(&p, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;  // re-checks the deadline
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n <= 0) break;  // end of the child's message
    message.append(buffer, static_cast<std::size_t>(n));
  }
  close(fds[0]);
  if (timed_out) kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  if (timed_out) return {Outcome::TimedOut, "no result within " + std::to_string(kCaseTimeLimitMs) + " ms"};
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || message.empty())
    return {Outcome::Crashed, WIFSIGNALED(status)
                                  ? "killed by signal " + std::to_string(WTERMSIG(status))
                                  : "exit status " + std::to_string(WEXITSTATUS(status)) + " (a sanitizer report?)"};
  const char kind = message[0];
  message.erase(0, 1);
  if (kind == 'L') return {Outcome::Loaded, message};
  if (kind == 'C') return {Outcome::ConfigErrorThrown, message};
  return {Outcome::OtherException, message};
}

// ---------------------------------------------------------------------------------------
// Mutations

const std::vector<std::string> kEdgeNumbers = {"nan",
                                               ".nan",
                                               ".NaN",
                                               "inf",
                                               ".inf",
                                               "-.inf",
                                               "1e308",
                                               "-1e308",
                                               "1.8e308",
                                               "5e-324",
                                               "-5e-324",
                                               "1e-320",
                                               "-0",
                                               "-0.0",
                                               "0",
                                               "1e20",
                                               "-1e20",
                                               "2147483648",
                                               "-2147483649",
                                               "9223372036854775808",
                                               "99999999999999999999999",
                                               "4294967297",
                                               "0x7fffffff",
                                               "1_000",
                                               "1e",
                                               "--1",
                                               "+.5",
                                               "0.",
                                               "1e-400",
                                               "~",
                                               "''"};

const std::vector<std::string> kGarbageLines = {
    "{",        "[",          "- ",       "&a [*a, *a]", "? [1, 2]\n: 3", "x: *undefined_alias", "!!binary AAAA",
    "\t- tab",  "%YAML 1.3",  "---",      "...",         "\xff\xfe\x00",  "key: [1, 2",          "\"unterminated",
    ": no key", "<<: {a: 1}", "!!map {}", "? complex"};

class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {}

  // Uniform-enough index in [0, n) (rng() % n: the same on every standard library).
  std::size_t pick(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng_() % n); }

  std::string mutate(const std::string& text, int kind, std::string* what) {
    switch (kind) {
      case 0:
        return flip_bytes(text, what);
      case 1:
        return truncate(text, what);
      case 2:
        return edge_numbers(text, 1, what);
      case 3:
        return edge_numbers(text, 3, what);
      case 4:
        return duplicate_key_line(text, what);
      case 5:
        return structural(text, what);
      default:
        return deep_nesting(text, what);
    }
  }
  static constexpr int kKinds = 7;
  static constexpr int kDuplicateKey = 4;

 private:
  static std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    return lines;
  }
  static std::string join(const std::vector<std::string>& lines) {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
  }

  std::string flip_bytes(std::string text, std::string* what) {
    const std::size_t flips = 1 + pick(4);
    for (std::size_t i = 0; i < flips; ++i) {
      const std::size_t at = pick(text.size());
      text[at] = static_cast<char>(text[at] ^ (1 << pick(8)));
    }
    *what = std::to_string(flips) + " byte(s) flipped";
    return text;
  }

  std::string truncate(const std::string& text, std::string* what) {
    const std::size_t at = pick(text.size());
    *what = "truncated at byte " + std::to_string(at);
    return text.substr(0, at);
  }

  std::string edge_numbers(std::string text, int count, std::string* what) {
    static const std::regex number(R"((^|[\s\[,:{])(-?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?)(?=[\s\],}#]|$))");
    *what = "numbers replaced:";
    for (int i = 0; i < count; ++i) {
      std::vector<std::pair<std::size_t, std::size_t>> spans;  // of the number itself
      for (auto it = std::sregex_iterator(text.begin(), text.end(), number); it != std::sregex_iterator(); ++it)
        spans.emplace_back(it->position(2), it->length(2));
      if (spans.empty()) break;
      const auto [at, length] = spans[pick(spans.size())];
      const std::string value = kEdgeNumbers[pick(kEdgeNumbers.size())];
      *what += " '" + text.substr(at, length) + "' -> '" + value + "'";
      text.replace(at, length, value);
    }
    return text;
  }

  std::string duplicate_key_line(const std::string& text, std::string* what) {
    static const std::regex key_line(R"(^\s*[A-Za-z_][A-Za-z0-9_]*:.*$)");
    std::vector<std::string> lines = lines_of(text);
    std::vector<std::size_t> keys;
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (std::regex_match(lines[i], key_line)) keys.push_back(i);
    if (keys.empty()) return text;
    const std::size_t i = keys[pick(keys.size())];
    // Same key, same indentation, another value: the classic stale line left above the real one.
    std::string copy = lines[i];
    const std::size_t colon = copy.find(':');
    copy = copy.substr(0, colon + 1) + " " + kEdgeNumbers[pick(kEdgeNumbers.size())];
    lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(i), copy);
    *what = "key line " + std::to_string(i + 1) + " duplicated as '" + copy + "'";
    return join(lines);
  }

  std::string structural(const std::string& text, std::string* what) {
    std::vector<std::string> lines = lines_of(text);
    if (lines.size() < 2) return text;
    const std::size_t a = pick(lines.size()), b = pick(lines.size());
    switch (pick(3)) {
      case 0:
        *what = "line " + std::to_string(a + 1) + " deleted";
        lines.erase(lines.begin() + static_cast<std::ptrdiff_t>(a));
        break;
      case 1:
        *what = "lines " + std::to_string(a + 1) + " and " + std::to_string(b + 1) + " swapped";
        std::swap(lines[a], lines[b]);
        break;
      default: {
        const std::string garbage = kGarbageLines[pick(kGarbageLines.size())];
        *what = "'" + garbage + "' inserted at line " + std::to_string(a + 1);
        lines.insert(lines.begin() + static_cast<std::ptrdiff_t>(a), garbage);
      }
    }
    return join(lines);
  }

  std::string deep_nesting(const std::string& text, std::string* what) {
    const std::size_t depth = 100 + pick(20000);
    const bool flow_map = pick(2) == 0;
    std::string nest = "deep: ";
    for (std::size_t i = 0; i < depth; ++i) nest += flow_map ? "{a: " : "[";
    *what = std::to_string(depth) + " nested " + (flow_map ? "mappings" : "lists");
    return text + nest + "\n";
  }

  std::mt19937_64 rng_;
};

// ---------------------------------------------------------------------------------------
// What a loaded file must give.

std::string check_bearing(const std::string& text, const std::string& source) {
  const BearingConfig c = bearing_config_from_string(text, source);
  const double numbers[] = {c.ball_diameter_m,
                            c.pitch_diameter_m,
                            c.row_spacing_m,
                            c.row_phase_rad,
                            c.contact_angle_rad,
                            c.clearance_m,
                            c.outer_diameter_m,
                            c.inner_diameter_m,
                            c.width_m,
                            c.rotating_mass_kg,
                            c.tilt_inertia_kg_m2,
                            c.contact_damping_Ns_per_m,
                            c.material.youngs_modulus_Pa,
                            c.material.poisson_ratio,
                            c.material.density_kg_m3};
  for (double v : numbers)
    if (!std::isfinite(v)) return "a non-finite number in the loaded bearing";
  const BearingModel model(c);
  if (c.has_dynamics() && !(model.mass_matrix().allFinite() && model.mass_matrix().diagonal().minCoeff() > 0.0))
    return "mass matrix not finite and positive";
  const BearingFrequencies f = bearing_frequencies(model, 10.0);
  if (!std::isfinite(f.cage_hz) || !std::isfinite(f.varying_compliance_hz) || !std::isfinite(f.ball_spin_hz))
    return "non-finite bearing frequencies";
  return "";
}

std::string check_sensor(const std::string& text, const std::string& source) {
  const AccelerometerConfig c = accelerometer_config_from_string(text, source);
  if (!c.mount_point_m.allFinite() || !c.axis.allFinite() || !std::isfinite(c.output_rate_hz))
    return "a non-finite number in the loaded sensor";
  // The dynamics' rate: a multiple of the output rate that keeps the path below 0.45 of it.
  const double multiple = std::max(1.0, std::ceil(c.path_resonance_hz / (0.4 * c.output_rate_hz)));
  if (multiple > 64.0) return "";  // usable only with a faster simulation: nothing to run here
  VirtualAccelerometer sensor(c, multiple * c.output_rate_hz);
  double y = 0.0;
  for (int i = 0; i < 2000; ++i) {
    Vector5 a = Vector5::Zero();
    a[0] = std::sin(0.05 * i);
    if (sensor.push(a, 0.001 * i, &y) && !std::isfinite(y)) return "non-finite sensor output";
  }
  return "";
}

std::string check_scenario(const std::string& text, const std::string& source) {
  const Scenario s = Scenario::from_string(text, source);
  if (!(s.duration_s() > 0.0) || !std::isfinite(s.duration_s()) || !std::isfinite(s.sample_rate_hz()))
    return "non-finite duration or rate";
  for (double t : {0.0, 0.37 * s.duration_s(), s.duration_s(), 2.0 * s.duration_s()}) {
    if (!std::isfinite(s.ring_speed_at(t)) || !std::isfinite(s.ring_angle_at(t)) || !s.load_at(t).allFinite())
      return "non-finite speed, angle or load at t = " + std::to_string(t) + " s";
    for (const Spall& sp : s.spalls_at(t))
      if (!std::isfinite(Scenario::spall_width_at(sp, t)) || !std::isfinite(Scenario::spall_depth_at(sp, t)))
        return "non-finite spall size at t = " + std::to_string(t) + " s";
  }
  return "";
}

struct FuzzedFile {
  std::string relative_path;
  std::function<std::string(const std::string&, const std::string&)> check;
};

void fuzz(const FuzzedFile& file, std::uint64_t seed) {
  // The source is the real path: the scenario's relative bearing and sensor files resolve.
  const std::string source = config_path(file.relative_path);
  const std::string original = read_text(source);
  ASSERT_FALSE(original.empty()) << source;
  {
    const Outcome baseline = run_isolated([&] { return file.check(original, source); });
    ASSERT_EQ(baseline.kind, Outcome::Loaded) << source << ": the unmutated file must load: " << baseline.detail;
    ASSERT_EQ(baseline.detail, "") << source;
  }
  Mutator mutator(seed);
  int loaded = 0, refused = 0;
  for (int i = 0; i < kCasesPerFile; ++i) {
    std::string what;
    const std::string text = mutator.mutate(original, i % Mutator::kKinds, &what);
    const Outcome o = run_isolated([&] { return file.check(text, source); });
    SCOPED_TRACE(file.relative_path + " case " + std::to_string(i) + ": " + what);
    if (i % Mutator::kKinds == Mutator::kDuplicateKey) {
      // The shipped files have no block scalars: a copied key line is a key of the same mapping.
      EXPECT_EQ(o.kind, Outcome::ConfigErrorThrown) << "a key written twice must be refused";
      EXPECT_NE(o.detail.find("appears twice"), std::string::npos) << o.detail;
    }
    switch (o.kind) {
      case Outcome::Loaded:
        ++loaded;
        EXPECT_EQ(o.detail, "") << "loaded, but the model is not usable";
        break;
      case Outcome::ConfigErrorThrown:
        ++refused;
        EXPECT_NE(o.detail.find(source), std::string::npos) << "the error does not name the file: " << o.detail;
        break;
      case Outcome::OtherException:
        ADD_FAILURE() << "an exception other than ConfigError: " << o.detail;
        break;
      case Outcome::Crashed:
        ADD_FAILURE() << "crashed: " << o.detail;
        break;
      case Outcome::TimedOut:
        ADD_FAILURE() << "hung: " << o.detail;
        break;
    }
  }
  // Both outcomes occur: the mutations are neither all harmless nor all fatal.
  EXPECT_GT(loaded, 0) << file.relative_path;
  EXPECT_GT(refused, 0) << file.relative_path;
}

TEST(ConfigFuzz, MutatedBearingFilesLoadIntoFiniteModelsOrAreRefusedNamingTheFile) {
  std::uint64_t seed = kSeed;
  for (const char* name : {"ct_gantry_lyc.yaml", "deep_groove_6205.yaml", "ins_618_22_db.yaml"})
    fuzz({std::string("bearings/") + name, check_bearing}, seed++);
}

TEST(ConfigFuzz, MutatedSensorFilesLoadIntoFiniteSensorsOrAreRefusedNamingTheFile) {
  fuzz({"sensors/ct_gantry_housing_accelerometer.yaml", check_sensor}, kSeed + 10);
}

TEST(ConfigFuzz, MutatedScenarioFilesLoadIntoFiniteTimeLinesOrAreRefusedNamingTheFile) {
  std::uint64_t seed = kSeed + 20;
  for (const char* name : {"ct_gantry_scan.yaml", "ct_gantry_run_to_failure.yaml"})
    fuzz({std::string("scenarios/") + name, check_scenario}, seed++);
}

}  // namespace
}  // namespace bearing_sim
