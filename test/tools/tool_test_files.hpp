#pragma once
// The shipped files the bearing_tool suites run on, and their one text helper.
#include <string>

namespace bearing_sim::test {

inline const std::string kConfigDir = std::string(BEARING_SIM_SOURCE_DIR) + "/config";
inline const std::string kCtBearingYaml = kConfigDir + "/bearings/ct_gantry_lyc.yaml";
inline const std::string kCtScanYaml = kConfigDir + "/scenarios/ct_gantry_scan.yaml";

// Path of a file of the source tree, e.g. source_file("config/scenarios/ct_gantry_scan.yaml").
inline std::string source_file(const std::string& relative) { return std::string(BEARING_SIM_SOURCE_DIR) + "/" + relative; }

inline bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

}  // namespace bearing_sim::test
