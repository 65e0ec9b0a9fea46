#pragma once
// The name of a list's element in error messages: key[i]. Internal to the core library.
#include <cstddef>
#include <string>

namespace bearing_sim::detail {

inline std::string at(const std::string& key, std::size_t i) { return key + "[" + std::to_string(i) + "]"; }

}  // namespace bearing_sim::detail
