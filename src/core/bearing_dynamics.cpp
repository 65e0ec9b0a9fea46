#include "bearing_sim/core/bearing_dynamics.hpp"

#include <cmath>
#include <limits>
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
  samples_since_split_ = 0;  // the contact margin depends on the inputs
}

void BearingDynamics::set_ring_speed(double ring_speed_rad_s) {
  if (!std::isfinite(ring_speed_rad_s)) throw InvalidInputError("ring speed is not finite");
  ring_speed_ = ring_speed_rad_s;
  update_cage_speed();
  samples_since_split_ = 0;
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
  samples_since_split_ = 0;  // the contact margin depends on the inputs
}

void BearingDynamics::reset_to_equilibrium() {
  const Vector5 guess = current_.displacement;
  const bool have_guess = sample_index_ > 0 && guess.allFinite();
  const StaticSolution s = solve_static(model_, load_, current_.cage_angle_rad, {}, have_guess ? &guess : nullptr);
  current_.displacement = s.displacement;
  current_.velocity.setZero();
  current_.acceleration =
      acceleration(current_.displacement, current_.velocity, current_.cage_angle_rad, model_.balls());
  acceleration_current_ = true;
  samples_since_split_ = 0;
}

Vector5 BearingDynamics::acceleration(const Vector5& q, const Vector5& q_dot, double cage_angle,
                                      const BallArrays& balls) const {
  return (load_ + model_.contact_force(q, q_dot, cage_angle, balls)).cwiseProduct(inverse_mass_);
}

double BearingDynamics::contact_margin_m(const Vector5& q, const Vector5& v, const Vector5& a) const {
  // Bound on how far any ball's deflection can move until the next split: ring motion
  // (velocity and acceleration over that time, with a factor 2 on the latter since the
  // acceleration oscillates) plus the balls' travel in azimuth, where
  // |d delta / d phi| <= 2|t| + 3|theta| * lever arm. Doubled for safety.
  const double h = kSamplesPerBallSplit / options_.sample_rate_hz;
  const double lever = model_.max_lever_arm_m();
  const double motion = (v.head<3>().norm() + v.tail<2>().norm() * lever) * h +
                        (a.head<3>().norm() + a.tail<2>().norm() * lever) * h * h;
  const double travel =
      std::abs(cage_speed_) * h * (2.0 * q.head<3>().norm() + 3.0 * q.tail<2>().norm() * lever);
  return 2.0 * (motion + travel) + 1e-10;
}

void BearingDynamics::integrate_sample(Vector5& q, Vector5& v, double& angle, const Vector5& a_start,
                                       const BallArrays& balls) const {
  const double h = 1.0 / (options_.sample_rate_hz * substeps_);
  for (int i = 0; i < substeps_; ++i) {
    const double mid = angle + 0.5 * h * cage_speed_, end = angle + h * cage_speed_;
    const Vector5 a1 = i == 0 ? a_start : acceleration(q, v, angle, balls);
    const Vector5 v2 = v + 0.5 * h * a1, q2 = q + 0.5 * h * v;
    const Vector5 a2 = acceleration(q2, v2, mid, balls);
    const Vector5 v3 = v + 0.5 * h * a2, q3 = q + 0.5 * h * v2;
    const Vector5 a3 = acceleration(q3, v3, mid, balls);
    const Vector5 v4 = v + h * a3, q4 = q + h * v3;
    const Vector5 a4 = acceleration(q4, v4, end, balls);
    q += h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4);
    v += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    angle = end;
  }
}

DynamicSample BearingDynamics::step() {
  const Vector5& q0 = current_.displacement;
  const Vector5& v0 = current_.velocity;
  const double angle0 = current_.cage_angle_rad;
  // The last sample's acceleration is the first stage, unless an input changed since.
  const Vector5 a_start = acceleration_current_ ? current_.acceleration : acceleration(q0, v0, angle0, model_.balls());
  // Only the balls that can touch during the next kSamplesPerBallSplit samples take part
  // in the integration; the others carry no load now, so a_start holds for either set.
  if (samples_since_split_ == 0) {
    const double margin = options_.skip_clear_balls ? contact_margin_m(q0, v0, a_start)
                                                    : std::numeric_limits<double>::infinity();
    model_.split_by_deflection(q0, angle0, margin, &active_balls_, &clear_balls_);
  }
  samples_since_split_ = (samples_since_split_ + 1) % kSamplesPerBallSplit;
  const BallArrays* balls = &active_balls_;
  Vector5 q = q0, v = v0;
  double angle = angle0;
  integrate_sample(q, v, angle, a_start, *balls);
  if (clear_balls_.size() > 0 && q.allFinite() && model_.max_deflection(q, angle, clear_balls_) > 0.0) {
    // A ball outside the margin came into contact: redo the sample with every ball.
    ++full_sample_retries_;
    samples_since_split_ = 0;
    balls = &model_.balls();
    q = q0;
    v = v0;
    angle = angle0;
    integrate_sample(q, v, angle, a_start, *balls);
  }
  return commit_sample(q, v, acceleration(q, v, angle, *balls), angle);
}

DynamicSample BearingDynamics::commit_sample(const Vector5& q, const Vector5& v, const Vector5& a, double angle) {
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
