#pragma once
// Strict reading of one YAML mapping of a bearing file: every error names the file
// (source) and the key. Internal to the core library.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include <yaml-cpp/yaml.h>

#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {
namespace detail {

// The text of a configuration file. Only a regular file of at most 1 MiB (the shipped files
// are a few kB): /dev/zero or a FIFO would otherwise be read until memory runs out.
inline std::string read_config_file(const std::string& path, const std::string& what) {
  constexpr std::uintmax_t kMaxBytes = 1u << 20;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw ConfigError(path + ": cannot open " + what + " (not a regular file)");
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxBytes)
    throw ConfigError(path + ": " + what + " larger than 1 MiB (or unreadable), refused");
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open " + what);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

class Reader {
 public:
  Reader(const YAML::Node& map, std::string source, std::string prefix)
      : map_(map), source_(std::move(source)), prefix_(std::move(prefix)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw ConfigError(source_ + ": key '" + prefix_ + key + "': " + what);
  }

  void check_keys(const std::set<std::string>& known) const {
    for (const auto& kv : map_) {
      const std::string key = kv.first.as<std::string>();
      if (!known.count(key)) {
        std::string list;
        for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
        fail(key, "unknown key (known keys: " + list + ")");
      }
    }
  }

  bool has(const std::string& key) const { return static_cast<bool>(map_[key]); }

  double number(const std::string& key, double fallback, bool required = false) const {
    const YAML::Node node = map_[key];
    if (!node) {
      if (required) fail(key, "is required but missing");
      return fallback;
    }
    if (!node.IsScalar()) fail(key, "expected a number");
    double value = 0.0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      fail(key, "expected a number, got '" + node.Scalar() + "'");
    }
    if (!std::isfinite(value)) fail(key, "must be finite, got '" + node.Scalar() + "'");
    return value;
  }

  int integer(const std::string& key, int fallback, bool required = false) const {
    const YAML::Node node = map_[key];
    if (!node) {
      if (required) fail(key, "is required but missing");
      return fallback;
    }
    long value = 0;
    try {
      if (!node.IsScalar()) throw YAML::Exception(YAML::Mark(), "");
      value = node.as<long>();
    } catch (const YAML::Exception&) {
      fail(key, "expected an integer, got '" + (node.IsScalar() ? node.Scalar() : std::string("a non-scalar")) + "'");
    }
    if (value < -1000000 || value > 1000000) fail(key, "integer out of range");
    return static_cast<int>(value);
  }

  std::string text(const std::string& key, const std::string& fallback) const {
    const YAML::Node node = map_[key];
    if (!node) return fallback;
    if (!node.IsScalar()) fail(key, "expected a string");
    return node.Scalar();
  }

  YAML::Node map(const std::string& key) const {
    const YAML::Node node = map_[key];
    if (node && !node.IsMap()) fail(key, "expected a mapping");
    return node;
  }

  void require(bool ok, const std::string& key, const std::string& what) const {
    if (!ok) fail(key, what);
  }

  const std::string& source() const { return source_; }

 private:
  YAML::Node map_;
  std::string source_;
  std::string prefix_;
};

}  // namespace detail
}  // namespace bearing_sim
