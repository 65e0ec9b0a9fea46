// The nodes' parameter readers (read_sim_node_parameters, read_viz_parameters,
// read_lcm_bridge_parameters) without a ROS master: the shipped config/nodes files are
// accepted and read as written (values compared with yaml-cpp's reading of the same file),
// every parameter a node reads is documented in its file, and each kind of bad value stops the
// node with a message naming the node's namespace, the key and the value.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/yaml_check.hpp"
#include "bearing_sim/ros/lcm_bridge_parameters.hpp"
#include "bearing_sim/ros/parameter_reader.hpp"
#include "bearing_sim/ros/sim_node_parameters.hpp"
#include "bearing_sim/viz/viz_parameters.hpp"

namespace {

using bearing_sim::ros_node::ParameterError;
using XmlRpc::XmlRpcValue;

const std::string kSource = BEARING_SIM_SOURCE_DIR;
const std::string kSimNs = "/bearing/bearing_sim_node";

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The file as roslaunch's `rosparam load subst_value="true"` gives it to the node.
std::string node_file_text(const std::string& name) {
  std::string text = read_text(kSource + "/config/nodes/" + name);
  const std::string find = "$(find bearing_sim)";
  for (std::size_t at = text.find(find); at != std::string::npos; at = text.find(find))
    text.replace(at, find.size(), kSource);
  return text;
}

// A YAML scalar typed as rosparam (YAML 1.1) types it: bool, int, float, else string.
XmlRpcValue to_xmlrpc(const YAML::Node& node) {
  const std::string s = node.Scalar();
  if (node.Tag() != "!") {
    if (s == "true" || s == "false") return XmlRpcValue(s == "true");
    if (std::regex_match(s, std::regex("[-+]?[0-9]+"))) return XmlRpcValue(std::stoi(s));
    if (std::regex_match(s, std::regex("[-+]?([0-9]*\\.[0-9]+|[0-9]+\\.[0-9]*)([eE][-+]?[0-9]+)?")))
      return XmlRpcValue(std::stod(s));
  }
  return XmlRpcValue(s);
}

XmlRpcValue to_struct(const YAML::Node& map) {
  XmlRpcValue v;
  v.begin();  // an empty struct, not an invalid value
  for (const auto& kv : map) v[kv.first.as<std::string>()] = to_xmlrpc(kv.second);
  return v;
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const ParameterError& e) {
    return e.what();
  }
  return "(no error)";
}

// The keys a reader knows: listed by its refusal of an unknown one.
std::set<std::string> known_keys(const std::function<void(const XmlRpcValue&)>& read, XmlRpcValue params) {
  params["zz_not_a_parameter"] = 1;
  const std::string message = error_of([&] { read(params); });
  const std::string marker = "its parameters are: ";
  const std::size_t at = message.find(marker);
  EXPECT_NE(at, std::string::npos) << message;
  std::set<std::string> keys;
  std::stringstream list(message.substr(at + marker.size()));
  for (std::string key; std::getline(list, key, ',');) keys.insert(key.substr(key.find_first_not_of(' ')));
  return keys;
}

// Every key a reader knows appears in its file, set or as a commented "# key:" line.
void expect_all_documented(const std::set<std::string>& keys, const std::string& file) {
  const std::string text = read_text(kSource + "/config/nodes/" + file);
  for (const std::string& key : keys)
    EXPECT_TRUE(std::regex_search(text, std::regex("(^|\n)(# )?" + key + ":"))) << key << " is not in " << file;
}

XmlRpcValue sim_file() { return to_struct(YAML::Load(node_file_text("bearing_sim_node.yaml"))); }

bearing_sim::ros_node::SimNodeParameters read_sim(const XmlRpcValue& v) {
  return bearing_sim::ros_node::read_sim_node_parameters(v, kSimNs);
}

TEST(SimNodeParameters, ShippedFileIsReadAsWritten) {
  const YAML::Node yaml = YAML::Load(node_file_text("bearing_sim_node.yaml"));
  const auto p = read_sim(to_struct(yaml));
  EXPECT_EQ(p.bearing_file, kSource + "/config/bearings/ct_gantry_lyc.yaml");
  EXPECT_EQ(p.sample_rate_hz, yaml["sample_rate_hz"].as<double>());
  EXPECT_EQ(p.initial_load(0), yaml["initial_force_x_N"].as<double>());
  EXPECT_EQ(p.initial_load(4), yaml["initial_moment_y_Nm"].as<double>());
  EXPECT_EQ(p.initial_speed_rad_s, yaml["initial_speed_rad_s"].as<double>());
  // 180 rpm, the gantry's speed.
  EXPECT_NEAR(p.initial_speed_rad_s, 180.0 * 2.0 * M_PI / 60.0, 1e-12);
  EXPECT_DOUBLE_EQ(p.lead_s, 1e-3 * yaml["lead_ms"].as<double>());
  EXPECT_EQ(p.realtime_priority, yaml["realtime_priority"].as<int>());
  EXPECT_EQ(p.limits.max_force_N, yaml["max_force_N"].as<double>());
  EXPECT_EQ(*p.chunk_samples, yaml["chunk_samples"].as<int>());
  EXPECT_EQ(bearing_sim::integration_method_name(p.integrator), yaml["integrator"].as<std::string>());
  EXPECT_FALSE(p.frame_id.has_value());      // commented out: the rotating ring's frame
  EXPECT_FALSE(p.clearance_um.has_value());  // commented out: the bearing file's
  EXPECT_EQ(p.publish_clock, !p.real_time);
  EXPECT_EQ(p.max_real_time_factor, yaml["max_real_time_factor"].as<double>());
}

TEST(SimNodeParameters, EveryParameterIsDocumentedInItsFile) {
  const auto keys = known_keys([](const XmlRpcValue& v) { read_sim(v); }, sim_file());
  EXPECT_EQ(keys.size(), 38u);  // the table of docs/node.md
  EXPECT_TRUE(keys.count("lead_ms") && keys.count("clearance_um") && keys.count("frame_id"));
  expect_all_documented(keys, "bearing_sim_node.yaml");
}

TEST(SimNodeParameters, IntegersAreAcceptedForNumbers) {
  XmlRpcValue v = sim_file();
  v["lead_ms"] = 30;  // `lead_ms: 30` in a file or a launch <param>
  v["sample_rate_hz"] = 20000;
  const auto p = read_sim(v);
  EXPECT_DOUBLE_EQ(p.lead_s, 0.030);
  EXPECT_EQ(p.sample_rate_hz, 20000.0);
}

struct BadValue {
  const char* key;
  XmlRpcValue value;
  const char* expected;  // in the message after "<ns>/<key> = "
};

TEST(SimNodeParameters, EachBadValueIsNamedWithItsKeyAndRange) {
  const BadValue cases[] = {
      {"sample_rate_hz", XmlRpcValue(-5.0), "-5: must be a finite number in [1000, 1000000] Hz"},
      {"sample_rate_hz", XmlRpcValue(std::numeric_limits<double>::quiet_NaN()), "nan: must be a finite number"},
      {"lead_ms", XmlRpcValue(1500.0), "1500: must be a finite number in [0, 1000] ms"},
      {"lead_ms", XmlRpcValue(std::string("fast")), "\"fast\": must be a number in [0, 1000] ms"},
      {"realtime_priority", XmlRpcValue(120), "120: must be an integer in [0, 99]"},
      {"chunk_samples", XmlRpcValue(100.5), "100.5: must be an integer in [1, 10000]"},
      {"integrator", XmlRpcValue(std::string("euler")), "\"euler\": must be one of adams_pec, adams_pece, etdrk4, rk4"},
      {"real_time", XmlRpcValue(1), "1: must be true or false"},
      {"bearing_frame_id", XmlRpcValue(std::string("")), "\"\": must be a non-empty string"},
      {"max_speed_rad_s", XmlRpcValue(0.0), "0: must be a finite number in [0.1, 10000] rad/s"},
      {"health_window_s", XmlRpcValue(0.01), "0.01: must be a finite number in [0.1, 60] s"},
      {"clearance_um", XmlRpcValue(250.0), "250: must be a finite number in [-200, 200] um"},
      // Beyond its limit (max_force_N of the file: 1e5 N).
      {"initial_force_y_N", XmlRpcValue(2.0e5), "200000: must be a finite number in [-100000, 100000] N"},
      // Above the dynamics' Nyquist frequency (10 kHz / 2).
      {"envelope_resonance_hz", XmlRpcValue(6000.0), "6000: must be a finite number in [0, 5000] Hz"},
      {"sample_rate", XmlRpcValue(10000.0), "10000: unknown to this node (misspelt?)"},
  };
  for (const BadValue& c : cases) {
    XmlRpcValue v = sim_file();
    v[c.key] = c.value;
    const std::string message = error_of([&] { read_sim(v); });
    EXPECT_NE(message.find(kSimNs + "/" + c.key + " = " + c.expected), std::string::npos) << c.key << ": " << message;
  }
}

TEST(SimNodeParameters, MissingBearingFileIsNamed) {
  XmlRpcValue v = sim_file();
  XmlRpcValue without;
  without.begin();
  for (auto it = v.begin(); it != v.end(); ++it)
    if (it->first != "bearing_file") without[it->first] = it->second;
  const std::string message = error_of([&] { read_sim(without); });
  EXPECT_NE(message.find(kSimNs + "/bearing_file (not set): required"), std::string::npos) << message;
}

TEST(SimNodeParameters, InitialForceMagnitudeBeyondTheLimitIsRefused) {
  // Each component within +-max_force_N, the magnitude sqrt(2) * 0.8 = 1.13 times it.
  XmlRpcValue v = sim_file();
  v["initial_force_x_N"] = 0.8e5;
  v["initial_force_y_N"] = 0.8e5;
  const std::string message = error_of([&] { read_sim(v); });
  EXPECT_NE(message.find("initial_force_x_N = 80000: the initial force's magnitude exceeds max_force_N"),
            std::string::npos)
      << message;
  v["initial_force_y_N"] = 0.6e5;  // magnitude exactly 1e5 N: accepted
  EXPECT_NO_THROW(read_sim(v));
}

XmlRpcValue viz_file() { return to_struct(YAML::Load(node_file_text("bearing_viz.yaml"))); }
void read_viz(const XmlRpcValue& v) { bearing_sim::viz::read_viz_parameters(v, "/bearing/bearing_viz"); }

TEST(VizParameters, ShippedFileIsReadAsWrittenAndDocumented) {
  const YAML::Node yaml = YAML::Load(node_file_text("bearing_viz.yaml"));
  const auto p = bearing_sim::viz::read_viz_parameters(to_struct(yaml), "/bearing/bearing_viz");
  EXPECT_EQ(p.update_rate_hz, yaml["update_rate_hz"].as<double>());
  EXPECT_EQ(p.ball_scale, yaml["ball_scale"].as<double>());
  EXPECT_EQ(p.fixed_frame, "gantry");
  expect_all_documented(known_keys(read_viz, viz_file()), "bearing_viz.yaml");
}

TEST(VizParameters, BadValuesAreNamed) {
  XmlRpcValue v = viz_file();
  v["update_rate_hz"] = 0.0;
  EXPECT_NE(error_of([&] { read_viz(v); })
                .find("/bearing/bearing_viz/update_rate_hz = 0: must be a finite number in "
                      "[0.1, 200] Hz"),
            std::string::npos);
  v = viz_file();
  v["ball_scale"] = std::string("big");
  EXPECT_NE(error_of([&] { read_viz(v); }).find("/bearing/bearing_viz/ball_scale = \"big\": must be a number"),
            std::string::npos);
}

XmlRpcValue lcm_file() { return to_struct(YAML::Load(node_file_text("lcm_bridge.yaml"))); }
bearing_sim::ros_node::LcmBridgeParameters read_lcm(const XmlRpcValue& v) {
  return bearing_sim::ros_node::read_lcm_bridge_parameters(v, "/bearing/lcm_bridge");
}

TEST(LcmBridgeParameters, ShippedFileIsReadAsWrittenAndDocumented) {
  const YAML::Node yaml = YAML::Load(node_file_text("lcm_bridge.yaml"));
  const auto p = read_lcm(to_struct(yaml));
  EXPECT_EQ(p.lcm_url, yaml["lcm_url"].as<std::string>());
  EXPECT_EQ(p.max_queue_mb, yaml["max_queue_mb"].as<double>());
  ASSERT_EQ(p.routes.size(), 5u);
  for (const auto& r : p.routes) {
    EXPECT_EQ(r.enabled, yaml["bridge_" + r.topic].as<bool>()) << r.topic;
    EXPECT_EQ(r.channel, yaml[r.topic + "_channel"].as<std::string>()) << r.topic;
  }
  expect_all_documented(known_keys([](const XmlRpcValue& v) { read_lcm(v); }, lcm_file()), "lcm_bridge.yaml");
}

TEST(LcmBridgeParameters, BadValuesAreNamed) {
  XmlRpcValue v = lcm_file();
  v["lcm_url"] = std::string("file:///tmp/run.lcm");
  EXPECT_NE(error_of([&] { read_lcm(v); })
                .find("/bearing/lcm_bridge/lcm_url = \"file:///tmp/run.lcm\": a file:// URL "
                      "needs mode=w"),
            std::string::npos);
  v = lcm_file();
  v["health_channel"] = std::string("");
  EXPECT_NE(error_of([&] { read_lcm(v); }).find("/bearing/lcm_bridge/health_channel = \"\": must be a non-empty"),
            std::string::npos);
  v = lcm_file();
  v["bridge_helth"] = true;
  EXPECT_NE(error_of([&] { read_lcm(v); }).find("/bearing/lcm_bridge/bridge_helth = true: unknown to this node"),
            std::string::npos);
}

// roslaunch loads the parameter files with PyYAML, which keeps the last of a key written twice
// without a word (the node then sees one value): every shipped file is checked as the
// package's own YAML files are read, and that check names a duplicate.
TEST(ParameterFiles, NoKeyIsWrittenTwiceInAShippedFileAndADuplicateIsNamed) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kSource + "/config/nodes")) {
    EXPECT_NO_THROW(bearing_sim::check_yaml_file(entry.path().string(), "parameter file")) << entry.path();
    ++files;
  }
  EXPECT_EQ(files, 3);
  const std::string path = testing::TempDir() + "/bearing_sim_node_twice.yaml";
  const std::string text = read_text(kSource + "/config/nodes/bearing_sim_node.yaml");
  std::ofstream(path) << text << "sample_rate_hz: 20000.0\n";
  const std::string last_line = std::to_string(std::count(text.begin(), text.end(), '\n') + 1);
  try {
    bearing_sim::check_yaml_file(path, "parameter file");
    ADD_FAILURE() << "a key written twice was accepted";
  } catch (const bearing_sim::ConfigError& e) {
    const std::string message = e.what();
    for (const std::string& word : {path, std::string("'sample_rate_hz' appears twice"), "lines 15 and " + last_line})
      EXPECT_NE(message.find(word), std::string::npos) << word << " not in: " << message;
  }
  std::filesystem::remove(path);
}

}  // namespace
