#pragma once
// Which CPU and SIMD code path ran: for benchmark contexts, `bearing_tool simulate --json`
// and the node's diagnostics, since speed figures mean little without them.
#include <string>

namespace bearing_sim {

// The Highway target the run-time dispatcher chose for the contact kernel ("AVX2", "AVX3", ...).
std::string simd_target_name();
// Keeps the dispatcher off every target better than `name` ("AVX2", "SSE4", ...), e.g. to
// measure on an AVX-512 machine what an AVX2-only CPU would run. Call it before the first
// force evaluation. False, changing nothing, when no compiled target of that name runs here.
bool limit_simd_target(const std::string& name);
// The compiled targets this CPU runs, best first, e.g. "AVX3, AVX2, SSE4, SSSE3, SCALAR".
std::string runnable_simd_targets();
// "model name" of the first processor in /proc/cpuinfo with its family and model numbers
// where given, e.g. "Intel(R) Xeon(R) Processor (family 6 model 167)", or "unknown".
std::string cpu_model_name();

}  // namespace bearing_sim
