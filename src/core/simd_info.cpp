#include "bearing_sim/core/simd_info.hpp"

#include <fstream>

#include <hwy/targets.h>

#include "contact_kernel.hpp"

namespace bearing_sim {

std::string simd_target_name() { return detail::contact_kernel_target_name(); }

bool limit_simd_target(const std::string& name) {
  for (const std::int64_t target : detail::contact_kernel_compiled_targets()) {
    if (name != hwy::TargetName(target) || (hwy::SupportedTargets() & target) == 0) continue;
    // Highway's better targets have the lower bits.
    hwy::DisableTargets(target - 1);
    return true;
  }
  return false;
}

std::string cpu_model_name() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) break;
    const std::size_t start = line.find_first_not_of(" \t", colon + 1);
    return start == std::string::npos ? "unknown" : line.substr(start);
  }
  return "unknown";
}

}  // namespace bearing_sim
