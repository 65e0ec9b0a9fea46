#pragma once
// A number as the core writes it in its messages, readers and time lines alike (internal to
// the core library).
#include <sstream>
#include <string>

namespace bearing_sim::detail {

// Shortest of "%g" kind: 0.5, 1e-06.
inline std::string format_number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace bearing_sim::detail
