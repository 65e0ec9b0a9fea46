#include "bearing_sim/ros/parameter_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace bearing_sim {
namespace ros_node {
namespace {

using XmlRpc::XmlRpcValue;

std::string number_text(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  if (std::strtod(buf, nullptr) != v) std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string range_text(double min, double max, const std::string& unit) {
  return "[" + number_text(min) + ", " + number_text(max) + "]" + (unit.empty() ? "" : " " + unit);
}

}  // namespace

std::string describe_parameter_value(const XmlRpcValue& value) {
  XmlRpcValue v = value;  // the conversions of XmlRpcValue are not all const
  switch (v.getType()) {
    case XmlRpcValue::TypeBoolean:
      return static_cast<bool>(v) ? "true" : "false";
    case XmlRpcValue::TypeInt:
      return std::to_string(static_cast<int>(v));
    case XmlRpcValue::TypeDouble:
      return number_text(static_cast<double>(v));
    case XmlRpcValue::TypeString:
      return "\"" + static_cast<std::string>(v) + "\"";
    case XmlRpcValue::TypeArray:
      return "a list";
    case XmlRpcValue::TypeStruct:
      return "a mapping";
    default:
      return "a value of another type";
  }
}

ParameterReader::ParameterReader(const XmlRpcValue& params, std::string ns) : ns_(std::move(ns)) {
  if (params.getType() != XmlRpcValue::TypeStruct) return;
  for (auto it = params.begin(); it != params.end(); ++it) params_.emplace(it->first, it->second);
}

bool ParameterReader::has(const std::string& key) {
  read_.insert(key);
  return params_.count(key) > 0;
}

const XmlRpcValue* ParameterReader::find(const std::string& key) {
  read_.insert(key);
  const auto it = params_.find(key);
  return it == params_.end() ? nullptr : &it->second;
}

void ParameterReader::fail(const std::string& key, const std::string& what) const {
  const auto it = params_.find(key);
  if (it == params_.end()) throw ParameterError("parameter " + ns_ + "/" + key + " (not set): " + what);
  fail_value(key, it->second, what);
}

void ParameterReader::fail_value(const std::string& key, const XmlRpcValue& value, const std::string& what) const {
  throw ParameterError("parameter " + ns_ + "/" + key + " = " + describe_parameter_value(value) + ": " + what);
}

double ParameterReader::number(const std::string& key, double fallback, double min, double max,
                               const std::string& unit) {
  const std::optional<double> v = optional_number(key, min, max, unit);
  return v ? *v : fallback;
}

std::optional<double> ParameterReader::optional_number(const std::string& key, double min, double max,
                                                       const std::string& unit) {
  const XmlRpcValue* p = find(key);
  if (!p) return std::nullopt;
  XmlRpcValue v = *p;
  double x = 0.0;
  if (v.getType() == XmlRpcValue::TypeDouble) x = static_cast<double>(v);
  else if (v.getType() == XmlRpcValue::TypeInt) x = static_cast<int>(v);
  else fail_value(key, v, "must be a number in " + range_text(min, max, unit));
  // NaN fails both comparisons: refused with the range.
  if (!(x >= min && x <= max)) fail_value(key, v, "must be a finite number in " + range_text(min, max, unit));
  return x;
}

int ParameterReader::integer(const std::string& key, int fallback, int min, int max) {
  const XmlRpcValue* p = find(key);
  if (!p) return fallback;
  XmlRpcValue v = *p;
  const std::string allowed = "must be an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]";
  if (v.getType() != XmlRpcValue::TypeInt) fail_value(key, v, allowed);
  const int x = static_cast<int>(v);
  if (x < min || x > max) fail_value(key, v, allowed);
  return x;
}

bool ParameterReader::boolean(const std::string& key, bool fallback) {
  const XmlRpcValue* p = find(key);
  if (!p) return fallback;
  XmlRpcValue v = *p;
  if (v.getType() != XmlRpcValue::TypeBoolean) fail_value(key, v, "must be true or false");
  return static_cast<bool>(v);
}

std::string ParameterReader::text(const std::string& key, const std::string& fallback, bool allow_empty) {
  const XmlRpcValue* p = find(key);
  if (!p) return fallback;
  XmlRpcValue v = *p;
  const std::string allowed = allow_empty ? "must be a string" : "must be a non-empty string";
  if (v.getType() != XmlRpcValue::TypeString) fail_value(key, v, allowed);
  const std::string s = static_cast<std::string>(v);
  if (s.empty() && !allow_empty) fail_value(key, v, allowed);
  return s;
}

std::string ParameterReader::choice(const std::string& key, const std::string& fallback,
                                    const std::vector<std::string>& allowed) {
  std::string options;
  for (const std::string& a : allowed) options += (options.empty() ? "" : ", ") + a;
  const std::string s = text(key, fallback, true);
  if (std::find(allowed.begin(), allowed.end(), s) == allowed.end()) fail(key, "must be one of " + options);
  return s;
}

void ParameterReader::reject_unknown(const std::vector<std::string>& also_known) const {
  for (const auto& [key, value] : params_) {
    if (read_.count(key) || std::find(also_known.begin(), also_known.end(), key) != also_known.end()) continue;
    std::string known;
    for (const std::string& k : read_) known += (known.empty() ? "" : ", ") + k;
    throw ParameterError("parameter " + ns_ + "/" + key + " = " + describe_parameter_value(value) +
                         ": unknown to this node (misspelt?); its parameters are: " + known);
  }
}

}  // namespace ros_node
}  // namespace bearing_sim
