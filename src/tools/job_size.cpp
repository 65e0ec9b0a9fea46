#include "job_size.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/ring_dynamics.hpp"
#include "bearing_sim/runtime/input_validator.hpp"
#include "tool_common.hpp"

namespace bearing_sim::tool {
namespace {
std::string duration_text(double s) {
  std::ostringstream o;
  o.precision(3);
  if (s >= 86400.0 * 365.0) o << s / (86400.0 * 365.0) << " years";
  else if (s >= 86400.0) o << s / 86400.0 << " days";
  else if (s >= 3600.0) o << s / 3600.0 << " hours";
  else if (s >= 60.0) o << s / 60.0 << " minutes";
  else o << s << " s";
  return o.str();
}

}  // namespace

int check_integrator_work(const BearingModel& model, const Vector5& load, double sample_rate_hz,
                          const std::string& bearing_file, IntegrationMethod method) {
  double rate = 0.0;
  const runtime::InputCheck check = runtime::check_integrator_work(model, load, &rate);
  // As BearingDynamics::choose_substeps, in double: an absurd mode overflows an int.
  const double needed = std::max(1.0, std::ceil(rate / sample_rate_hz / BearingDynamics::step_times_omega_max(method)));
  if (check.accepted) return static_cast<int>(std::min(needed, 1e9));
  throw ConfigError(bearing_file + ": " + check.reason + "; the integrator would need " + general(needed, 3) +
                    " steps per sample at " + general(sample_rate_hz, 6) + " Hz; no bearing has a mode above " +
                    runtime::frequency_text(runtime::kMaxStiffRateRadS / (2.0 * kPi)));
}

double measure_seconds_per_step(const std::function<void()>& step) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  int n = 0;
  double elapsed = 0.0;
  while (n < 200 && elapsed < 0.2) {
    step();
    ++n;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  }
  return elapsed / n;
}

double measure_seconds_per_sample(const BearingModel& model, const Vector5& load, double ring_speed_rad_s,
                                  double sample_rate_hz, int substeps, IntegrationMethod method) {
  const std::unique_ptr<RingDynamics> dynamics =
      make_ring_dynamics(model, load, ring_speed_rad_s, DynamicsOptions{sample_rate_hz, substeps, true, method});
  return measure_seconds_per_step([&dynamics] {
    try {
      dynamics->step();
    } catch (const DivergenceError&) {
      dynamics->reset_to_equilibrium();
    }
  });
}

void check_job_size(double samples, double estimate_s, bool confirmed, const std::string& what,
                    const std::string& flag) {
  if (!(estimate_s > kAnnounceRunS)) return;
  std::ostringstream text;
  text << what << ": " << general(samples, 4) << " samples at the " << general(estimate_s / samples * 1e6, 3)
       << " us per sample measured on this machine: about " << duration_text(estimate_s);
  if (estimate_s > kLongRunLimitS && !confirmed)
    throw InputError(text.str() + ", more than " + duration_text(kLongRunLimitS) + "; give " + flag +
                     " to start it anyway");
  warn(text.str());
}

}  // namespace bearing_sim::tool
