#pragma once
// What a dynamic run of bearing_tool will cost, checked before it starts: the integrator's
// work per sample (a stiff mode from an implausible bearing value) and the wall time of the
// whole run, estimated from the speed measured on a short probe on this machine.
#include <functional>
#include <string>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim::tool {

// Runs estimated longer than kAnnounceRunS (bearing_dynamics.hpp, shared with the Python
// module) are announced on stderr before they start; longer than kLongRunLimitS, they need the
// confirmation flag.

// The automatic substeps at `load`. Above the ceiling of ros_node::check_integrator_work (the
// node's check) throws ConfigError naming the bearing file, the stiff mode (or overdamped
// contacts), its frequency and the key behind it, e.g. "tilt mode at 35 MHz:
// tilt_inertia_kg_m2 (7.9e-06) is implausibly small for this bearing".
int check_integrator_work(const BearingModel& model, const Vector5& load, double sample_rate_hz,
                          const std::string& bearing_file, IntegrationMethod method = kDefaultIntegrationMethod);

// Wall time per call of `step`, measured on a short probe: 200 calls, or 0.2 s of wall time
// when the calls are slow.
double measure_seconds_per_step(const std::function<void()>& step);

// Wall time per output sample of the dynamics alone, measured on a short run (a fraction of a
// second) from the static equilibrium.
double measure_seconds_per_sample(const BearingModel& model, const Vector5& load, double ring_speed_rad_s,
                                  double sample_rate_hz, int substeps,
                                  IntegrationMethod method = kDefaultIntegrationMethod);

// Refuses (InputError) a run of `samples` estimated to take `estimate_s` of wall time beyond
// kLongRunLimitS unless `confirmed`; says the estimate on stderr above kAnnounceRunS. `what` names
// the run, `flag` the confirmation.
void check_job_size(double samples, double estimate_s, bool confirmed, const std::string& what,
                    const std::string& flag);

}  // namespace bearing_sim::tool
