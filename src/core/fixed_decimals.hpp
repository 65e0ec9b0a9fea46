#pragma once
// A number with a fixed count of decimals, for the analysis notes (internal to the core).
#include <sstream>
#include <string>

namespace bearing_sim::detail {

inline std::string fixed_decimals(double v, int decimals) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(decimals);
  s << v;
  return s.str();
}

}  // namespace bearing_sim::detail
