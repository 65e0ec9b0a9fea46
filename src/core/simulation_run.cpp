#include "bearing_sim/core/simulation_run.hpp"

#include <array>
#include <chrono>
#include <cmath>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/ring_dynamics.hpp"
#include "bearing_sim/core/signal_statistics.hpp"
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

  // The rigid ring's BearingDynamics, or a flexible ring's FlexibleDynamics (its rigid-body
  // coordinates' samples).
  const std::unique_ptr<RingDynamics> ring =
      make_ring_dynamics(model, request.load, request.ring_speed_rad_s,
                         DynamicsOptions{request.sample_rate_hz, request.substeps, true, request.method});
  RingDynamics& dynamics = *ring;
  const std::size_t half = n / 2;
  // Mean and RMS about it streamed: a buffer of the accelerations took 12 bytes per sample,
  // 12 GB for the longest run.
  std::array<StreamedStatistics, 3> accel;
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
      for (int axis = 0; axis < 3; ++axis) accel[axis].add(sample.acceleration[axis]);
      s.mean_displacement += sample.displacement;
    }
    if (on_sample) on_sample(sample);
  }
  const double kept = static_cast<double>(n - half);
  s.mean_displacement /= kept;
  s.a_rms_x = accel[0].statistics().rms;
  s.a_rms_y = accel[1].statistics().rms;
  s.a_rms_z = accel[2].statistics().rms;
  s.level_db = vibration_level_db(s.a_rms_x);
  s.realtime_factor = request.duration_s / integration_s;
  return s;
}

}  // namespace bearing_sim
