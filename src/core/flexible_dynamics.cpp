#include "bearing_sim/core/flexible_dynamics.hpp"

#include <cmath>
#include <string>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"

namespace bearing_sim {

FlexibleDynamics::FlexibleDynamics(FlexibleBearing bearing, const Vector5& load, double ring_speed_rad_s,
                                   double sample_rate_hz, int substeps)
    : bearing_(std::move(bearing)), load_(load), sample_rate_hz_(sample_rate_hz) {
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz))
    throw InvalidInputError("flexible ring dynamics: the sample rate must be > 0");
  if (!std::isfinite(ring_speed_rad_s)) throw InvalidInputError("flexible ring dynamics: non-finite ring speed");
  check_ring_speed(ring_speed_rad_s, bearing_.model().config().pitch_diameter_m, "flexible ring dynamics: ring speed");
  if (substeps < 0 || substeps > 100000) throw InvalidInputError("flexible ring dynamics: substeps out of range");
  const BearingModel& model = bearing_.model();
  const Eigen::MatrixXd mass = bearing_.mass_matrix();  // throws without rotating_mass_kg
  mass_.compute(mass);
  k_ring_ = bearing_.ring_stiffness();
  c_ring_ = bearing_.ring_damping();
  external_ = Eigen::VectorXd::Zero(bearing_.size());
  external_.head<5>() = load;
  model.ring_speeds(ring_speed_rad_s, &inner_speed_, &outer_speed_);
  // The mean cage slip is kept; its random fluctuation is not modelled here.
  cage_speed_ = model.cage_speed_rad_s(inner_speed_, outer_speed_) * (1.0 - model.config().imperfections.cage_slip);
  spin_speed_ = model.ball_spin_speed_rad_s(inner_speed_, outer_speed_);

  equilibrium_ = solve_flexible_static(bearing_, load, RollingPhase{});
  highest_frequency_rad_s_ = flexible_natural_frequencies_rad_s(bearing_, equilibrium_).maxCoeff();
  substeps_ = substeps > 0 ? substeps
                           : std::max(1, static_cast<int>(std::ceil(highest_frequency_rad_s_ /
                                                                     (kStepTimesOmegaMax * sample_rate_hz))));
  current_.coordinates = equilibrium_.coordinates;
  // The static shape is fixed to the load, so the turning ring runs through it: in the ring's
  // own frame each mode's (cos, sin) pair turns at n Omega, (a, b)' = n Omega (b, -a). Starting
  // with that rate instead of at rest spares the run a start-up transient of the ring's modes.
  current_.velocities = Eigen::VectorXd::Zero(bearing_.size());
  const double ring_rate = model.config().rotating_ring == RotatingRing::Outer ? outer_speed_ : inner_speed_;
  const auto& modes = bearing_.modes();
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const double turn = modes[i].order * ring_rate;
    current_.velocities[5 + 2 * i] = turn * current_.coordinates[6 + 2 * i];
    current_.velocities[6 + 2 * i] = -turn * current_.coordinates[5 + 2 * i];
  }
  current_.accelerations = acceleration(current_.coordinates, current_.velocities, current_.phase);
}

RollingPhase FlexibleDynamics::advanced(const RollingPhase& p, double dt) const {
  return RollingPhase{p.cage + cage_speed_ * dt, p.inner_ring + inner_speed_ * dt, p.outer_ring + outer_speed_ * dt,
                      p.ball_spin + spin_speed_ * dt, p.time_s + dt};
}

Eigen::VectorXd FlexibleDynamics::acceleration(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                               const RollingPhase& phase) const {
  const Eigen::VectorXd f = external_ + bearing_.contact_force(x, v, phase) - k_ring_.cwiseProduct(x) -
                            c_ring_.cwiseProduct(v);
  return mass_.solve(f);
}

const FlexibleSample& FlexibleDynamics::step() {
  const double h = internal_step_s();
  Eigen::VectorXd x = current_.coordinates, v = current_.velocities, a = current_.accelerations;
  RollingPhase phase = current_.phase;
  for (int s = 0; s < substeps_; ++s) {
    const RollingPhase mid = advanced(phase, 0.5 * h), end = advanced(phase, h);
    const Eigen::VectorXd x2 = x + 0.5 * h * v, v2 = v + 0.5 * h * a;
    const Eigen::VectorXd a2 = acceleration(x2, v2, mid);
    const Eigen::VectorXd x3 = x + 0.5 * h * v2, v3 = v + 0.5 * h * a2;
    const Eigen::VectorXd a3 = acceleration(x3, v3, mid);
    const Eigen::VectorXd x4 = x + h * v3, v4 = v + h * a3;
    const Eigen::VectorXd a4 = acceleration(x4, v4, end);
    x += h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4);
    v += h / 6.0 * (a + 2.0 * a2 + 2.0 * a3 + a4);
    phase = end;
    a = acceleration(x, v, phase);
  }
  if (!x.allFinite() || !v.allFinite())
    throw DivergenceError(bearing_.model().config().name + ": the flexible ring's state is not finite at t = " +
                          std::to_string(phase.time_s) + " s");
  ++sample_index_;
  // The time from the sample count, so that it does not drift with the summed steps.
  phase.time_s = static_cast<double>(sample_index_) / sample_rate_hz_;
  current_.time_s = phase.time_s;
  current_.phase = phase;
  current_.coordinates = x;
  current_.velocities = v;
  current_.accelerations = a;
  return current_;
}

}  // namespace bearing_sim
