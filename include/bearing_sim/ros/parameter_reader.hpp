#pragma once
// One node's private parameters, each read with its allowed range. The values come as the
// parameter server's tree of the node's private namespace (an XmlRpcValue struct, see
// private_parameters.hpp), so that the checks need no ROS master and are tested as they are.
// The first bad value throws ParameterError naming the key, the value and what is allowed.
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <xmlrpcpp/XmlRpcValue.h>

namespace bearing_sim {
namespace ros_node {

// A private parameter of a node that is missing, of the wrong type or out of range, or
// unknown. what() names it ("~sample_rate_hz = -5: ..." with the node's namespace).
class ParameterError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ParameterReader {
 public:
  // `params`: the private namespace as one struct (anything else: no parameters set);
  // `ns`: the namespace for the messages, e.g. "/bearing/bearing_sim_node".
  ParameterReader(const XmlRpc::XmlRpcValue& params, std::string ns);

  // Whether `key` is set (it counts as known from then on).
  bool has(const std::string& key);
  // A number in [min, max]; an integer is accepted. `unit` only for the message ("Hz").
  double number(const std::string& key, double fallback, double min, double max, const std::string& unit);
  std::optional<double> optional_number(const std::string& key, double min, double max, const std::string& unit);
  int integer(const std::string& key, int fallback, int min, int max);
  bool boolean(const std::string& key, bool fallback);
  // A string; `allow_empty` false refuses "" (a frame id, a channel name).
  std::string text(const std::string& key, const std::string& fallback, bool allow_empty);
  std::string choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& allowed);
  // A rule across keys broken (e.g. an initial load beyond its limit): throws naming `key`
  // with its value.
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  // Throws on a key of the namespace that no call above read: a misspelt name would
  // otherwise leave its default in force without a word. `also_known`: keys that others
  // read in the same namespace (diagnostic_updater's diagnostic_period).
  void reject_unknown(const std::vector<std::string>& also_known = {}) const;

 private:
  const XmlRpc::XmlRpcValue* find(const std::string& key);
  [[noreturn]] void fail_value(const std::string& key, const XmlRpc::XmlRpcValue& value, const std::string& what) const;

  std::map<std::string, XmlRpc::XmlRpcValue> params_;
  std::string ns_;
  std::set<std::string> read_;
};

// The value as the message shows it: numbers with full precision, strings quoted.
std::string describe_parameter_value(const XmlRpc::XmlRpcValue& value);

}  // namespace ros_node
}  // namespace bearing_sim
