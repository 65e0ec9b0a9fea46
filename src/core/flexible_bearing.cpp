#include "bearing_sim/core/flexible_bearing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "flexible_kernel.hpp"

namespace bearing_sim {

FlexibleBearing::FlexibleBearing(BearingModel model) : model_(std::move(model)) {
  const FlexibleRingSpec& spec = model_.config().flexible_ring;
  if (!spec.present) throw InvalidInputError(model_.config().name + ": the bearing file has no flexible_ring block");
  modes_ = ring_modes(spec);
  for (const RingMode& m : modes_) {
    max_order_ = std::max(max_order_, m.order);
    mode_orders_.push_back(m.order);
    mode_radial_.push_back(m.direction == RingModeDirection::Radial ? 1 : 0);
  }
  const std::vector<double>& beta = model_.balls().base_azimuth;
  const int nb = static_cast<int>(beta.size());
  stride_ = (nb + 63) / 64 * 64;  // whole vectors of up to 64 lanes (4096-bit SVE) read past nb
  base_cos_n_.assign(static_cast<std::size_t>(max_order_ + 1) * stride_, 0.0);
  base_sin_n_.assign(static_cast<std::size_t>(max_order_ + 1) * stride_, 0.0);
  for (int k = 0; k <= max_order_; ++k)
    for (int b = 0; b < nb; ++b) {
      base_cos_n_[static_cast<std::size_t>(k) * stride_ + b] = std::cos(k * beta[b]);
      base_sin_n_[static_cast<std::size_t>(k) * stride_ + b] = std::sin(k * beta[b]);
    }
  radial_mode_of_order_.assign(static_cast<std::size_t>(max_order_ + 1), -1);
  axial_mode_of_order_.assign(static_cast<std::size_t>(max_order_ + 1), -1);
  for (std::size_t i = 0; i < modes_.size(); ++i) {
    int& slot = (mode_radial_[i] ? radial_mode_of_order_ : axial_mode_of_order_)[static_cast<std::size_t>(mode_orders_[i])];
    if (slot >= 0) throw std::logic_error("flexible bearing: two ring modes of one order and direction");
    slot = static_cast<int>(i);
  }
  // Rows in phase without spacing scatter share their azimuths exactly (the CT bearing's two
  // rows): the ring's displacement there is the same for both.
  const int rows = model_.config().rows, per_row = model_.config().balls_per_row;
  bool shared = rows == 2 && rows * per_row == nb;
  for (int j = 0; shared && j < per_row; ++j) shared = beta[static_cast<std::size_t>(per_row + j)] == beta[j];
  rows_sharing_ = shared ? rows : 1;
  azimuths_ = nb / rows_sharing_;
  row_stride_ = (azimuths_ + 63) / 64 * 64;
  groove_radius_ = model_.groove_centre_radius_m();
  cos_a0_ = std::cos(model_.config().contact_angle_rad);
}

Eigen::MatrixXd FlexibleBearing::mass_matrix() const {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(size(), size());
  m.topLeftCorner<5, 5>() = model_.mass_matrix();
  for (std::size_t i = 0; i < modes_.size(); ++i)
    m(5 + 2 * i, 5 + 2 * i) = m(6 + 2 * i, 6 + 2 * i) = modes_[i].modal_mass_kg;
  return m;
}

Eigen::VectorXd FlexibleBearing::ring_stiffness() const {
  Eigen::VectorXd k = Eigen::VectorXd::Zero(size());
  for (std::size_t i = 0; i < modes_.size(); ++i) k[5 + 2 * i] = k[6 + 2 * i] = modes_[i].stiffness_N_per_m();
  return k;
}

Eigen::VectorXd FlexibleBearing::ring_damping() const {
  Eigen::VectorXd c = Eigen::VectorXd::Zero(size());
  for (std::size_t i = 0; i < modes_.size(); ++i) c[5 + 2 * i] = c[6 + 2 * i] = modes_[i].modal_damping_Ns_per_m;
  return c;
}

double FlexibleBearing::ring_angle_rad(const RollingPhase& phase) const {
  return model_.config().rotating_ring == RotatingRing::Outer ? phase.outer_ring : phase.inner_ring;
}

double FlexibleBearing::displacement_m(const Eigen::VectorXd& x, double theta, RingModeDirection direction) const {
  double w = 0.0;
  for (std::size_t i = 0; i < modes_.size(); ++i)
    if (modes_[i].direction == direction)
      w += x[5 + 2 * i] * std::cos(modes_[i].order * theta) + x[6 + 2 * i] * std::sin(modes_[i].order * theta);
  return w;
}

double FlexibleBearing::radial_displacement_m(const Eigen::VectorXd& x, double theta) const {
  return displacement_m(x, theta, RingModeDirection::Radial);
}

double FlexibleBearing::axial_displacement_m(const Eigen::VectorXd& x, double theta) const {
  return displacement_m(x, theta, RingModeDirection::Axial);
}

FlexibleBearing::Deformation FlexibleBearing::deformation(const Eigen::VectorXd& x, const RollingPhase& phase,
                                                          int points) const {
  if (points < 1) throw InvalidInputError("flexible ring deformation: points must be at least 1");
  Deformation d;
  d.ring_angle_rad = ring_angle_rad(phase);
  d.azimuth_rad.resize(points);
  d.radial_m.resize(points);
  d.axial_m.resize(points);
  for (int i = 0; i < points; ++i) {
    const double phi = 2.0 * kPi * i / points;
    d.azimuth_rad[i] = phi;
    d.radial_m[i] = radial_displacement_m(x, phi - d.ring_angle_rad);
    d.axial_m[i] = axial_displacement_m(x, phi - d.ring_angle_rad);
  }
  return d;
}

// One pass over the balls: the kinematics of docs/model.md section 5 with the ring's modal
// displacement added to each groove centre's, u = G x with G = [rigid map | e_r cos n theta,
// e_r sin n theta (radial modes) | e_z cos n theta, e_z sin n theta (axial modes)].
template <bool kDamped, bool kStiffness>
void FlexibleBearing::contact_loop(const Eigen::VectorXd& x, const Eigen::VectorXd* x_dot, const RollingPhase& phase,
                                   Eigen::VectorXd* force, Eigen::MatrixXd* stiffness,
                                   std::vector<BallState>* states) const {
  const int n = size();
  if (x.size() != n || (x_dot && x_dot->size() != n))
    throw InvalidInputError("flexible bearing: expected " + std::to_string(n) + " coordinates");
  const BallArrays& balls = model_.balls();
  const int nb = static_cast<int>(balls.size());
  thread_local std::vector<double> offsets, cos_n, sin_n;
  offsets = balls.deflection_offset;
  model_.imperfections().add_offsets(phase, offsets.data());
  cos_n.assign(max_order_ + 1, 1.0);
  sin_n.assign(max_order_ + 1, 0.0);

  const double cc = std::cos(phase.cage), sc = std::sin(phase.cage);
  const double psi = ring_angle_rad(phase), cpsi = std::cos(psi), spsi = std::sin(psi);
  const double A = model_.groove_centre_distance_m(), g0 = model_.clearance_m(), sg = model_.moving_sign();
  const double kn = model_.contact_stiffness(), cn = model_.config().contact_damping_Ns_per_m;
  const double rho = groove_radius_, aca = A * cos_a0_;
  const double* q = x.data();
  const double* qd = x_dot ? x_dot->data() : nullptr;
  const int modes = static_cast<int>(modes_.size());
  if (force) force->setZero(n);
  if (kStiffness) stiffness->setZero(n, n);
  if (states) states->assign(nb, BallState{});
  Eigen::Matrix<double, 3, Eigen::Dynamic> G(3, kStiffness ? n : 0);
  if (kStiffness) G.setZero();

  for (int b = 0; b < nb; ++b) {
    const double cphi = cc * balls.cos_base[b] - sc * balls.sin_base[b];
    const double sphi = sc * balls.cos_base[b] + cc * balls.sin_base[b];
    // The ball's place on the ring: theta = phi - psi, and its multiples by recurrence.
    cos_n[1] = cphi * cpsi + sphi * spsi;
    sin_n[1] = sphi * cpsi - cphi * spsi;
    for (int k = 2; k <= max_order_; ++k) {
      cos_n[k] = cos_n[k - 1] * cos_n[1] - sin_n[k - 1] * sin_n[1];
      sin_n[k] = sin_n[k - 1] * cos_n[1] + cos_n[k - 1] * sin_n[1];
    }
    double w = 0.0, uz_ring = 0.0, w_dot = 0.0, uz_ring_dot = 0.0;
    for (int i = 0; i < modes; ++i) {
      const int o = modes_[i].order;
      const double d = q[5 + 2 * i] * cos_n[o] + q[6 + 2 * i] * sin_n[o];
      const double d_dot = kDamped ? qd[5 + 2 * i] * cos_n[o] + qd[6 + 2 * i] * sin_n[o] : 0.0;
      if (modes_[i].direction == RingModeDirection::Radial) {
        w += d;
        w_dot += d_dot;
      } else {
        uz_ring += d;
        uz_ring_dot += d_dot;
      }
    }
    const double px = rho * cphi, py = rho * sphi, pz = balls.groove_centre_z[b], nz = balls.normal_z[b];
    const double ux = q[0] + q[4] * pz + w * cphi;
    const double uy = q[1] - q[3] * pz + w * sphi;
    const double uz = q[2] + q[3] * py - q[4] * px + uz_ring;
    const double vx = aca * cphi - sg * ux, vy = aca * sphi - sg * uy, vz = A * nz - sg * uz;
    const double norm = std::sqrt(vx * vx + vy * vy + vz * vz);
    const double deflection = norm - A - g0 + offsets[b];
    double load = deflection > 0.0 ? kn * deflection * std::sqrt(deflection) : 0.0;
    if (states) {
      BallState& s = (*states)[b];
      const double phi = phase.cage + balls.base_azimuth[b];
      s.row = balls.row[b];
      s.index_in_row = b % model_.balls_per_row();
      s.azimuth_rad = std::remainder(phi, 2.0 * kPi);
      s.deflection_m = deflection;
      s.load_N = load;
      s.contact_angle_rad = std::atan2(std::abs(vz), vx * cphi + vy * sphi);
      s.normal = Eigen::Vector3d(vx, vy, vz) / norm;
      s.pressure_Pa =
          std::max(model_.inner_contact().max_pressure_Pa(load), model_.outer_contact().max_pressure_Pa(load));
    }
    if (!(deflection > 0.0) || !force) continue;
    if (kDamped) {
      // d(delta)/dt = -sign e . du/dt; the contact cannot pull.
      const double udx = qd[0] + qd[4] * pz + w_dot * cphi;
      const double udy = qd[1] - qd[3] * pz + w_dot * sphi;
      const double udz = qd[2] + qd[3] * py - qd[4] * px + uz_ring_dot;
      load -= cn * sg * (vx * udx + vy * udy + vz * udz) / norm;
      if (!(load > 0.0)) continue;
    }
    const double s = sg * load / norm;  // force on the moving ring: sign Q e
    const double fx = s * vx, fy = s * vy, fz = s * vz;
    double* f = force->data();
    f[0] += fx;
    f[1] += fy;
    f[2] += fz;
    f[3] += py * fz - pz * fy;
    f[4] += pz * fx - px * fz;
    const double fr = fx * cphi + fy * sphi;
    for (int i = 0; i < modes; ++i) {
      const int o = modes_[i].order;
      const double g = modes_[i].direction == RingModeDirection::Radial ? fr : fz;
      f[5 + 2 * i] += g * cos_n[o];
      f[6 + 2 * i] += g * sin_n[o];
    }
    if (kStiffness) {
      G(0, 0) = 1.0;
      G(0, 4) = pz;
      G(1, 1) = 1.0;
      G(1, 3) = -pz;
      G(2, 2) = 1.0;
      G(2, 3) = py;
      G(2, 4) = -px;
      for (int i = 0; i < modes; ++i) {
        const int o = modes_[i].order;
        const bool radial = modes_[i].direction == RingModeDirection::Radial;
        for (int c = 0; c < 2; ++c) {
          const double shape = c == 0 ? cos_n[o] : sin_n[o];
          G(0, 5 + 2 * i + c) = radial ? shape * cphi : 0.0;
          G(1, 5 + 2 * i + c) = radial ? shape * sphi : 0.0;
          G(2, 5 + 2 * i + c) = radial ? 0.0 : shape;
        }
      }
      const Eigen::Vector3d e(vx / norm, vy / norm, vz / norm);
      const Eigen::Matrix3d ee = e * e.transpose();
      const double load_slope = 1.5 * kn * std::sqrt(deflection);
      const Eigen::Matrix3d kc = load_slope * ee + (load / norm) * (Eigen::Matrix3d::Identity() - ee);
      stiffness->noalias() += G.transpose() * (kc * G);
    }
  }
}

Eigen::VectorXd FlexibleBearing::contact_force(const Eigen::VectorXd& x, const Eigen::VectorXd& x_dot,
                                               const RollingPhase& phase) const {
  Eigen::VectorXd f;
  contact_loop<true, false>(x, &x_dot, phase, &f, nullptr, nullptr);
  return f;
}

Eigen::VectorXd FlexibleBearing::contact_force_and_stiffness(const Eigen::VectorXd& x, const RollingPhase& phase,
                                                             Eigen::MatrixXd* stiffness) const {
  Eigen::VectorXd f;
  if (stiffness) contact_loop<false, true>(x, nullptr, phase, &f, stiffness, nullptr);
  else contact_loop<false, false>(x, nullptr, phase, &f, nullptr, nullptr);
  return f;
}

Eigen::VectorXd FlexibleBearing::contact_force_load_frame(const Eigen::VectorXd& z, const Eigen::VectorXd& rates,
                                                          const RollingPhase& phase, bool simd,
                                                          std::vector<double>* work) const {
  const int n = size();
  if (z.size() != n || rates.size() != n)
    throw InvalidInputError("flexible bearing: expected " + std::to_string(n) + " coordinates");
  const BallArrays& balls = model_.balls();
  const int nb = static_cast<int>(balls.size()), modes = static_cast<int>(modes_.size());
  std::vector<double> own;
  std::vector<double>& scratch = work ? *work : own;
  scratch.resize(static_cast<std::size_t>(nb + detail::flexible_kernel_work_size(rows_sharing_, row_stride_, modes, max_order_)));
  double* const offsets = scratch.data();
  std::copy(balls.deflection_offset.begin(), balls.deflection_offset.end(), offsets);
  model_.imperfections().add_offsets(phase, offsets);
  detail::FlexibleKernelInput in{};
  in.cos_cage = std::cos(phase.cage);
  in.sin_cage = std::sin(phase.cage);
  in.groove_centre_radius = groove_radius_;
  in.cos_a0 = cos_a0_;
  in.groove_centre_distance = model_.groove_centre_distance_m();
  in.clearance = model_.clearance_m();
  in.sign = model_.moving_sign();
  in.stiffness = model_.contact_stiffness();
  in.damping = model_.config().contact_damping_Ns_per_m;
  in.q = z.data();
  in.q_dot = rates.data();
  in.modes = static_cast<int>(modes_.size());
  in.max_order = max_order_;
  in.order = mode_orders_.data();
  in.radial = mode_radial_.data();
  in.radial_mode_of_order = radial_mode_of_order_.data();
  in.axial_mode_of_order = axial_mode_of_order_.data();
  in.mode_position = z.data() + 5;
  in.mode_rate = rates.data() + 5;
  in.base_cos_n = base_cos_n_.data();
  in.base_sin_n = base_sin_n_.data();
  in.stride = stride_;
  in.cos_base = balls.cos_base.data();
  in.sin_base = balls.sin_base.data();
  in.groove_centre_z = balls.groove_centre_z.data();
  in.normal_z = balls.normal_z.data();
  in.offset = offsets;
  in.n = nb;
  in.rows_sharing = rows_sharing_;
  in.azimuths = azimuths_;
  in.row_stride = row_stride_;
  in.work = offsets + nb;
  Eigen::VectorXd f(n);
  if (simd) detail::flexible_contact_simd(in, f.data());
  else detail::flexible_contact_scalar(in, f.data());
  return f;
}

std::vector<BallState> FlexibleBearing::ball_states(const Eigen::VectorXd& x, const RollingPhase& phase) const {
  std::vector<BallState> states;
  contact_loop<false, false>(x, nullptr, phase, nullptr, nullptr, &states);
  return states;
}

namespace {

// Residual with the moments divided by the pitch radius (as solve_static), N.
double scaled_norm(const Eigen::VectorXd& r, double pitch_radius) {
  Eigen::VectorXd s = r;
  s.segment<2>(3) /= pitch_radius;
  return s.norm();
}

}  // namespace

FlexibleStaticSolution solve_flexible_static(const FlexibleBearing& bearing, const Vector5& load,
                                             const RollingPhase& phase) {
  const BearingModel& model = bearing.model();
  // The rigid ring's equilibrium: the start, and the load check (it throws when not carried).
  const StaticSolution rigid = solve_static(model, load, phase);
  const int n = bearing.size();
  const Eigen::VectorXd k_ring = bearing.ring_stiffness();
  Eigen::VectorXd external = Eigen::VectorXd::Zero(n);
  external.head<5>() = load;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  x.head<5>() = rigid.displacement;
  const double rp = model.pitch_radius_m();
  const double tolerance = 1e-9 + 1e-11 * scaled_norm(external, rp);

  const auto residual = [&](const Eigen::VectorXd& at, Eigen::MatrixXd* k) {
    return Eigen::VectorXd(external + bearing.contact_force_and_stiffness(at, phase, k) - k_ring.cwiseProduct(at));
  };
  Eigen::MatrixXd k_contact;
  Eigen::VectorXd r = residual(x, &k_contact);
  double r_norm = scaled_norm(r, rp);
  int iterations = 0;
  constexpr int kMaxIterations = 100;
  while (r_norm > tolerance) {
    if (++iterations > kMaxIterations || !std::isfinite(r_norm))
      throw LoadNotCarriedError(model.config().name + ": no equilibrium of the flexible ring found (residual " +
                                std::to_string(r_norm) + " N)");
    Eigen::MatrixXd jacobian = k_contact;
    jacobian.diagonal() += k_ring;
    const Eigen::VectorXd dx = jacobian.fullPivLu().solve(r);
    // Halve the step until the residual falls (the contacts switch on and off).
    double t = 1.0;
    Eigen::VectorXd trial, r_trial;
    double trial_norm = std::numeric_limits<double>::infinity();
    for (int halvings = 0; halvings < 40; ++halvings, t *= 0.5) {
      trial = x + t * dx;
      r_trial = residual(trial, nullptr);
      trial_norm = scaled_norm(r_trial, rp);
      if (trial_norm < (1.0 - 1e-4 * t) * r_norm) break;
    }
    if (!(trial_norm < r_norm)) {
      // No descent left: converged as far as rounding allows, or stuck.
      if (r_norm < 1e3 * tolerance) break;
      throw LoadNotCarriedError(model.config().name + ": the flexible ring's equilibrium does not converge");
    }
    x = trial;
    r = residual(x, &k_contact);
    r_norm = scaled_norm(r, rp);
  }

  FlexibleStaticSolution sol;
  sol.coordinates = x;
  sol.stiffness = k_contact;
  sol.stiffness.diagonal() += k_ring;
  StaticSolution& s = sol.rigid_coordinates;
  s.displacement = x.head<5>();
  // The modes eliminated: K_qq - K_qe K_ee^-1 K_eq.
  const int m = n - 5;
  s.stiffness = sol.stiffness.topLeftCorner<5, 5>();
  if (m > 0) {
    const Eigen::MatrixXd k_ee = sol.stiffness.bottomRightCorner(m, m);
    s.stiffness -= sol.stiffness.topRightCorner(5, m) * k_ee.ldlt().solve(sol.stiffness.bottomLeftCorner(m, 5));
  }
  s.balls = bearing.ball_states(x, phase);
  for (const BallState& b : s.balls) {
    s.max_ball_load_N = std::max(s.max_ball_load_N, b.load_N);
    s.max_contact_pressure_Pa = std::max(s.max_contact_pressure_Pa, b.pressure_Pa);
  }
  s.residual_norm = r_norm;
  s.iterations = rigid.iterations + iterations;
  return sol;
}

Eigen::VectorXd flexible_natural_frequencies_rad_s(const FlexibleBearing& bearing,
                                                   const FlexibleStaticSolution& solution) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(
      0.5 * (solution.stiffness + solution.stiffness.transpose()), bearing.mass_matrix());
  if (eig.info() != Eigen::Success) throw InvalidInputError("flexible ring: the modal problem did not solve");
  return eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
}

}  // namespace bearing_sim
