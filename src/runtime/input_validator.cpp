#include "bearing_sim/runtime/input_validator.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Cholesky>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/symmetric_eigen.hpp"

namespace bearing_sim {
namespace runtime {

InputCheck check_load(const Vector5& load, const InputLimits& limits, const BearingModel* model) {
  InputCheck c;
  std::ostringstream why;
  const double force = load.head<3>().norm(), moment = load.tail<2>().norm();
  if (!load.allFinite()) {
    why << "load is not finite";
  } else if (force > limits.max_force_N) {
    why << "force " << force << " N exceeds max_force_N = " << limits.max_force_N;
  } else if (moment > limits.max_moment_Nm) {
    why << "moment " << moment << " N*m exceeds max_moment_Nm = " << limits.max_moment_Nm;
  } else if (model) {
    // A load with no static equilibrium would only drive the dynamics to divergence.
    try {
      c.max_contact_pressure_Pa = solve_static(*model, load).max_contact_pressure_Pa;
    } catch (const LoadNotCarriedError& e) {
      why << "load not carried: " << e.what();
    } catch (const InvalidInputError& e) {
      why << "invalid load: " << e.what();
    }
  }
  c.reason = why.str();
  c.accepted = c.reason.empty();
  return c;
}

InputCheck check_speed(double ring_speed_rad_s, const InputLimits& limits, const BearingModel* model) {
  InputCheck c;
  std::ostringstream why;
  if (!std::isfinite(ring_speed_rad_s)) why << "speed is not finite";
  else if (model && !ring_speed_refusal(ring_speed_rad_s, model->config().pitch_diameter_m).empty())
    why << "speed " << ring_speed_refusal(ring_speed_rad_s, model->config().pitch_diameter_m);
  else if (std::abs(ring_speed_rad_s) > limits.max_speed_rad_s)
    why << "speed " << ring_speed_rad_s << " rad/s exceeds max_speed_rad_s = " << limits.max_speed_rad_s;
  c.reason = why.str();
  c.accepted = c.reason.empty();
  return c;
}

std::string frequency_text(double hz) {
  std::ostringstream s;
  s.precision(3);
  if (hz >= 1e6) s << hz / 1e6 << " MHz";
  else if (hz >= 1e3) s << hz / 1e3 << " kHz";
  else s << hz << " Hz";
  return s.str();
}

InputCheck check_integrator_work(const BearingModel& model, const Vector5& load, double* fastest_rate_rad_s) {
  InputCheck c;
  const double rate = BearingDynamics::fastest_rate_rad_s(model, load);
  if (fastest_rate_rad_s) *fastest_rate_rad_s = rate;
  if (rate <= kMaxStiffRateRadS) return c;  // NaN fails too
  // Which cause: the fastest mode of the undamped ring (M^-1/2 K M^-1/2), whose inertia is
  // too small for its stiffness; or contact damping far above critical (M^-1/2 C M^-1/2).
  // A tiny inertia raises both (the damping rate as 1/J, the mode as 1/sqrt(J)), so the
  // mode decides: a ring's rigid-body modes on its balls lie well below 100 kHz (a 6205's
  // near 5 kHz, the CT ring's near 1 kHz), so a mode above it means the inertia is wrong.
  const StaticSolution s = solve_static(model, load);
  Matrix5 damping;
  model.contact_force_and_stiffness(s.displacement, RollingPhase{}, nullptr, &damping);
  // M = L L^T: L^-1 K L^-T and L^-1 C L^-T (M^-1/2 K M^-1/2 for a diagonal M).
  const Matrix5 l_inv = Eigen::LLT<Matrix5>(model.mass_matrix()).matrixL().solve(Matrix5::Identity());
  const Matrix5 a = l_inv * s.stiffness * l_inv.transpose();
  const Matrix5 d = l_inv * damping * l_inv.transpose();
  const SymmetricEigen5 eigen = symmetric_eigen(0.5 * (a + a.transpose()), true);
  const double omega_max = std::sqrt(std::max(0.0, eigen.eigenvalues[4]));
  const double damping_rate = symmetric_eigen(0.5 * (d + d.transpose()), false).eigenvalues[4];
  const BearingConfig& b = model.config();
  std::ostringstream why;
  constexpr double kHighestPlausibleModeHz = 1.0e5;
  if (omega_max / kTwoPi <= kHighestPlausibleModeHz) {
    why.precision(3);
    why << "overdamped contacts decaying at " << damping_rate << " 1/s (c/m, the ring's fastest mode is "
        << frequency_text(omega_max / kTwoPi) << ")"
        << ": damping.contact_damping_Ns_per_m (" << b.contact_damping_Ns_per_m
        << ") is implausibly large for this bearing";
  } else {
    Eigen::Index dof = 0;
    // The mode's shape in the ring's coordinates, each DOF weighted by its own inertia.
    const Vector5 shape = l_inv.transpose() * eigen.eigenvectors.col(4);
    shape.cwiseProduct(model.mass_matrix().diagonal().cwiseSqrt()).cwiseAbs().maxCoeff(&dof);
    const std::string mode = dof >= 3 ? "tilt" : dof == 2 ? "axial" : "radial";
    why << mode << " mode at " << frequency_text(omega_max / kTwoPi) << ": ";
    if (dof >= 3)
      why << "tilt_inertia_kg_m2 (" << b.tilt_inertia_kg_m2
          << (b.tilt_inertia_given ? "" : ", derived from rotating_mass_kg and the envelope")
          << ") is implausibly small for this bearing";
    else why << "rotating_mass_kg (" << b.rotating_mass_kg << ") is implausibly small for this bearing";
  }
  c.reason = why.str();
  c.accepted = false;
  return c;
}

InputCheck check_setting(double value, const SettingRange& range) {
  InputCheck c;
  if (!std::isfinite(value) || value < range.min || value > range.max) {
    std::ostringstream why;
    why << range.name << " = " << value << " refused: must be finite and in [" << range.min << ", " << range.max << "]";
    c.reason = why.str();
  }
  c.accepted = c.reason.empty();
  return c;
}

}  // namespace runtime
}  // namespace bearing_sim
