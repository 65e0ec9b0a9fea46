#include "bearing_sim/core/simulation_run.hpp"

#include <chrono>
#include <cmath>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/vibration_level.hpp"

namespace bearing_sim {

SimulationSummary run_simulation(const BearingModel& model, const SimulationRequest& request,
                                 const std::function<void(const DynamicSample&)>& on_sample) {
  if (!(request.duration_s > 0.0) || !std::isfinite(request.duration_s))
    throw InvalidInputError("duration must be a positive number of seconds");
  if (!(request.sample_rate_hz > 0.0) || !std::isfinite(request.sample_rate_hz))
    throw InvalidInputError("sample rate must be a positive number of Hz");
  const auto n = static_cast<std::size_t>(std::llround(request.duration_s * request.sample_rate_hz));
  if (n < 4) throw InvalidInputError("the run must hold at least 4 samples (duration x rate)");
  if (n > 1'000'000'000) throw InvalidInputError("the run is too long (over 1e9 samples)");

  BearingDynamics dynamics(model, request.load, request.ring_speed_rad_s,
                           DynamicsOptions{request.sample_rate_hz, request.substeps, true, request.method});
  const std::size_t half = n / 2;
  // Mean and RMS about it streamed (Welford): a buffer of the accelerations took 12 bytes per
  // sample, 12 GB for the longest run.
  Eigen::Vector3d mean_a = Eigen::Vector3d::Zero(), sum_sq = Eigen::Vector3d::Zero();
  SimulationSummary s;
  s.samples = n;
  s.substeps = dynamics.substeps();
  s.internal_step_s = dynamics.internal_step_s();

  double integration_s = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const DynamicSample& sample = dynamics.step();
    integration_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (i >= half) {
      const Eigen::Vector3d a = sample.acceleration.head<3>();
      const Eigen::Vector3d before = a - mean_a;
      mean_a += before / static_cast<double>(i - half + 1);
      sum_sq += before.cwiseProduct(a - mean_a);
      s.mean_displacement += sample.displacement;
    }
    if (on_sample) on_sample(sample);
  }
  const double kept = static_cast<double>(n - half);
  s.mean_displacement /= kept;
  s.a_rms_x = std::sqrt(sum_sq[0] / kept);
  s.a_rms_y = std::sqrt(sum_sq[1] / kept);
  s.a_rms_z = std::sqrt(sum_sq[2] / kept);
  s.level_db = vibration_level_db(s.a_rms_x);
  s.realtime_factor = request.duration_s / integration_s;
  return s;
}

}  // namespace bearing_sim
