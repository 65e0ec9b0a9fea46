#include "bearing_sim/core/flexible_dynamics.hpp"

#include <cmath>
#include <string>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"

namespace bearing_sim {

FlexibleDynamics::FlexibleDynamics(FlexibleBearing bearing, const Vector5& load, double ring_speed_rad_s,
                                   double sample_rate_hz, int substeps, IntegrationMethod method)
    : bearing_(std::move(bearing)), sample_rate_hz_(sample_rate_hz), method_(method) {
  if (method != IntegrationMethod::Rk4 && method != IntegrationMethod::ExponentialAdamsPec)
    throw InvalidInputError(std::string("flexible ring dynamics: integrator ") + integration_method_name(method) +
                            " is not available for a flexible ring (adams_pec or rk4)");
  if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz))
    throw InvalidInputError("flexible ring dynamics: the sample rate must be > 0");
  if (!std::isfinite(ring_speed_rad_s)) throw InvalidInputError("flexible ring dynamics: non-finite ring speed");
  if (!load.allFinite()) throw InvalidInputError("flexible ring dynamics: the load is not finite");
  check_ring_speed(ring_speed_rad_s, bearing_.model().config().pitch_diameter_m, "flexible ring dynamics: ring speed");
  if (substeps < 0 || substeps > 100000) throw InvalidInputError("flexible ring dynamics: substeps out of range");
  load_line_.load = load;
  ring_speed_ = ring_speed_rad_s;
  bearing_changed();  // throws without rotating_mass_kg

  equilibrium_ = solve_flexible_static(bearing_, load, RollingPhase{});
  const Eigen::VectorXd natural = flexible_natural_frequencies_rad_s(bearing_, equilibrium_);
  highest_frequency_rad_s_ = natural.maxCoeff();
  const bool adams = method == IntegrationMethod::ExponentialAdamsPec;
  automatic_substeps_ = substeps == 0;
  substeps_ =
      substeps > 0 ? substeps
      : adams
          ? automatic_adams_steps()
          : std::max(1, static_cast<int>(std::ceil(highest_frequency_rad_s_ / (kStepTimesOmegaMax * sample_rate_hz))));
  current_.coordinates = equilibrium_.coordinates;
  // Starting with the shape's turning rate instead of at rest spares the run a start-up
  // transient of the ring's modes.
  current_.velocities = static_shape_velocities(current_.coordinates);
  current_.accelerations = acceleration(current_.coordinates, current_.velocities, current_.phase);
  // In the load's frame the static shape stands still: start from it at rest (at t = 0 the
  // frames coincide).
  if (adams) {
    lowest_frequency_lin_rad_s_ = natural.minCoeff();
    start_adams(equilibrium_.coordinates, Eigen::VectorXd::Zero(bearing_.size()), 0.0);
  }
}

void FlexibleDynamics::bearing_changed() {
  const BearingModel& model = bearing_.model();
  const Eigen::MatrixXd mass = bearing_.mass_matrix();  // throws without rotating_mass_kg
  mass_.compute(mass);
  inverse_rigid_mass_ = mass.topLeftCorner<5, 5>().inverse();
  k_ring_ = bearing_.ring_stiffness();
  c_ring_ = bearing_.ring_damping();
  external_ = Eigen::VectorXd::Zero(bearing_.size());
  max_order_ = 0;
  for (const RingMode& m : bearing_.modes()) max_order_ = std::max(max_order_, m.order);
  (void)model;
  update_speeds();
}

void FlexibleDynamics::update_speeds() {
  const BearingModel& model = bearing_.model();
  model.ring_speeds(ring_speed_, &inner_speed_, &outer_speed_);
  // The mean cage slip is kept; its random fluctuation is not modelled here.
  cage_speed_ = model.cage_speed_rad_s(inner_speed_, outer_speed_) * (1.0 - model.config().imperfections.cage_slip);
  spin_speed_ = model.ball_spin_speed_rad_s(inner_speed_, outer_speed_);
}

const Eigen::VectorXd& FlexibleDynamics::external_at(double t) const {
  external_.head<5>() = load_line_.at(t);
  return external_;
}

void FlexibleDynamics::linearization_steps(Eigen::VectorXd* z_step, Eigen::VectorXd* v_step) const {
  // Difference steps for the linear part: 1 nm, 1 nm over the pitch radius for the tilts; 1 um/s.
  const int n = bearing_.size();
  const double rp = bearing_.model().pitch_radius_m();
  *z_step = Eigen::VectorXd::Constant(n, 1e-9);
  *v_step = Eigen::VectorXd::Constant(n, 1e-6);
  z_step->segment<2>(3) /= rp;
  v_step->segment<2>(3) /= rp;
}

void FlexibleDynamics::start_adams(const Eigen::VectorXd& z0, const Eigen::VectorXd& v0, double t0) {
  Eigen::VectorXd z_step, v_step;
  linearization_steps(&z_step, &v_step);
  adams_.emplace(load_frame_function(), z0, z_step, v_step, z0, v0, internal_step_s(), t0);
  load_lin_ = load_line_.load;
  speed_lin_ = ring_rate_rad_s();
  samples_since_linearization_ = 0;
  ++linearizations_;
}

void FlexibleDynamics::relinearize_adams() {
  const double t = adams_->time_s();
  const RollingPhase phase = phase_at(t);
  // About the equilibrium of the current load (the ring vibrates about it), its shape in the
  // load's frame, or about the current state when there is none.
  Eigen::VectorXd z_lin = adams_->position();
  try {
    const FlexibleStaticSolution s = solve_flexible_static(bearing_, load_line_.load, phase);
    z_lin = to_load_frame(s.coordinates, bearing_.ring_angle_rad(phase));
    lowest_frequency_lin_rad_s_ = flexible_natural_frequencies_rad_s(bearing_, s).minCoeff();
  } catch (const LoadNotCarriedError&) {
  }
  Eigen::VectorXd z_step, v_step;
  linearization_steps(&z_step, &v_step);
  adams_->relinearize(load_frame_function(), z_lin, z_step, v_step);
  load_lin_ = load_line_.load;
  speed_lin_ = ring_rate_rad_s();
  samples_since_linearization_ = 0;
  ++linearizations_;
}

Eigen::VectorXd FlexibleDynamics::to_load_frame(const Eigen::VectorXd& x, double psi) const {
  Eigen::VectorXd z = x;
  const auto& modes = bearing_.modes();
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const int j = 5 + 2 * static_cast<int>(i);
    const double c = std::cos(modes[i].order * psi), s = std::sin(modes[i].order * psi);
    z[j] = c * x[j] - s * x[j + 1];
    z[j + 1] = s * x[j] + c * x[j + 1];
  }
  return z;
}

void FlexibleDynamics::set_load(const Vector5& load) { set_load(load, load); }

void FlexibleDynamics::set_load(const Vector5& load, const Vector5& load_at_sample_end) {
  if (!load.allFinite()) throw InvalidInputError("load is not finite");
  if (!load_at_sample_end.allFinite()) throw InvalidInputError("load at the sample's end is not finite");
  const double half_sample_s = 0.5 / sample_rate_hz_;
  change_load(load, (load_at_sample_end - load) / half_sample_s, state_time_s() + half_sample_s);
}

void FlexibleDynamics::change_load(const Vector5& load, const Vector5& rate, double mid_time_s) {
  const LoadLine before = load_line_;
  load_line_ = LoadLine{load, rate, mid_time_s};
  // The contact forces do not depend on the external load: the accelerations move by the
  // change over the mass (zero on the modes: the mass matrix is block diagonal), the current
  // one and the Adams remainders each at its time.
  const auto moved = [&](double t) -> Vector5 { return inverse_rigid_mass_ * (load_line_.at(t) - before.at(t)); };
  if (adams_) adams_->add_to_rigid_remainders(moved);
  current_.accelerations.head<5>() += moved(state_time_s());
}

void FlexibleDynamics::set_ring_speed(double ring_speed_rad_s) {
  if (!std::isfinite(ring_speed_rad_s)) throw InvalidInputError("ring speed is not finite");
  check_ring_speed(ring_speed_rad_s, bearing_.model().config().pitch_diameter_m, "ring speed");
  // The phases go on from now at the new speeds.
  origin_ = current_.phase;
  origin_.time_s = state_time_s();
  const double rate_before = ring_rate_rad_s();
  ring_speed_ = ring_speed_rad_s;
  update_speeds();
  const double change = ring_rate_rad_s() - rate_before;
  if (adams_ && change != 0.0) {
    // The material's motion stays; its rate in the load's frame, b' = R a' + n Omega J b, moves.
    const auto& modes = bearing_.modes();
    adams_->change_velocities([&](const Eigen::VectorXd& z, Eigen::VectorXd& v) {
      for (std::size_t i = 0; i < modes.size(); ++i) {
        const int j = 5 + 2 * static_cast<int>(i);
        const double dw = modes[i].order * change;
        v[j] -= dw * z[j + 1];
        v[j + 1] += dw * z[j];
      }
    });
  }
  // The ring frame's accelerations (RK4's first stage) hold: x and x' are the material's.
}

void FlexibleDynamics::set_model(BearingModel model) {
  if (!model.config().flexible_ring.present)
    throw InvalidInputError(model.config().name + ": a flexible-ring run needs a bearing with a flexible_ring block");
  FlexibleBearing bearing(std::move(model));
  if (bearing.size() != bearing_.size())
    throw InvalidInputError(bearing.model().config().name + ": the new bearing's ring has " +
                            std::to_string(bearing.modes().size()) + " modes, the running one " +
                            std::to_string(bearing_.modes().size()));
  bearing_ = std::move(bearing);
  bearing_changed();
  current_.accelerations = acceleration(current_.coordinates, current_.velocities, current_.phase);
  if (adams_) relinearize_adams();
}

void FlexibleDynamics::add_spall(Spall spall) {
  spall.created_at_s = state_time_s();
  BearingModel model = bearing_.model();
  model.add_spall(spall);
  bearing_ = FlexibleBearing(std::move(model));
  current_.accelerations = acceleration(current_.coordinates, current_.velocities, current_.phase);
  defects_changed();
}

int FlexibleDynamics::automatic_adams_steps() const {
  return bearing_.model().imperfections().spalls().empty() ? kAdamsStepsPerSample : kAdamsStepsPerSampleWithSpall;
}

void FlexibleDynamics::defects_changed() {
  if (!adams_) return;
  if (!automatic_substeps_ || automatic_adams_steps() == substeps_) {
    adams_->refresh(load_frame_function());  // the remainder jumps
    return;
  }
  // Another step: the history's spacing no longer fits; start again from the state.
  substeps_ = automatic_adams_steps();
  const Eigen::VectorXd z = adams_->position(), v = adams_->velocity();
  const double t = adams_->time_s();
  start_adams(z, v, t);
  relinearize_adams();  // at the static equilibrium of the load
}

void FlexibleDynamics::clear_spalls() {
  BearingModel model = bearing_.model();
  model.clear_spalls();
  bearing_ = FlexibleBearing(std::move(model));
  current_.accelerations = acceleration(current_.coordinates, current_.velocities, current_.phase);
  defects_changed();
}

Eigen::VectorXd FlexibleDynamics::static_shape_velocities(const Eigen::VectorXd& coordinates) const {
  // The static shape is fixed to the load, so the turning ring runs through it: in the ring's
  // own frame each mode's (cos, sin) pair turns at n Omega, (a, b)' = n Omega (b, -a).
  Eigen::VectorXd velocities = Eigen::VectorXd::Zero(bearing_.size());
  const double ring_rate = ring_rate_rad_s();
  const auto& modes = bearing_.modes();
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const double turn = modes[i].order * ring_rate;
    velocities[5 + 2 * i] = turn * coordinates[6 + 2 * i];
    velocities[6 + 2 * i] = -turn * coordinates[5 + 2 * i];
  }
  return velocities;
}

void FlexibleDynamics::reset_to_equilibrium() {
  const double t = state_time_s();
  RollingPhase phase = current_.phase;
  phase.time_s = t;
  const FlexibleStaticSolution s = solve_flexible_static(bearing_, load_line_.load, phase);
  current_.time_s = t;
  current_.phase = phase;
  current_.coordinates = s.coordinates;
  current_.velocities = static_shape_velocities(current_.coordinates);
  current_.accelerations = acceleration(current_.coordinates, current_.velocities, phase);
  origin_ = phase;
  if (adams_) {
    lowest_frequency_lin_rad_s_ = flexible_natural_frequencies_rad_s(bearing_, s).minCoeff();
    start_adams(to_load_frame(s.coordinates, bearing_.ring_angle_rad(phase)), Eigen::VectorXd::Zero(bearing_.size()),
                t);
  }
}

double FlexibleDynamics::ring_rate_rad_s() const {
  return bearing_.model().config().rotating_ring == RotatingRing::Outer ? outer_speed_ : inner_speed_;
}

void FlexibleDynamics::to_ring_frame(const Eigen::VectorXd& z, const Eigen::VectorXd& z_dot,
                                     const Eigen::VectorXd* z_ddot, double t, Eigen::VectorXd* x,
                                     Eigen::VectorXd* x_dot, Eigen::VectorXd* x_ddot) const {
  *x = z;
  material_rate(z, z_dot, x_dot);  // R a', turned back below
  if (z_ddot) *x_ddot = *z_ddot;
  const double psi = bearing_.ring_angle_rad(phase_at(t)), rate = ring_rate_rad_s();
  const auto& modes = bearing_.modes();
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const int j = 5 + 2 * static_cast<int>(i);
    const double c = std::cos(modes[i].order * psi), s = std::sin(modes[i].order * psi);
    const double w = modes[i].order * rate;
    const double b0 = z[j], b1 = z[j + 1];
    // a = R^T b; a' = R^T (b' - w J b); a'' = R^T (b'' - 2 w J b' - w^2 b), J = [0 -1; 1 0].
    (*x)[j] = c * b0 + s * b1;
    (*x)[j + 1] = -s * b0 + c * b1;
    const double r0 = (*x_dot)[j], r1 = (*x_dot)[j + 1];
    (*x_dot)[j] = c * r0 + s * r1;
    (*x_dot)[j + 1] = -s * r0 + c * r1;
    if (z_ddot) {
      const double q0 = (*z_ddot)[j] + 2.0 * w * z_dot[j + 1] - w * w * b0;
      const double q1 = (*z_ddot)[j + 1] - 2.0 * w * z_dot[j] - w * w * b1;
      (*x_ddot)[j] = c * q0 + s * q1;
      (*x_ddot)[j + 1] = -s * q0 + c * q1;
    }
  }
}

void FlexibleDynamics::material_rate(const Eigen::VectorXd& z, const Eigen::VectorXd& z_dot,
                                     Eigen::VectorXd* rate_out) const {
  *rate_out = z_dot;
  const double rate = ring_rate_rad_s();
  const auto& modes = bearing_.modes();
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const int j = 5 + 2 * static_cast<int>(i);
    const double w = modes[i].order * rate;
    (*rate_out)[j] += w * z[j + 1];
    (*rate_out)[j + 1] -= w * z[j];
  }
}

Eigen::VectorXd FlexibleDynamics::load_frame_acceleration(const Eigen::VectorXd& z, const Eigen::VectorXd& z_dot,
                                                          double t) const {
  // The ring's own stiffness and damping act on b and on the material's rate (both isotropic
  // per pair), the contact damping on the material's rate too.
  const double rate = ring_rate_rad_s();
  const auto& modes = bearing_.modes();
  material_rate(z, z_dot, &material_rate_);
  const RollingPhase phase = phase_at(t);
  const Eigen::VectorXd contact = bearing_.contact_force_load_frame(z, material_rate_, phase, true, &contact_work_);
  Eigen::VectorXd a =
      mass_.solve(external_at(t) + contact - k_ring_.cwiseProduct(z) - c_ring_.cwiseProduct(material_rate_));
  // b'' = R a'' + 2 w J b' + w^2 b.
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const int j = 5 + 2 * static_cast<int>(i);
    const double w = modes[i].order * rate;
    a[j] += -2.0 * w * z_dot[j + 1] + w * w * z[j];
    a[j + 1] += 2.0 * w * z_dot[j] + w * w * z[j + 1];
  }
  return a;
}

RollingPhase FlexibleDynamics::advanced(const RollingPhase& p, double dt) const {
  return p.advanced(cage_speed_, inner_speed_, outer_speed_, spin_speed_, dt);
}

Eigen::VectorXd FlexibleDynamics::acceleration(const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                                               const RollingPhase& phase) const {
  const Eigen::VectorXd f = external_at(phase.time_s) + bearing_.contact_force(x, v, phase) - k_ring_.cwiseProduct(x) -
                            c_ring_.cwiseProduct(v);
  return mass_.solve(f);
}

const FlexibleSample& FlexibleDynamics::step() {
  if (adams_) {
    // A changed load or speed is followed at most every kSamplesPerLinearization samples, so
    // that an input changing every sample cannot make every sample pay for a linearization.
    ++samples_since_linearization_;
    if (samples_since_linearization_ >= kSamplesPerLinearization &&
        ((load_line_.load - load_lin_).norm() > kRelinearizeLoadChange * load_lin_.norm() ||
         max_order_ * std::abs(ring_rate_rad_s() - speed_lin_) > kRelinearizeTurnChange * lowest_frequency_lin_rad_s_))
      relinearize_adams();
    step_adams();
  } else {
    step_rk4();
  }
  // A load line is for one sample: from its end on the load holds the end value.
  if (!load_line_.rate.isZero()) {
    const double t = state_time_s();
    change_load(load_line_.at(t), Vector5::Zero(), t);
  }
  return current_;
}

void FlexibleDynamics::step_adams() {
  const FlexibleAdams::Acceleration accel = [this](const Eigen::VectorXd& z, const Eigen::VectorXd& zd, double t) {
    return load_frame_acceleration(z, zd, t);
  };
  for (int s = 0; s < substeps_; ++s) adams_->step(accel);
  if (!adams_->position().allFinite() || !adams_->velocity().allFinite())
    throw DivergenceError(bearing_.model().config().name + ": the flexible ring's state is not finite at t = " +
                          std::to_string(adams_->time_s()) + " s");
  ++sample_index_;
  const double t = static_cast<double>(sample_index_) / sample_rate_hz_;
  RollingPhase phase = phase_at(adams_->time_s());
  phase.time_s = t;
  current_.time_s = t;
  current_.phase = phase;
  to_ring_frame(adams_->position(), adams_->velocity(), &adams_->acceleration(), adams_->time_s(),
                &current_.coordinates, &current_.velocities, &current_.accelerations);
}

void FlexibleDynamics::step_rk4() {
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
    throw DivergenceError(bearing_.model().config().name +
                          ": the flexible ring's state is not finite at t = " + std::to_string(phase.time_s) + " s");
  ++sample_index_;
  // The time from the sample count, so that it does not drift with the summed steps.
  phase.time_s = static_cast<double>(sample_index_) / sample_rate_hz_;
  current_.time_s = phase.time_s;
  current_.phase = phase;
  current_.coordinates = x;
  current_.velocities = v;
  current_.accelerations = a;
}

}  // namespace bearing_sim
