#pragma once
// Which CPU and SIMD code path ran: for benchmark contexts, `bearing_tool simulate --json`
// and the node's diagnostics, since speed figures mean little without them.
#include <string>

namespace bearing_sim {

// The Highway target the run-time dispatcher chose for the contact kernel ("AVX2", "AVX3", ...).
std::string simd_target_name();
// "model name" of the first processor in /proc/cpuinfo, or "unknown".
std::string cpu_model_name();

}  // namespace bearing_sim
