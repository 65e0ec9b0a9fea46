#include "bearing_sim/core/flexible_adams.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "bearing_sim/core/errors.hpp"
#include "phi_functions.hpp"
#include "small_products.hpp"

namespace bearing_sim {

namespace {

// Weights of the remainders f_0 (newest), f_-1, ... from those of the backward differences
// nabla^j f_0 = sum_i (-1)^i C(j, i) f_i, j < order: side by side, [W0 W1 W2 W3].
Eigen::MatrixXd remainder_weights(const std::array<Eigen::MatrixXd, 4>& of_differences, int order) {
  static constexpr int kBinomial[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
  const Eigen::Index rows = of_differences[0].rows(), cols = of_differences[0].cols();
  Eigen::MatrixXd w = Eigen::MatrixXd::Zero(rows, 4 * cols);
  for (int i = 0; i < 4; ++i)
    for (int j = i; j < order; ++j)
      w.middleCols(i * cols, cols) += ((i % 2) ? -1.0 : 1.0) * kBinomial[j][i] * of_differences[j];
  return w;
}

}  // namespace

FlexibleAdams::FlexibleAdams(const Acceleration& accel, const Eigen::VectorXd& z_lin, const Eigen::VectorXd& z_scale,
                             const Eigen::VectorXd& v_scale, const Eigen::VectorXd& z0, const Eigen::VectorXd& v0,
                             double step_s, double t0)
    : n_(static_cast<int>(z_lin.size())), h_(step_s), t0_(t0), t_(t0), z_lin_(z_lin), z_(z0), v_(v0) {
  if (!(step_s > 0.0) || !std::isfinite(step_s)) throw InvalidInputError("flexible ring dynamics: bad step");
  const int n = n_;
  linearize(accel, z_scale, v_scale, t0);
  remainders_ = Eigen::VectorXd::Zero(5 * n);
  history_z_ = Eigen::MatrixXd::Zero(n, 4);
  history_v_ = Eigen::MatrixXd::Zero(n, 4);
  history_z_.col(0) = z_;
  history_v_.col(0) = v_;
  history_t_[0] = t_;
  remainders_.segment(n, n) = remainder(accel, z_, v_, t_, &a_);
  known_ = 1;
  y_.resize(2 * n);
  free_.resize(2 * n);
  yp_.resize(2 * n);
  yc_.resize(2 * n);
}

void FlexibleAdams::linearize(const Acceleration& accel, const Eigen::VectorXd& z_scale, const Eigen::VectorXd& v_scale,
                              double t0) {
  const int n = n_;
  const Eigen::VectorXd& z_lin = z_lin_;
  // The linear part: the Jacobian of the acceleration at the equilibrium at rest, by central
  // differences (the remainder takes whatever it misses, so it need only be close).
  lin_.resize(n, 2 * n);
  const Eigen::VectorXd rest = Eigen::VectorXd::Zero(n);
  for (int j = 0; j < 2 * n; ++j) {
    Eigen::VectorXd zp = z_lin, zm = z_lin, vp = rest, vm = rest;
    const double d = j < n ? z_scale[j] : v_scale[j - n];
    if (j < n) {
      zp[j] += d;
      zm[j] -= d;
    } else {
      vp[j - n] += d;
      vm[j - n] -= d;
    }
    lin_.col(j) = (accel(zp, vp, t0) - accel(zm, vm, t0)) / (2.0 * d);
  }
  // L = [0 I; lin]; e^{hL} and phi_1..4(hL) (their right halves, the remainder's) by scaling
  // and squaring, on the balanced D L D^-1 with D = diag(w I, I), w^2 = |d z''/d z| (SI units
  // put 1e8 next to 1: see BearingDynamics).
  const double w = std::max(1.0, std::sqrt(lin_.leftCols(n).lpNorm<Eigen::Infinity>()));
  const int m = 2 * n;
  Eigen::MatrixXd balanced = Eigen::MatrixXd::Zero(m, m);
  balanced.topRightCorner(n, n) = w * Eigen::MatrixXd::Identity(n, n);
  balanced.bottomLeftCorner(n, n) = lin_.leftCols(n) / w;
  balanced.bottomRightCorner(n, n) = lin_.rightCols(n);
  highest_rate_ = Eigen::EigenSolver<Eigen::MatrixXd>(balanced, false).eigenvalues().cwiseAbs().maxCoeff();
  const detail::PhiFunctions f = detail::phi_functions(h_ * balanced, n);
  Eigen::VectorXd d(m);
  d << Eigen::VectorXd::Constant(n, w), Eigen::VectorXd::Ones(n);
  exp_ = d.cwiseInverse().asDiagonal() * f.exp * d.asDiagonal();
  // The right halves' columns are D's unit ones.
  std::array<Eigen::MatrixXd, 5> phi;  // phi_1..phi_4 (index 1..4), right half, times h
  for (int k = 1; k <= 4; ++k) phi[k] = h_ * (d.cwiseInverse().asDiagonal() * f.phi[k - 1]);
  // ETD-AB (polynomial through the step's start and the steps before): phi1, phi2,
  // phi3 + phi2/2, phi4 + phi3 + phi2/3 on nabla^0..3; ETD-AM (through the step's end and
  // the steps before): phi1, phi2 - phi1, phi3 - phi2/2, phi4 - phi2/6.
  const std::array<Eigen::MatrixXd, 4> ab = {phi[1], phi[2], phi[3] + 0.5 * phi[2], phi[4] + phi[3] + phi[2] / 3.0};
  const std::array<Eigen::MatrixXd, 4> am = {phi[1], phi[2] - phi[1], phi[3] - 0.5 * phi[2], phi[4] - phi[2] / 6.0};
  for (int order = 1; order <= 4; ++order) {
    predictor_[order - 1] = remainder_weights(ab, order);
    corrector_[order - 1] = remainder_weights(am, order);
  }
}

void FlexibleAdams::relinearize(const Acceleration& accel, const Eigen::VectorXd& z_lin, const Eigen::VectorXd& z_scale,
                                const Eigen::VectorXd& v_scale) {
  z_lin_ = z_lin;
  linearize(accel, z_scale, v_scale, t_);
  refresh(accel);
}

void FlexibleAdams::refresh(const Acceleration& accel) {
  Eigen::VectorXd a;
  for (int k = 0; k < known_; ++k)
    remainders_.segment(n_ * (k + 1), n_) = remainder(accel, history_z_.col(k), history_v_.col(k), history_t_[k], &a);
  // The current state's acceleration with the new function (reported until the next step).
  const Eigen::VectorXd r = remainder(accel, z_, v_, t_, &a_);
  (void)r;
}

void FlexibleAdams::add_to_rigid_remainders(const std::function<Eigen::Matrix<double, 5, 1>(double)>& delta) {
  for (int k = 0; k < known_; ++k) remainders_.segment<5>(n_ * (k + 1)) += delta(history_t_[k]);
  a_.head<5>() += delta(t_);
}

void FlexibleAdams::change_velocities(const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& change) {
  change(z_, v_);
  for (int k = 0; k < known_; ++k) {
    Eigen::VectorXd v = history_v_.col(k);
    change(history_z_.col(k), v);
    history_v_.col(k) = v;
  }
}

Eigen::VectorXd FlexibleAdams::remainder(const Acceleration& accel, const Eigen::VectorXd& z, const Eigen::VectorXd& v,
                                         double t, Eigen::VectorXd* a) const {
  *a = accel(z, v, t);
  // r = a - lin (z - z_lin, v), with the product's base -a and the sign turned after.
  remainder_y_.resize(2 * n_);
  remainder_y_.head(n_) = z - z_lin_;
  remainder_y_.tail(n_) = v;
  minus_remainder_.resize(n_);
  const Eigen::VectorXd minus_a = -*a;
  detail::multiply_add(n_, 2 * n_, lin_.data(), remainder_y_.data(), minus_a.data(), minus_remainder_.data());
  return -minus_remainder_;
}

void FlexibleAdams::step(const Acceleration& accel) {
  const int n = n_;
  const auto product = [](const Eigen::MatrixXd& a, const double* x, const double* base, double* out) {
    detail::multiply_add(static_cast<int>(a.rows()), static_cast<int>(a.cols()), a.data(), x, base, out);
  };
  y_.head(n) = z_ - z_lin_;
  y_.tail(n) = v_;
  product(exp_, y_.data(), nullptr, free_.data());
  // Predict from the step's start and the remainders before it.
  const int p = std::min(known_, 4);
  product(predictor_[p - 1], remainders_.data() + n, free_.data(), yp_.data());
  const double t_end = t0_ + static_cast<double>(steps_ + 1) * h_;  // not summed: no drift
  remainders_.head(n) = remainder(accel, z_lin_ + yp_.head(n), yp_.tail(n), t_end, &a_end_);
  // Correct with the predicted end's remainder (PEC: not evaluated again).
  const int c = std::min(known_ + 1, 4);
  product(corrector_[c - 1], remainders_.data(), free_.data(), yc_.data());
  // The predicted end's remainder is the newest now, with its state and time.
  std::copy_backward(remainders_.data(), remainders_.data() + 4 * n, remainders_.data() + 5 * n);
  for (int k = 3; k > 0; --k) {
    history_z_.col(k) = history_z_.col(k - 1);
    history_v_.col(k) = history_v_.col(k - 1);
    history_t_[k] = history_t_[k - 1];
  }
  history_z_.col(0) = z_lin_ + yp_.head(n);
  history_v_.col(0) = yp_.tail(n);
  history_t_[0] = t_end;
  known_ = std::min(known_ + 1, 4);
  z_ = z_lin_ + yc_.head(n);
  v_ = yc_.tail(n);
  // The end's acceleration: the predicted end's moved by the linear part.
  y_ = yc_ - yp_;
  a_.resize(n);
  product(lin_, y_.data(), a_end_.data(), a_.data());
  t_ = t_end;
  ++steps_;
}

}  // namespace bearing_sim
