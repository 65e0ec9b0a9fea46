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

std::string runnable_simd_targets() {
  std::string names;
  for (const std::int64_t target : detail::contact_kernel_compiled_targets()) {
    if ((hwy::SupportedTargets() & target) == 0) continue;
    names += (names.empty() ? "" : ", ") + std::string(hwy::TargetName(target));
  }
  return names;
}

std::string cpu_model_name() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, name, family, model;
  // The first processor's entries only (they end at its first blank line).
  while (std::getline(in, line) && !line.empty()) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::size_t start = line.find_first_not_of(" \t", colon + 1);
    const std::string value = start == std::string::npos ? "" : line.substr(start);
    const std::string key = line.substr(0, line.find_last_not_of(" \t", colon - 1) + 1);
    if (key == "model name") name = value;
    if (key == "cpu family") family = value;
    if (key == "model") model = value;
  }
  if (name.empty()) return "unknown";
  // A virtual machine often names every CPU alike ("Intel(R) Xeon(R) Processor"): the
  // family and model numbers tell them apart.
  if (!family.empty() && !model.empty()) name += " (family " + family + " model " + model + ")";
  return name;
}

}  // namespace bearing_sim
