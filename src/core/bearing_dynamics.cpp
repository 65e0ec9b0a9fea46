#include "bearing_sim/core/bearing_dynamics.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include <unsupported/Eigen/MatrixFunctions>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "dynamics_eigenvalues.hpp"
#include "small_products.hpp"

namespace bearing_sim {
namespace {
// m x for the integrators' small fixed-size matrices: the SIMD kernel of small_products.hpp
// (Eigen's products at these sizes cost several times the arithmetic).
template <int Rows, int Cols>
Eigen::Matrix<double, Rows, 1> times(const Eigen::Matrix<double, Rows, Cols>& m, const double* x) {
  Eigen::Matrix<double, Rows, 1> out;
  detail::multiply_add<Rows, Cols>(m.data(), x, nullptr, out.data());
  return out;
}

}  // namespace

BearingDynamics::BearingDynamics(BearingModel model, const Vector5& load, double ring_speed_rad_s,
                                 DynamicsOptions options)
    : model_(std::move(model)), options_(options), slip_rng_(model_.config().imperfections.seed ^ 0x2545f491u) {
  if (!(options_.sample_rate_hz > 0.0) || !std::isfinite(options_.sample_rate_hz))
    throw InvalidInputError("sample rate must be a positive number of Hz");
  if (options_.substeps < 0) throw InvalidInputError("substeps must be >= 0 (0: automatic)");
  if (model_.config().flexible_ring.present)
    throw ConfigError(model_.config().name + ": key 'flexible_ring': " + kFlexibleRingNotRigid);
  set_inverse_mass(model_.mass_matrix().inverse());
  displacement_limit_m_ = 0.25 * model_.config().ball_diameter_m + std::abs(model_.clearance_m());
  set_load(load);
  set_ring_speed(ring_speed_rad_s);
  step_ratio_ = options_.substeps > 0
                    ? StepRatio{options_.substeps, 1}
                    : choose_step_ratio(model_, load_line_.load, options_.sample_rate_hz, options_.method);
  substeps_load_norm_ = load_line_.load.norm();
  slowest_mode_rad_s_ = natural_frequencies_rad_s(model_, load_line_.load).minCoeff();
  reset_to_equilibrium();
}

Vector5 BearingDynamics::natural_frequencies_rad_s(const BearingModel& model, const Vector5& load) {
  const StaticSolution s = solve_static(model, load);
  return detail::undamped_natural_frequencies(s.stiffness, model.mass_matrix());
}

double BearingDynamics::fastest_rate_rad_s(const BearingModel& model, const Vector5& load) {
  // Eigenvalues of the linearized first-order system [0 I; -M^-1 K  -M^-1 C]: |lambda| is
  // omega for light damping and grows to c/m when the contacts are overdamped, which an
  // explicit step must resolve too.
  const StaticSolution s = solve_static(model, load);
  Matrix5 damping;
  model.contact_force_and_stiffness(s.displacement, RollingPhase{}, nullptr, &damping);
  const Matrix5 inv_m = model.mass_matrix().inverse();
  Eigen::Matrix<double, 10, 10> a = Eigen::Matrix<double, 10, 10>::Zero();
  a.topRightCorner<5, 5>().setIdentity();
  a.bottomLeftCorner<5, 5>() = -(inv_m * s.stiffness);
  a.bottomRightCorner<5, 5>() = -(inv_m * damping);
  return detail::largest_eigenvalue_magnitude(a);
}

const char* integration_method_name(IntegrationMethod method) {
  switch (method) {
    case IntegrationMethod::ExponentialAdamsPec:
      return "adams_pec";
    case IntegrationMethod::ExponentialAdams:
      return "adams_pece";
    case IntegrationMethod::ExponentialRk4:
      return "etdrk4";
    case IntegrationMethod::Rk4:
      return "rk4";
  }
  return "unknown";
}

std::vector<std::string> integration_method_names() { return {"adams_pec", "adams_pece", "etdrk4", "rk4"}; }

std::optional<IntegrationMethod> integration_method_from_name(const std::string& name) {
  for (const IntegrationMethod m : {IntegrationMethod::ExponentialAdamsPec, IntegrationMethod::ExponentialAdams,
                                    IntegrationMethod::ExponentialRk4, IntegrationMethod::Rk4})
    if (name == integration_method_name(m)) return m;
  return std::nullopt;
}

double BearingDynamics::step_times_omega_max(IntegrationMethod method) {
  switch (method) {
    case IntegrationMethod::Rk4:
      return kStepTimesOmegaMax;
    case IntegrationMethod::ExponentialRk4:
      return kExponentialStepTimesOmegaMax;
    case IntegrationMethod::ExponentialAdams:
    case IntegrationMethod::ExponentialAdamsPec:
      return kAdamsStepTimesOmegaMax;
  }
  return kStepTimesOmegaMax;
}

int BearingDynamics::choose_substeps(const BearingModel& model, const Vector5& load, double sample_rate_hz,
                                     IntegrationMethod method) {
  const double rate_max = fastest_rate_rad_s(model, load);
  const double h_sample = 1.0 / sample_rate_hz;
  return std::max(1, static_cast<int>(std::ceil(rate_max * h_sample / step_times_omega_max(method))));
}

BearingDynamics::StepRatio BearingDynamics::choose_step_ratio(const BearingModel& model, const Vector5& load,
                                                              double sample_rate_hz, IntegrationMethod method) {
  if (method != IntegrationMethod::ExponentialAdams && method != IntegrationMethod::ExponentialAdamsPec)
    return {choose_substeps(model, load, sample_rate_hz, method), 1};
  const Imperfections& imperfections = model.imperfections();
  const bool spalls = !imperfections.spalls().empty();
  const double steps = fastest_rate_rad_s(model, load) / sample_rate_hz /
                       (spalls ? kAdamsWithSpallStepTimesOmegaMax : kAdamsStepTimesOmegaMax);
  // A sample within a step takes its acceleration from the cubic through the step's
  // remainders, which a ball dropping into a spall or a race's roughness (orders up to 4096)
  // makes rough: there the samples are whole steps apart.
  if (spalls || imperfections.has_roughness()) return {std::max(1, static_cast<int>(std::ceil(steps))), 1};
  const int divisions = kAdamsStepSampleDivisions;
  const int parts = std::max(divisions, static_cast<int>(std::ceil(steps * divisions)));
  const int common = std::gcd(parts, divisions);
  return {parts / common, divisions / common};
}

void BearingDynamics::linearize(const Vector5& q, const RollingPhase& phase) {
  Matrix5 stiffness, damping;
  model_.contact_force_and_stiffness(q, phase, &stiffness, &damping);
  etd_.q_lin = q;
  etd_.load_lin = load_line_.load;
  etd_.lin_accel.leftCols<5>() = -(inverse_mass_ * stiffness);
  etd_.lin_accel.rightCols<5>() = -(inverse_mass_ * damping);
  // The exponential of [hL I 0 0; 0 0 I 0; 0 0 0 I; 0 0 0 0] holds e^{hL} and
  // phi_1..phi_3(hL) in its first block row (phi_k(z) = (e^z - sum_{j<k} z^j/j!) / z^k);
  // of [hL I; 0 0], e^{hL} and phi_1(hL). In SI units L is far from normal (|M^-1 K| ~ 1e8
  // next to 1), which costs the scaling and squaring many squarings: it works on the
  // balanced D L D^-1, D = diag(w I, I) with w^2 = |M^-1 K|, and f(L) = D^-1 f(D L D^-1) D.
  const double w = std::max(1.0, std::sqrt(etd_.lin_accel.leftCols<5>().lpNorm<Eigen::Infinity>()));
  Matrix10 balanced = Matrix10::Zero();
  balanced.topRightCorner<5, 5>() = w * Matrix5::Identity();
  balanced.bottomLeftCorner<5, 5>() = etd_.lin_accel.leftCols<5>() / w;
  balanced.bottomRightCorner<5, 5>() = etd_.lin_accel.rightCols<5>();
  Eigen::Matrix<double, 10, 1> d;
  d << Vector5::Constant(w), Vector5::Ones();
  const auto unbalance = [&d](const Matrix10& f) -> Matrix10 {
    return d.cwiseInverse().asDiagonal() * f * d.asDiagonal();
  };
  // The Adams methods' ETDRK4 weights are for the step backward (their history).
  const double h = internal_step_s();
  const double h_etd = adams() ? -h : h;
  {
    Eigen::Matrix<double, 20, 20> x = Eigen::Matrix<double, 20, 20>::Zero();
    x.block<10, 10>(0, 0) = 0.5 * h_etd * balanced;
    x.block<10, 10>(0, 10).setIdentity();
    const Eigen::Matrix<double, 20, 20> e = x.exp();
    etd_.exp_half = unbalance(e.block<10, 10>(0, 0));
    etd_.phi_half = 0.5 * h_etd * unbalance(e.block<10, 10>(0, 10)).rightCols<5>();
  }
  if (adams()) {
    // phi_4 as well, from the same construction one block larger, W = [hL I 0 0 0; 0 0 I 0 0;
    // ...; 0], for every theta = j/m of a step that samples fall on (m = step_ratio_.samples):
    // the first block row of e^{theta W} is (e^{theta h L}, theta phi_1(theta h L), ...,
    // theta^4 phi_4(theta h L)), and that of e^{(j+1) W/m} is that of e^{j W/m} times e^{W/m}.
    // One exponential for all of them.
    using Matrix50 = Eigen::Matrix<double, 50, 50>;
    const int m = step_ratio_.samples;
    Matrix50 augmented = Matrix50::Zero();
    augmented.topLeftCorner<10, 10>() = (h / m) * balanced;
    for (int k = 0; k < 4; ++k) augmented.block<10, 10>(10 * k, 10 * (k + 1)) = Matrix10::Identity() / m;
    const Matrix50 part = augmented.exp();
    Eigen::Matrix<double, 10, 50> row = part.topRows<10>();
    std::vector<std::array<Matrix10, 5>> phi_at(m);  // at theta = (j + 1)/m: e, phi_1 .. phi_4
    for (int j = 0; j < m; ++j) {
      const double theta = static_cast<double>(j + 1) / m;
      double power = 1.0;
      for (int k = 0; k <= 4; ++k, power *= theta)
        phi_at[j][k] = unbalance(Matrix10(row.block<10, 10>(0, 10 * k))) / power;
      if (j + 1 < m) row = (row * part).eval();
    }
    const auto& [e_h, phi1, phi2, phi3, phi4] = phi_at[m - 1];
    // Weights of the backward differences nabla^j of the remainder: ETD-AB4 (polynomial
    // through the step's start and the 3 steps before) phi1, phi2, phi3 + phi2/2,
    // phi4 + phi3 + phi2/3; ETD-AM4 (through the step's end and the 3 before) phi1,
    // phi2 - phi1, phi3 - phi2/2, phi4 - phi2/6. Stored as weights of the remainders
    // themselves (nabla^j f_0 = sum_i (-1)^i C(j, i) f_i), right half, times h.
    const std::array<Matrix10, 4> ab = {Matrix10(phi1), Matrix10(phi2), Matrix10(phi3 + 0.5 * phi2),
                                        Matrix10(phi4 + phi3 + phi2 / 3.0)};
    const std::array<Matrix10, 4> am = {Matrix10(phi1), Matrix10(phi2 - phi1), Matrix10(phi3 - 0.5 * phi2),
                                        Matrix10(phi4 - phi2 / 6.0)};
    static constexpr double kBinomial[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
    for (int i = 0; i < 4; ++i) {
      Matrix10 predictor = Matrix10::Zero();
      for (int j = i; j < 4; ++j) predictor += kBinomial[j][i] * ab[j];
      const double sign = i % 2 ? -1.0 : 1.0;
      adams_weights_.step.block<10, 5>(0, 10 + 5 * i) = sign * h * predictor.rightCols<5>();
    }
    // The corrector's weight of r_{n+1}: sum of the AM4 weights (every nabla^j holds r_{n+1}
    // once). The corrector's cubic is the predictor's plus (nabla^4 r_{n+1}) times the cubic
    // that is 1 at t_{n+1} and 0 at t_n, t_{n-1}, t_{n-2}, so y_c = y_p + C0 nabla^4 r_{n+1}.
    adams_weights_.corrector = h * (am[0] + am[1] + am[2] + am[3]).rightCols<5>();
    // (y_p, A y_p) = [E P; A E  A P] (y, r, r_-1, r_-2, r_-3): the predicted end's linear
    // part comes with the predictor, one product per step instead of three.
    adams_weights_.step.topLeftCorner<10, 10>() = e_h;
    adams_weights_.step.bottomRows<5>() = etd_.lin_accel * adams_weights_.step.topRows<10>();
    // A sample at theta of a step: y(theta) = e^{theta h L} y_n + h int_0^theta
    // e^{(theta - s) h L} p(s) ds with p the corrector's cubic through the remainders at
    // s = 1, 0, -1, -2; for p = s^k the integral is k! theta^(k+1) phi_{k+1}(theta h L). Its
    // acceleration: A y(theta) + p(theta).
    Eigen::Matrix4d vandermonde;  // rows: the nodes 1, 0, -1, -2; columns: s^0 .. s^3
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 4; ++k) vandermonde(i, k) = std::pow(1.0 - i, k);
    const Eigen::Matrix4d monomial = vandermonde.inverse();  // (k, i): s^k coefficient of node i's basis
    for (int lead = 1; lead < step_ratio_.samples; ++lead) {
      const double theta = 1.0 - static_cast<double>(lead) / m;
      const std::array<Matrix10, 5>& f = phi_at[m - lead - 1];
      Eigen::Matrix<double, 15, 30>& sample_map = adams_weights_.sample_within_step[lead - 1];
      sample_map.setZero();
      sample_map.topLeftCorner<10, 10>() = f[0];
      for (int i = 0; i < 4; ++i) {
        Matrix10 weight = Matrix10::Zero();
        double basis = 0.0;
        double factorial = 1.0;
        for (int k = 0; k < 4; ++k) {
          if (k > 0) factorial *= k;
          weight += monomial(k, i) * factorial * std::pow(theta, k + 1) * f[k + 1];
          basis += monomial(k, i) * std::pow(theta, k);
        }
        sample_map.block<10, 5>(0, 10 + 5 * i) = h * weight.rightCols<5>();
        sample_map.block<5, 5>(10, 10 + 5 * i) = basis * Matrix5::Identity();
      }
      sample_map.bottomRows<5>() += etd_.lin_accel * sample_map.topRows<10>();
    }
  }
  // ETDRK4 (backward with the Adams methods, for their history): Cox-Matthews weights of the
  // four remainders (the remainder has no displacement part, so only the right half of each
  // matrix is kept).
  {
    Eigen::Matrix<double, 40, 40> x = Eigen::Matrix<double, 40, 40>::Zero();
    x.block<10, 10>(0, 0) = h_etd * balanced;
    for (int k = 0; k < 3; ++k) x.block<10, 10>(10 * k, 10 * (k + 1)).setIdentity();
    const Eigen::Matrix<double, 40, 40> e = x.exp();
    etd_.exp_full = unbalance(e.block<10, 10>(0, 0));
    const Matrix10 phi1 = unbalance(e.block<10, 10>(0, 10)), phi2 = unbalance(e.block<10, 10>(0, 20)),
                   phi3 = unbalance(e.block<10, 10>(0, 30));
    etd_.w1 = h_etd * (phi1 - 3.0 * phi2 + 4.0 * phi3).rightCols<5>();
    etd_.w2 = 2.0 * h_etd * (phi2 - 2.0 * phi3).rightCols<5>();
    etd_.w3 = h_etd * (4.0 * phi3 - phi2).rightCols<5>();
  }
  etd_.step_s = h;
  etd_.samples_since_linearization = 0;
  ++etd_.linearizations;
  adams_.started = false;  // the remainder is relative to the linearization
}

void BearingDynamics::update_substeps() {
  if (options_.substeps > 0) return;
  try {
    step_ratio_ = choose_step_ratio(model_, load_line_.load, options_.sample_rate_hz, options_.method);
    substeps_load_norm_ = load_line_.load.norm();
  } catch (const LoadNotCarriedError&) {
    // Keep the step: the caller learns of the load when it resets to the equilibrium.
  }
}

void BearingDynamics::set_load(const Vector5& load) { set_load(load, load); }

void BearingDynamics::set_load(const Vector5& load, const Vector5& load_at_sample_end) {
  if (!load.allFinite()) throw InvalidInputError("load is not finite");
  if (!load_at_sample_end.allFinite()) throw InvalidInputError("load at the sample's end is not finite");
  // The straight line through the mid value at the sample's middle and the end value at its end.
  const double half_sample_s = 0.5 / options_.sample_rate_hz;
  change_load(LoadLine{load, (load_at_sample_end - load) / half_sample_s, phase_.time_s + half_sample_s});
}

void BearingDynamics::change_load(const LoadLine& line) {
  const LoadLine before = load_line_;
  load_line_ = line;
  // The contact forces do not depend on the external load: the current acceleration moves
  // by the change over the mass, and stays the first RK4 stage of the next sample. The ball
  // split stays too (inputs may change every sample, e.g. a rotating unbalance): a ball that
  // the new load brings into contact is caught by the check after the sample.
  const Vector5 load_now = load_line_.at(phase_.time_s);
  current_.acceleration += inverse_mass_ * (load_now - load_in_current_acceleration_);
  load_in_current_acceleration_ = load_now;
  // So do the Adams method's remainders, each at its time: as if the new load had always
  // been there (it holds from the method's time, less than one step past the sample).
  if (adams_.started) {
    const double h = internal_step_s();
    for (int k = 0; k < 4; ++k) {
      const double t = phase_.time_s + adams_lead_s(adams_) - k * h;
      adams_.x.segment<5>(10 + 5 * k) += inverse_mass_ * (load_line_.at(t) - before.at(t));
    }
  }
  // The contact stiffness grows with the load (as F^(1/3)): check the step again when
  // the load has changed a lot since it was chosen.
  if (substeps_load_norm_ > 0.0 &&
      (load_line_.load.norm() > 1.5 * substeps_load_norm_ || load_line_.load.norm() < substeps_load_norm_ / 1.5)) {
    update_substeps();
    split_.samples_since = 0;
  }
}

void BearingDynamics::set_ring_speed(double ring_speed_rad_s) {
  if (!std::isfinite(ring_speed_rad_s)) throw InvalidInputError("ring speed is not finite");
  check_ring_speed(ring_speed_rad_s, model_.config().pitch_diameter_m, "ring speed");
  // Only the phases of the next samples change: acceleration and ball split stay.
  ring_speed_ = ring_speed_rad_s;
  update_cage_speed();
}

void BearingDynamics::update_slip_fluctuation() {
  // Ornstein-Uhlenbeck process: stationary standard deviation and correlation time as
  // configured, exact for any step.
  const ImperfectionSpec& spec = model_.config().imperfections;
  if (spec.cage_slip_variation <= 0.0) {
    slip_fluctuation_ = 0.0;
    return;
  }
  const double decay = std::exp(-1.0 / (options_.sample_rate_hz * spec.cage_slip_correlation_s));
  slip_fluctuation_ =
      decay * slip_fluctuation_ + spec.cage_slip_variation * std::sqrt(1.0 - decay * decay) * slip_noise_(slip_rng_);
}

void BearingDynamics::update_cage_speed() {
  model_.ring_speeds(ring_speed_, &inner_speed_, &outer_speed_);
  cage_speed_ = model_.cage_speed_rad_s(inner_speed_, outer_speed_);
  spin_speed_ = model_.ball_spin_speed_rad_s(inner_speed_, outer_speed_);
}

void BearingDynamics::set_model(BearingModel model) {
  if (model.config().flexible_ring.present)
    throw ConfigError(model.config().name + ": key 'flexible_ring': " + kFlexibleRingNotRigid);
  const Matrix5 inverse_mass = model.mass_matrix().inverse();
  model_ = std::move(model);
  set_inverse_mass(inverse_mass);
  displacement_limit_m_ = 0.25 * model_.config().ball_diameter_m + std::abs(model_.clearance_m());
  update_cage_speed();
  update_substeps();  // clearance and damping change the fastest mode
  etd_.step_s = 0.0;  // and the linearized contacts: again before the next sample
  acceleration_current_ = false;
  split_.samples_since = 0;  // the contact margin depends on the inputs
}

void BearingDynamics::add_spall(Spall spall) {
  spall.created_at_s = phase_.time_s;
  model_.add_spall(spall);
  acceleration_current_ = false;
  adams_.started = false;  // the remainder jumps: start again
  split_.samples_since = 0;
  update_substeps();  // the Adams step is shorter with a spall
}

void BearingDynamics::clear_spalls() {
  model_.clear_spalls();
  acceleration_current_ = false;
  adams_.started = false;
  split_.samples_since = 0;
  update_substeps();
}

void BearingDynamics::reset_to_equilibrium() {
  const Vector5 guess = current_.displacement;
  const bool have_guess = sample_index_ > 0 && guess.allFinite();
  const StaticSolution s = solve_static(model_, load_line_.load, phase_, {}, have_guess ? &guess : nullptr);
  current_.displacement = s.displacement;
  current_.velocity.setZero();
  current_.acceleration = acceleration(current_.displacement, current_.velocity, phase_, model_.balls());
  load_in_current_acceleration_ = load_line_.at(phase_.time_s);
  acceleration_current_ = true;
  split_.samples_since = 0;
  if (exponential()) linearize(s.displacement, phase_);
}

void BearingDynamics::set_inverse_mass(const Matrix5& inverse_mass) {
  inverse_mass_ = inverse_mass;
  inverse_mass_is_diagonal_ = inverse_mass.isDiagonal(0.0);
  inverse_mass_diagonal_ = inverse_mass.diagonal();
}

Vector5 BearingDynamics::divided_by_mass(const Vector5& force) const {
  // A bare ring's mass matrix is diagonal: 5 products instead of 25 (the same values: the
  // other 20 add exact zeros), in every force evaluation.
  if (inverse_mass_is_diagonal_) return inverse_mass_diagonal_.cwiseProduct(force);
  return inverse_mass_ * force;
}

Vector5 BearingDynamics::acceleration(const Vector5& q, const Vector5& q_dot, const RollingPhase& phase,
                                      const BallArrays& balls) const {
  return divided_by_mass(load_line_.at(phase.time_s) + model_.contact_force(q, q_dot, phase, balls));
}

Vector5 BearingDynamics::acceleration(const Vector5& q, const Vector5& q_dot, const RollingPhase& phase,
                                      const BallArrays& balls, const CageTrig& trig) const {
  return divided_by_mass(load_line_.at(phase.time_s) + model_.contact_force(q, q_dot, phase, balls, trig.c, trig.s));
}

double BearingDynamics::slipping_cage_speed() const {
  return cage_speed_ * (1.0 - model_.config().imperfections.cage_slip - slip_fluctuation_);
}

RollingPhase BearingDynamics::advanced(const RollingPhase& p, double dt) const {
  return p.advanced(slipping_cage_speed(), inner_speed_, outer_speed_, spin_speed_, dt);
}

double BearingDynamics::contact_margin_m(const Vector5& q, const Vector5& v, const Vector5& a) const {
  // How far any ball's deflection may move until the next split, doubled: ring motion,
  // the balls' travel in azimuth (|d delta / d phi| <= 2|t| + 3|theta| * lever arm) and
  // the imperfections passing under them. The ring motion is the smaller of the kinematic
  // bound and twice the amplitude of the slowest ring mode (the ring vibrates, it does not
  // run off). A ball that touches all the same is caught by the check after the sample.
  const double h = kSamplesPerBallSplit / options_.sample_rate_hz;
  const double lever = model_.max_lever_arm_m();
  const double speed = v.head<3>().norm() + v.tail<2>().norm() * lever;
  const double accel = a.head<3>().norm() + a.tail<2>().norm() * lever;
  const double kinematic = speed * h + accel * h * h;
  const double w = slowest_mode_rad_s_;
  const double oscillation = w > 0.0 ? 2.0 * std::hypot(accel / (w * w), speed / w) : kinematic;
  const double travel = std::abs(cage_speed_) * h * (2.0 * q.head<3>().norm() + 3.0 * q.tail<2>().norm() * lever);
  const double imperfections = model_.max_offset_change_m(inner_speed_, outer_speed_, h);
  return 2.0 * (std::min(kinematic, oscillation) + travel + imperfections) + 1e-10;
}

bool BearingDynamics::integrate_sample(Vector5& q, Vector5& v, RollingPhase& phase, const Vector5& a_start,
                                       const BallArrays& balls, AdamsState& adams_state, Vector5* a_end) const {
  if (adams()) {
    integrate_sample_adams(q, v, phase, a_start, balls, adams_state, a_end);
    return true;
  }
  if (exponential()) integrate_sample_exponential(q, v, phase, a_start, balls);
  else integrate_sample_rk4(q, v, phase, a_start, balls);
  return false;
}

BearingDynamics::CageTrig BearingDynamics::half_step_rotation() const {
  const double half_turn = slipping_cage_speed() * (0.5 * internal_step_s());
  if (half_turn != etd_.half_step_turn) {
    etd_.half_step_turn = half_turn;
    etd_.half_step_rotation = CageTrig{std::cos(half_turn), std::sin(half_turn)};
  }
  return etd_.half_step_rotation;
}

namespace {
// The cage's cos and sin carried through the stages by rotation (they differ from sincos of
// each stage's angle by a few ulp), instead of a sincos at every stage.
template <typename Trig>
Trig rotated(const Trig& t, const Trig& r) {
  return Trig{t.c * r.c - t.s * r.s, t.s * r.c + t.c * r.s};
}
}  // namespace

BearingDynamics::Vector10 BearingDynamics::etdrk4_step(const Vector10& y, const Vector5& r1, const RollingPhase& phase,
                                                       const CageTrig& trig, double h, const CageTrig& rotation,
                                                       const BallArrays& balls) const {
  // Cox-Matthews ETDRK4 on y = (q - q_lin, v): y' = L y + (0, r(y, t)). The products are
  // small and fixed-size: coefficient-based (lazyProduct), not Eigen's general
  // matrix-vector routine, which for these sizes costs more than the arithmetic.
  const auto remainder = [&](const Vector10& u, const RollingPhase& p, const CageTrig& t) {
    return Vector5(acceleration(etd_.q_lin + u.head<5>(), u.tail<5>(), p, balls, t) - etd_.lin_accel.lazyProduct(u));
  };
  const RollingPhase mid = advanced(phase, 0.5 * h), end = advanced(phase, h);
  const CageTrig trig_mid = rotated(trig, rotation), trig_end = rotated(trig_mid, rotation);
  const Vector10 e_half_y = etd_.exp_half.lazyProduct(y);
  const Vector10 y2 = e_half_y + etd_.phi_half.lazyProduct(r1);
  const Vector5 r2 = remainder(y2, mid, trig_mid);
  const Vector10 y3 = e_half_y + etd_.phi_half.lazyProduct(r2);
  const Vector5 r3 = remainder(y3, mid, trig_mid);
  const Vector10 y4 = etd_.exp_half.lazyProduct(y2) + etd_.phi_half.lazyProduct(Vector5(2.0 * r3 - r1));
  const Vector5 r4 = remainder(y4, end, trig_end);
  return etd_.exp_full.lazyProduct(y) + etd_.w1.lazyProduct(r1) + etd_.w2.lazyProduct(Vector5(r2 + r3)) +
         etd_.w3.lazyProduct(r4);
}

void BearingDynamics::integrate_sample_exponential(Vector5& q, Vector5& v, RollingPhase& phase, const Vector5& a_start,
                                                   const BallArrays& balls) const {
  const double h = internal_step_s();
  const CageTrig rot = half_step_rotation();
  CageTrig trig{std::cos(phase.cage), std::sin(phase.cage)};
  Vector10 y;
  y << q - etd_.q_lin, v;
  for (int i = 0; i < step_ratio_.steps; ++i) {
    const Vector5 r1 = (i == 0 ? a_start : acceleration(etd_.q_lin + y.head<5>(), y.tail<5>(), phase, balls, trig)) -
                       etd_.lin_accel.lazyProduct(y);
    y = etdrk4_step(y, r1, phase, trig, h, rot, balls);
    phase = advanced(phase, h);
    trig = rotated(rotated(trig, rot), rot);
  }
  etd_.sample_end_trig = trig;
  q = etd_.q_lin + y.head<5>();
  v = y.tail<5>();
}

void BearingDynamics::start_adams(AdamsState& adams, const RollingPhase& start, const BallArrays& balls) const {
  // The remainders one, two and three steps before, from ETDRK4 steps backward in time along
  // the trajectory through the start (its weights are stored for -h): the history the
  // extrapolation needs, as smooth as the motion, from 12 evaluations.
  const double h = internal_step_s();
  const CageTrig forward = half_step_rotation();
  const CageTrig backward{forward.c, -forward.s};
  Vector10 y = adams.x.head<10>();
  Vector5 r = adams.x.segment<5>(10);
  RollingPhase phase = start;
  CageTrig trig{std::cos(phase.cage), std::sin(phase.cage)};
  for (int k = 1; k <= 3; ++k) {
    y = etdrk4_step(y, r, phase, trig, -h, backward, balls);
    phase = advanced(phase, -h);
    trig = rotated(rotated(trig, backward), backward);
    r = acceleration(etd_.q_lin + y.head<5>(), y.tail<5>(), phase, balls, trig) - etd_.lin_accel.lazyProduct(y);
    adams.x.segment<5>(10 + 5 * k) = r;
  }
  adams.lead = 0;
  adams.started = true;
}

void BearingDynamics::integrate_sample_adams(Vector5& q, Vector5& v, RollingPhase& phase, const Vector5& a_start,
                                             const BallArrays& balls, AdamsState& adams, Vector5* a_end) const {
  // y = (q - q_lin, v) as in ETDRK4. Per step: the remainder r at the start (the previous
  // step's end evaluation), the predictor y_p = e^{hL} y + P0 r + P1 r_-1 + P2 r_-2 + P3 r_-3,
  // the remainder r_p at y_p and the step's end, the corrector
  // y_next = e^{hL} y + C0 r_p + C1 r + C2 r_-1 + C3 r_-2 = y_p + C0 nabla^4 r_p. The
  // predictor and the linear part of the predicted end, A y_p, are one product of
  // adams_weights_.step with x = (y, r, r_-1, r_-2, r_-3); a step moves the remainders down by one.
  // The method runs until it reaches or passes the sample's end (lead >= 0); a sample
  // within its last step comes from that step's start and the four remainders.
  const double h = internal_step_s();
  const CageTrig rot = half_step_rotation();
  const bool evaluate_end = options_.method == IntegrationMethod::ExponentialAdams;  // PECE, else PEC
  Eigen::Matrix<double, 30, 1>& x = adams.x;
  if (!adams.started) {
    x.head<5>() = q - etd_.q_lin;
    x.segment<5>(5) = v;
    x.segment<5>(10) = a_start - times(etd_.lin_accel, x.data());
    start_adams(adams, phase, balls);
    adams.trig_samples = 0;
  }
  RollingPhase method_phase = advanced(phase, adams_lead_s(adams));
  CageTrig trig = adams.trig;
  // The last sample's end, where the carried cos and sin belong, up to the rounding of the
  // phases (~1e-15 rad; the angle is wrapped once per sample, so also up to 2 pi); else the
  // phase was set anew or the cage's slip moved the method's time: a sincos.
  constexpr double kSameAngle = 1e-12;
  const double gap = std::abs(method_phase.cage - adams.trig_cage);
  if (adams.trig_samples > 0 && (gap < kSameAngle || std::abs(gap - kTwoPi) < kSameAngle)) {
    --adams.trig_samples;
  } else {
    trig = CageTrig{std::cos(method_phase.cage), std::sin(method_phase.cage)};
    adams.trig_samples = kSamplesPerCageTrig - 1;
  }
  adams.lead -= step_ratio_.steps;
  while (adams.lead < 0) {
    const RollingPhase end = advanced(method_phase, h);
    const CageTrig trig_end = rotated(rotated(trig, rot), rot);  // the same rotations as ETDRK4's stages
    const Eigen::Matrix<double, 15, 1> predicted = times(adams_weights_.step, x.data());  // (y_p, A y_p)
    const Vector5 r_p = acceleration(etd_.q_lin + predicted.head<5>(), predicted.segment<5>(5), end, balls, trig_end) -
                        predicted.tail<5>();
    const Vector5 fourth_difference =
        r_p - 4.0 * x.segment<5>(10) + 6.0 * x.segment<5>(15) - 4.0 * x.segment<5>(20) + x.segment<5>(25);
    adams.y_last_start = x.head<10>();
    // y_c = y_p + C nabla^4 r_p straight into x (y_p is the head of `predicted`).
    detail::multiply_add<10, 5>(adams_weights_.corrector.data(), fourth_difference.data(), predicted.data(), x.data());
    for (int i = 29; i >= 15; --i) x[i] = x[i - 5];  // the history one place down
    // The next step's r: the predicted end's (PEC) or the corrected end's (PECE).
    x.segment<5>(10) = evaluate_end
                           ? Vector5(acceleration(etd_.q_lin + x.head<5>(), x.segment<5>(5), end, balls, trig_end) -
                                     times(etd_.lin_accel, x.data()))
                           : r_p;
    method_phase = end;
    trig = trig_end;
    adams.lead += step_ratio_.samples;
  }
  adams.trig = trig;
  adams.trig_cage = method_phase.cage;
  phase = advanced(phase, 1.0 / options_.sample_rate_hz);  // as without steps: the same for any step
  if (adams.lead == 0) {
    // PEC: a_p + A (y_c - y_p) = r_p + A y_c (its remainder is then the predicted one again).
    q = etd_.q_lin + x.head<5>();
    v = x.segment<5>(5);
    *a_end = x.segment<5>(10) + times(etd_.lin_accel, x.data());
    return;
  }
  Eigen::Matrix<double, 30, 1> z;
  z.head<10>() = adams.y_last_start;
  z.tail<20>() = x.tail<20>();
  const Eigen::Matrix<double, 15, 1> sample = times(adams_weights_.sample_within_step[adams.lead - 1], z.data());
  q = etd_.q_lin + sample.head<5>();
  v = sample.segment<5>(5);
  *a_end = sample.tail<5>();
}

void BearingDynamics::integrate_sample_rk4(Vector5& q, Vector5& v, RollingPhase& phase, const Vector5& a_start,
                                           const BallArrays& balls) const {
  const double h = internal_step_s();
  for (int i = 0; i < step_ratio_.steps; ++i) {
    const RollingPhase mid = advanced(phase, 0.5 * h), end = advanced(phase, h);
    const Vector5 a1 = i == 0 ? a_start : acceleration(q, v, phase, balls);
    const Vector5 v2 = v + 0.5 * h * a1, q2 = q + 0.5 * h * v;
    const Vector5 a2 = acceleration(q2, v2, mid, balls);
    const Vector5 v3 = v + 0.5 * h * a2, q3 = q + 0.5 * h * v2;
    const Vector5 a3 = acceleration(q3, v3, mid, balls);
    const Vector5 v4 = v + h * a3, q4 = q + h * v3;
    const Vector5 a4 = acceleration(q4, v4, end, balls);
    q += h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4);
    v += h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    phase = end;
  }
}

DynamicSample BearingDynamics::step() {
  const Vector5& q0 = current_.displacement;
  const Vector5& v0 = current_.velocity;
  // The last sample's acceleration is the first stage, unless the model changed since (a
  // new load has already moved it).
  const Vector5 a_start = acceleration_current_ ? current_.acceleration : acceleration(q0, v0, phase_, model_.balls());
  // Only the balls that can touch during the next kSamplesPerBallSplit samples take part
  // in the integration; the others carry no load now, so a_start holds for either set.
  if (split_.samples_since == 0) {
    const double margin =
        options_.skip_clear_balls ? contact_margin_m(q0, v0, a_start) : std::numeric_limits<double>::infinity();
    split_.clear_max_deflection_m = model_.split_by_deflection(q0, phase_, margin, &split_.active, &split_.clear);
    split_.displacement = q0;
    split_.travel = {};
  }
  split_.samples_since = (split_.samples_since + 1) % kSamplesPerBallSplit;
  // A moving load is followed at most every kSamplesPerLinearization samples, so that an
  // input changing every sample cannot make every sample pay for a linearization.
  ++etd_.samples_since_linearization;
  if (exponential() && (etd_.step_s != internal_step_s() ||
                        (etd_.samples_since_linearization >= kSamplesPerLinearization &&
                         (load_line_.load - etd_.load_lin).norm() > kRelinearizeLoadChange * etd_.load_lin.norm()))) {
    // About the equilibrium of the current load (the ring vibrates about it), or about the
    // current displacement when there is none.
    Vector5 q_eq = q0;
    try {
      q_eq = solve_static(model_, load_line_.load, phase_, {}, &q0).displacement;
    } catch (const LoadNotCarriedError&) {
    }
    linearize(q_eq, phase_);
  }
  const BallArrays* balls = &split_.active;
  Vector5 q = q0, v = v0;
  RollingPhase phase = phase_;
  AdamsState adams_state = adams_;  // kept only when the sample is
  Vector5 a_end = Vector5::Zero();
  bool end_known = integrate_sample(q, v, phase, a_start, *balls, adams_state, &a_end);
  // The skipped balls are checked ball by ball only when the bound of clear_deflection_bound_m
  // does not already show them all clear (it almost always does: the split's margin is twice
  // the bound's growth over kSamplesPerBallSplit samples).
  split_.travel[0] += std::abs(phase.cage - phase_.cage);
  split_.travel[1] += std::abs((phase.cage - phase_.cage) - (phase.outer_ring - phase_.outer_ring));
  split_.travel[2] += std::abs((phase.cage - phase_.cage) - (phase.inner_ring - phase_.inner_ring));
  split_.travel[3] += std::abs(phase.ball_spin - phase_.ball_spin);
  if (split_.clear.size() > 0 && q.allFinite() && clear_deflection_bound_m(q, split_.travel) > 0.0 &&
      model_.max_deflection(q, phase, split_.clear) > 0.0) {
    // A ball outside the margin came into contact: redo the sample with every ball.
    ++split_.full_sample_retries;
    split_.samples_since = 0;
    balls = &model_.balls();
    q = q0;
    v = v0;
    phase = phase_;
    adams_state = adams_;
    end_known = integrate_sample(q, v, phase, a_start, *balls, adams_state, &a_end);
  }
  // The exponential integrators left cos and sin of the end's cage angle.
  const DynamicSample sample = commit_sample(q, v,
                                             end_known       ? a_end
                                             : exponential() ? acceleration(q, v, phase, *balls, etd_.sample_end_trig)
                                                             : acceleration(q, v, phase, *balls),
                                             phase);
  if (adams()) adams_ = adams_state;
  // A load line is for one sample: from its end on the load holds the end value.
  if (!load_line_.rate.isZero()) change_load(LoadLine{load_line_.at(phase_.time_s), Vector5::Zero(), phase_.time_s});
  return sample;
}

double BearingDynamics::clear_deflection_bound_m(const Vector5& q, const std::array<double, 4>& travel) const {
  // A ball's deflection is |v| - A - g0 + offset with v = A e0(phi) - s u, u = t + theta x p(phi)
  // the displacement of its groove centre p (|p| <= lever arm, theta = (theta_x, theta_y, 0)).
  // From the split (q0, phi0) to now (q, phi0 + dphi), spalls left out (they only remove
  // deflection): a rotation by dphi moves |v| by at most |dphi| (|t_xy| + |theta| lever)
  // (rotate v back: only u's rotation remains, by at most the arc), the change of q at
  // fixed phi by at most |dt| + |dtheta| lever, and the offsets by the imperfections' bound
  // for the races' and balls' travel. Plus a rounding allowance.
  const double lever = model_.max_lever_arm_m();
  const Vector5 dq = q - split_.displacement;
  const double rotation = travel[0] * (q.head<2>().norm() + q.tail<2>().norm() * lever);
  const double displacement = dq.head<3>().norm() + dq.tail<2>().norm() * lever;
  const double offsets = model_.imperfections().max_offset_change_m(travel[1], travel[2], travel[3]);
  const double rounding = 1e-9 * model_.groove_centre_distance_m() + 1e-15;
  return split_.clear_max_deflection_m + rotation + displacement + offsets + rounding;
}

DynamicSample BearingDynamics::commit_sample(const Vector5& q, const Vector5& v, const Vector5& a,
                                             const RollingPhase& phase) {
  const double translation = q.head<3>().norm();
  const double tilt = q.tail<2>().norm() * model_.pitch_radius_m();
  // One sum for the fifteen finiteness tests: a NaN or an infinity anywhere makes it NaN or
  // infinite (and so would finite values near 1e308, far past the displacement limit).
  if (!std::isfinite(q.sum() + v.sum() + a.sum()) || translation > displacement_limit_m_ ||
      tilt > displacement_limit_m_) {
    std::ostringstream os;
    os << "dynamic state diverged at t=" << current_.time_s << " s (displacement " << translation * 1e6
       << " um, tilt at the pitch radius " << tilt * 1e6 << " um)";
    throw DivergenceError(os.str());
  }
  ++sample_index_;
  // Angles wrapped once per sample keep their precision over long runs.
  // std::remainder(x, 2 pi) without its cost for the usual |x| <= 3 pi (an angle wrapped last
  // sample plus one sample's advance): n = round-half-even(x / 2 pi) is -1, 0 or 1, the
  // comparison with pi (= 2 pi / 2 exactly) picks it exactly and x -+ 2 pi is the one
  // rounding std::remainder makes, so the result is bit for bit the same.
  const auto wrap = [](double x) {
    if (!(std::abs(x) <= 3.0 * kPi)) return std::remainder(x, kTwoPi);
    return x > kPi ? x - kTwoPi : x < -kPi ? x + kTwoPi : x;
  };
  const double cage = wrap(phase.cage);
  // The turns the wrap took off the cage, counted (the balls' passages; a whole multiple of
  // 2 pi up to the rounding of x -+ 2 pi).
  const std::int64_t turns = phase.cage_turns + std::llround((phase.cage - cage) / kTwoPi);
  phase_ = RollingPhase{cage,
                        wrap(phase.inner_ring),
                        wrap(phase.outer_ring),
                        wrap(phase.ball_spin),
                        static_cast<double>(sample_index_) / options_.sample_rate_hz,
                        turns};
  current_.time_s = phase_.time_s;
  update_slip_fluctuation();
  current_.cage_angle_rad = phase_.cage;
  current_.ring_angle_rad =
      model_.config().rotating_ring == RotatingRing::Outer ? phase_.outer_ring : phase_.inner_ring;
  current_.displacement = q;
  current_.velocity = v;
  current_.acceleration = a;  // with the load at its time
  load_in_current_acceleration_ = load_line_.at(phase_.time_s);
  acceleration_current_ = true;
  return current_;
}

}  // namespace bearing_sim
