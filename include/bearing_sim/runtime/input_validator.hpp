#pragma once
// Checks of the load and speed inputs before they reach the dynamics (ROS-free).
#include <string>

#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim {
namespace runtime {

struct InputLimits {
  double max_force_N = 1.0e5;      // |(Fx, Fy, Fz)|
  double max_moment_Nm = 5.0e4;    // |(Mx, My)|
  double max_speed_rad_s = 100.0;  // |speed of the rotating ring|
};

struct InputCheck {
  bool accepted = true;
  std::string reason;                    // why it was rejected
  double max_contact_pressure_Pa = 0.0;  // of the static solution, when the load was solved
};

// Rejects non-finite values and magnitudes beyond the limits; if `model` is given, also a
// load that the bearing cannot carry (no static equilibrium).
InputCheck check_load(const Vector5& load, const InputLimits& limits, const BearingModel* model);
// The speed also within the bearing's physical limit (max_ring_speed_rad_s) when `model` is given.
InputCheck check_speed(double ring_speed_rad_s, const InputLimits& limits, const BearingModel* model = nullptr);

// Fastest rate of the linearized ring dynamics (a mode's angular frequency, or the decay rate
// c/m of overdamped contacts) that the automatic integration step may follow: 1e7 rad/s
// (1.6 MHz) is far above the modes of any bearing and already 1000 steps per sample at 10 kHz.
// A bearing value that passes its own range check can still create such a mode (a tilt
// inertia of 7.9e-6 kg m^2 on the CT bearing: tens of thousands of steps per sample).
constexpr double kMaxStiffRateRadS = 1.0e7;
// Rejects a bearing whose fastest rate at `load` exceeds kMaxStiffRateRadS (or is not finite);
// the reason names the mode (radial, axial, tilt; or the overdamped contacts), its frequency
// and the key behind it, e.g. "tilt mode at 35 MHz: tilt_inertia_kg_m2 (7.9e-06) is
// implausibly small for this bearing". Throws LoadNotCarriedError if the load has no
// equilibrium. `fastest_rate_rad_s` receives the rate when given.
InputCheck check_integrator_work(const BearingModel& model, const Vector5& load, double* fastest_rate_rad_s = nullptr);

// A frequency with 3 significant digits in Hz, kHz or MHz, for messages.
std::string frequency_text(double hz);

// Accepted range of one dynamic_reconfigure parameter (the ranges of cfg/BearingSim.cfg:
// the server clamps finite values to them but lets NaN through).
struct SettingRange {
  const char* name;
  double min, max;
};
constexpr SettingRange kClearanceUm{"clearance_um", -200.0, 200.0};
constexpr SettingRange kContactDampingNsPerM{"contact_damping_Ns_per_m", 0.0, 2000.0};
constexpr SettingRange kChunkSamples{"chunk_samples", 1.0, 10000.0};
constexpr SettingRange kLevelWindowS{"level_window_s", 0.01, 60.0};
constexpr SettingRange kLevelRateHz{"level_rate_hz", 0.1, 100.0};
constexpr SettingRange kBallLoadsRateHz{"ball_loads_rate_hz", 0.1, 200.0};
// Rejects a non-finite value or one outside [min, max]; the reason names the parameter and the range.
InputCheck check_setting(double value, const SettingRange& range);

}  // namespace runtime
}  // namespace bearing_sim
