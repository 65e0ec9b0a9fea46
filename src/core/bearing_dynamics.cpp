#include "bearing_sim/core/bearing_dynamics.hpp"

#include <cmath>
#include <sstream>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/quasi_static.hpp"

namespace bearing_sim {

BearingDynamics::BearingDynamics(BearingModel model, const Vector5& load, double ring_speed_rad_s,
                                 DynamicsOptions options)
    : model_(std::move(model)), options_(options) {
  if (!(options_.sample_rate_hz > 0.0) || !std::isfinite(options_.sample_rate_hz))
    throw InvalidInputError("sample rate must be a positive number of Hz");
  if (options_.substeps < 0) throw InvalidInputError("substeps must be >= 0 (0: automatic)");
  inverse_mass_ = model_.mass_diagonal().cwiseInverse();
  displacement_limit_m_ = 0.25 * model_.config().ball_diameter_m + std::abs(model_.config().clearance_m);
  set_load(load);
  set_ring_speed(ring_speed_rad_s);
  substeps_ = options_.substeps > 0 ? options_.substeps
                                    : choose_substeps(model_, load_, options_.sample_rate_hz);
  reset_to_equilibrium();
}

int BearingDynamics::choose_substeps(const BearingModel& model, const Vector5& load, double sample_rate_hz) {
  const StaticSolution s = solve_static(model, load);
  const Vector5 inv_sqrt_m = model.mass_diagonal().cwiseSqrt().cwiseInverse();
  const Matrix5 a = inv_sqrt_m.asDiagonal() * s.stiffness * inv_sqrt_m.asDiagonal();
  const double omega_max = std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Matrix5>(a).eigenvalues().maxCoeff()));
  const double h_sample = 1.0 / sample_rate_hz;
  return std::max(1, static_cast<int>(std::ceil(omega_max * h_sample / kStepTimesOmegaMax)));
}

void BearingDynamics::set_load(const Vector5& load) {
  if (!load.allFinite()) throw InvalidInputError("load is not finite");
  load_ = load;
  acceleration_current_ = false;
}

void BearingDynamics::set_ring_speed(double ring_speed_rad_s) {
  if (!std::isfinite(ring_speed_rad_s)) throw InvalidInputError("ring speed is not finite");
  ring_speed_ = ring_speed_rad_s;
  update_cage_speed();
}

void BearingDynamics::update_cage_speed() {
  double wi = 0.0, wo = 0.0;
  model_.ring_speeds(ring_speed_, &wi, &wo);
  cage_speed_ = model_.cage_speed_rad_s(wi, wo);
}

void BearingDynamics::set_model(BearingModel model) {
  const Vector5 inverse_mass = model.mass_diagonal().cwiseInverse();
  model_ = std::move(model);
  inverse_mass_ = inverse_mass;
  displacement_limit_m_ = 0.25 * model_.config().ball_diameter_m + std::abs(model_.config().clearance_m);
  update_cage_speed();
  acceleration_current_ = false;
}

void BearingDynamics::reset_to_equilibrium() {
  const Vector5 guess = current_.displacement;
  const bool have_guess = sample_index_ > 0 && guess.allFinite();
  const StaticSolution s = solve_static(model_, load_, current_.cage_angle_rad, {}, have_guess ? &guess : nullptr);
  current_.displacement = s.displacement;
  current_.velocity.setZero();
  current_.acceleration = acceleration(current_.displacement, current_.velocity, current_.cage_angle_rad);
  acceleration_current_ = true;
}

Vector5 BearingDynamics::acceleration(const Vector5& q, const Vector5& q_dot, double cage_angle) const {
  return (load_ + model_.contact_force(q, q_dot, cage_angle)).cwiseProduct(inverse_mass_);
}

DynamicSample BearingDynamics::step() {
  const double h = 1.0 / (options_.sample_rate_hz * substeps_);
  Vector5 q = current_.displacement, v = current_.velocity;
  double angle = current_.cage_angle_rad;
  for (int i = 0; i < substeps_; ++i) {
    const double mid = angle + 0.5 * h * cage_speed_, end = angle + h * cage_speed_;
    // The last sample's acceleration is the first stage, unless an input changed since.
    const Vector5 a1 = (i == 0 && acceleration_current_) ? current_.acceleration : acceleration(q, v, angle);
    const Vector5 v2 = v + 0.5 * h * a1, q2 = q + 0.5 * h * v;
    const Vector5 a2 = acceleration(q2, v2, mid);
    const Vector5 v3 = v + 0.5 * h * a2, q3 = q + 0.5 * h * v2;
    const Vector5 a3 = acceleration(q3, v3, mid);
    const Vector5 v4 = v + h * a3, q4 = q + h * v3;
    const Vector5 a4 = acceleration(q4, v4, end);
    q += h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4);
    v += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    angle = end;
  }
  const Vector5 a = acceleration(q, v, angle);
  const double translation = q.head<3>().norm();
  const double tilt = q.tail<2>().norm() * model_.pitch_radius_m();
  if (!q.allFinite() || !v.allFinite() || !a.allFinite() || translation > displacement_limit_m_ ||
      tilt > displacement_limit_m_) {
    std::ostringstream os;
    os << "dynamic state diverged at t=" << current_.time_s << " s (displacement " << translation * 1e6
       << " um, tilt at the pitch radius " << tilt * 1e6 << " um)";
    throw DivergenceError(os.str());
  }
  ++sample_index_;
  current_.time_s = static_cast<double>(sample_index_) / options_.sample_rate_hz;
  current_.cage_angle_rad = std::remainder(angle, 2.0 * 3.14159265358979323846);
  current_.displacement = q;
  current_.velocity = v;
  current_.acceleration = a;
  acceleration_current_ = true;
  return current_;
}

}  // namespace bearing_sim
