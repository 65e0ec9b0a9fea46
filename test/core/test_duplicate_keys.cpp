// A key written twice in one mapping of any file the package reads is an error naming the file,
// the key and both lines (yaml-cpp's node API would silently keep the first occurrence).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/core/sweep.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::config_path;
using test::read_text;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// The message of the error `load` throws (of type E), or "" with a test failure.
template <typename E>
std::string error_of(const std::function<void()>& load) {
  try {
    load();
    ADD_FAILURE() << "loaded without an error";
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
  }
  return "";
}

void expect_names(const std::string& message, const std::vector<std::string>& words) {
  for (const auto& w : words) EXPECT_NE(message.find(w), std::string::npos) << "'" << w << "' not in: " << message;
}

TEST(DuplicateKeys, AStaleBallCountAboveTheRealOneIsRefusedNotSimulated) {
  // The classic: balls_per_row: 10 left above the real balls_per_row: 207.
  const std::string path = config_path("bearings/ct_gantry_lyc.yaml");
  std::vector<std::string> lines = lines_of(read_text(path));
  const auto real = std::find(lines.begin(), lines.end(), "balls_per_row: 207");
  ASSERT_NE(real, lines.end());
  const int line = static_cast<int>(real - lines.begin()) + 1;  // 1-based, as the message
  lines.insert(real, "balls_per_row: 10");
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  const std::string message = error_of<ConfigError>([&] { bearing_config_from_string(text, path); });
  expect_names(message, {path, "'balls_per_row'", "appears twice",
                         "lines " + std::to_string(line) + " and " + std::to_string(line + 1)});
}

TEST(DuplicateKeys, EveryTopLevelKeyOfEveryShippedFileWrittenTwiceIsRefused) {
  struct File {
    std::string relative;
    std::function<void(const std::string&, const std::string&)> load;
  };
  // Every shipped bearing, sensor and scenario file, whatever is added later.
  std::vector<File> files;
  const std::function<void(const std::string&, const std::string&)> loaders[] = {
      [](auto& t, auto& s) { bearing_config_from_string(t, s); },
      [](auto& t, auto& s) { accelerometer_config_from_string(t, s); },
      [](auto& t, auto& s) { Scenario::from_string(t, s); }};
  const char* const folders[] = {"bearings", "sensors", "scenarios"};
  for (int k = 0; k < 3; ++k) {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(config_path(folders[k])))
      if (entry.path().extension() == ".yaml") names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    for (const std::string& name : names) files.push_back({std::string(folders[k]) + "/" + name, loaders[k]});
  }
  ASSERT_GE(files.size(), 6u);
  const std::regex top_level_key(R"(^([A-Za-z_][A-Za-z0-9_]*):.*$)");
  int checked = 0;
  for (const File& f : files) {
    const std::string path = config_path(f.relative);
    const std::string text = read_text(path);
    ASSERT_NO_THROW(f.load(text, path)) << path;  // as shipped: no duplicate
    const std::vector<std::string> lines = lines_of(text);
    ASSERT_EQ(text.back(), '\n');
    for (std::size_t i = 0; i < lines.size(); ++i) {
      std::smatch m;
      if (!std::regex_match(lines[i], m, top_level_key)) continue;
      const std::string key = m[1];
      // Appended at the end (line lines.size() + 1), with no value.
      const std::string mutated = text + key + ":\n";
      SCOPED_TRACE(f.relative + ": " + key);
      const std::string message = error_of<ConfigError>([&] { f.load(mutated, path); });
      expect_names(message, {path, "'" + key + "'", "appears twice",
                             "lines " + std::to_string(i + 1) + " and " + std::to_string(lines.size() + 1)});
      ++checked;
    }
  }
  EXPECT_GE(checked, 40);  // every file has several top-level keys
}

TEST(DuplicateKeys, NestedDuplicatesNameTheirPathAndTheSameKeyInTwoMappingsIsFine) {
  const std::string base =
      "name: test\n"
      "balls_per_row: 9\n"
      "ball_diameter_mm: 7.94\n"
      "pitch_diameter_mm: 39.04\n"
      "inner_groove_curvature: 0.52\n"
      "outer_groove_curvature: 0.52\n";
  // In a flow mapping on one line.
  std::string message = error_of<ConfigError>([&] {
    bearing_config_from_string(base + "material: {youngs_modulus_GPa: 208, youngs_modulus_GPa: 100}\n", "flow.yaml");
  });
  expect_names(message, {"flow.yaml", "'material.youngs_modulus_GPa'", "lines 7 and 7"});
  // In the second entry of a list of mappings.
  message = error_of<ConfigError>([&] {
    bearing_config_from_string(base +
                                   "defects:\n"
                                   "  - {surface: outer_race, width_mm: 1.0, depth_um: 10}\n"
                                   "  - surface: inner_race\n"
                                   "    width_mm: 1.0\n"
                                   "    depth_um: 10\n"
                                   "    depth_um: 20\n",
                               "list.yaml");
  });
  expect_names(message, {"list.yaml", "'defects[1].depth_um'", "lines 11 and 12"});
  // The same key in two different mappings (two defects) is no duplicate: both are kept.
  const BearingConfig two = bearing_config_from_string(base +
                                                           "defects:\n"
                                                           "  - {surface: outer_race, width_mm: 1.0, depth_um: 10}\n"
                                                           "  - {surface: inner_race, width_mm: 1.0, depth_um: 20}\n",
                                                       "two.yaml");
  ASSERT_EQ(two.imperfections.spalls.size(), 2u);
  EXPECT_DOUBLE_EQ(two.imperfections.spalls[1].depth_m, 20e-6);
}

TEST(DuplicateKeys, ASweepDefinitionWithAKeyTwiceIsRefusedNamingItsLines) {
  const std::string path = testing::TempDir() + "/duplicate_key_sweep.yaml";
  {
    std::ofstream out(path);
    out << "name: study\n"
           "bearing: "
        << config_path("bearings/deep_groove_6205.yaml")
        << "\n"
           "analysis: static\n"
           "analysis: dynamic\n";
  }
  const std::string message = error_of<InvalidInputError>([&] { load_sweep_definition(path); });
  expect_names(message, {path, "'analysis'", "appears twice", "lines 3 and 4"});
  std::remove(path.c_str());
}

}  // namespace
}  // namespace bearing_sim
