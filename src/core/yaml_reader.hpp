#pragma once
// Strict reading of the package's YAML files (bearing, sensor, scenario, sweep): the text of
// a sane file, parsed with keys written twice refused, and one mapping read key by key. Every
// error names the file (source) and the key. Internal to the core library.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/yaml.h>

#include "bearing_sim/core/errors.hpp"
#include "number_text.hpp"  // format_number, for the readers' messages

namespace bearing_sim {
namespace detail {

// The text of a configuration file. Only a regular file of at most 1 MiB (the shipped files
// are a few kB): /dev/zero or a FIFO would otherwise be read until memory runs out.
inline std::string read_config_file(const std::string& path, const std::string& what) {
  constexpr std::uintmax_t kMaxBytes = 1u << 20;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    const bool exists = std::filesystem::exists(path, ec);
    throw ConfigError(path + ": cannot open " + what + (exists ? " (not a regular file)" : " (no such file)"));
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxBytes) throw ConfigError(path + ": " + what + " larger than 1 MiB (or unreadable), refused");
  std::ifstream in(path);
  if (!in) throw ConfigError(path + ": cannot open " + what);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// Finds a key written twice in one mapping. yaml-cpp's Node API silently keeps the first
// (a stray `balls_per_row: 10` above the real one would win), so the text is first walked
// with the event parser, which still sees both and where they are.
class DuplicateKeyFinder : public YAML::EventHandler {
 public:
  explicit DuplicateKeyFinder(std::string source) : source_(std::move(source)) {}

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { node("~", mark); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { node("*alias", mark); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string& value) override {
    node(value, mark);
  }
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    open(false);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    open(true);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Level {
    bool is_map = false;
    bool at_key = true;                // map: the next node is a key
    bool is_key = false;               // this collection is itself a mapping key
    std::string key;                   // map: the current key; sequence: the current index
    std::size_t index = 0;             // sequence: entries so far
    std::map<std::string, int> lines;  // map: key -> line (1-based) of its first occurrence
  };

  std::string path() const {
    std::string p;
    for (const Level& l : stack_) {
      if (l.is_map) {
        if (!l.at_key) p += (p.empty() ? "" : ".") + l.key;
      } else {
        p += "[" + l.key + "]";
      }
    }
    return p;
  }

  // A scalar, null or alias at the current level.
  void node(const std::string& scalar, const YAML::Mark& mark) {
    if (stack_.empty()) return;
    Level& top = stack_.back();
    if (!top.is_map) {
      top.key = std::to_string(++top.index);  // index of the next entry
      return;
    }
    if (!top.at_key) {
      top.at_key = true;
      return;
    }
    top.at_key = false;
    top.key = scalar;
    const int line = mark.line + 1;
    const auto [it, inserted] = top.lines.emplace(scalar, line);
    if (!inserted)
      throw ConfigError(source_ + ": key '" + path() + "' appears twice (lines " + std::to_string(it->second) +
                        " and " + std::to_string(line) + "); remove one");
  }

  void open(bool is_map) {
    Level l;
    l.is_map = is_map;
    l.key = "0";
    if (!stack_.empty() && stack_.back().is_map && stack_.back().at_key) {
      // A collection used as a key (nothing the loaders read): its value follows.
      l.is_key = true;
      stack_.back().key = "<complex key>";
    }
    stack_.push_back(std::move(l));
  }

  void close() {
    const bool was_key = stack_.back().is_key;
    stack_.pop_back();
    if (stack_.empty()) return;
    Level& top = stack_.back();
    if (!top.is_map) top.key = std::to_string(++top.index);
    else top.at_key = !was_key;
  }

  std::string source_;
  std::vector<Level> stack_;
};

// The first document of a YAML text; a malformed text or a key written twice in one mapping
// is a ConfigError naming `source` (and the key and both lines).
inline YAML::Node load_yaml(const std::string& text, const std::string& source) {
  try {
    std::istringstream in(text);
    YAML::Parser parser(in);
    DuplicateKeyFinder finder(source);
    parser.HandleNextDocument(finder);
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source + ": malformed YAML: " + e.what());
  }
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
      if (!kv.first.IsScalar()) fail("?", "a key must be a plain name, not a list or mapping");
      const std::string key = kv.first.Scalar();
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
