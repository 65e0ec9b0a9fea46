#include "phi_functions.hpp"

#include <algorithm>
#include <cmath>

namespace bearing_sim::detail {

namespace {

// Taylor degree and scaled norm: ||A / 2^s||_1 <= 1/2 leaves terms of phi_0 beyond degree 14
// below 0.5^15 / 15! = 2e-17 of the norm (phi_k's coefficients are smaller still).
constexpr int kDegree = 14;
constexpr double kScaledNorm = 0.5;

}  // namespace

PhiFunctions phi_functions(const Eigen::MatrixXd& a, Eigen::Index columns) {
  constexpr int kHighest = PhiFunctions::kHighest;
  const Eigen::Index m = a.rows();
  const double norm = a.cwiseAbs().colwise().sum().maxCoeff();
  const int s = norm > kScaledNorm ? static_cast<int>(std::ceil(std::log2(norm / kScaledNorm))) : 0;
  const Eigen::MatrixXd x = std::ldexp(1.0, -s) * a;
  // 1 / n! for n up to kDegree + kHighest.
  std::array<double, kDegree + kHighest + 1> inverse_factorial{};
  inverse_factorial[0] = 1.0;
  for (int i = 1; i <= kDegree + kHighest; ++i) inverse_factorial[i] = inverse_factorial[i - 1] / i;
  PhiFunctions out;
  out.exp = Eigen::MatrixXd::Identity(m, m);
  for (int k = 1; k <= kHighest; ++k)
    out.phi[k - 1] = inverse_factorial[k] * Eigen::MatrixXd::Identity(m, m).rightCols(columns);
  // Each power once, added to every function with its own coefficient.
  Eigen::MatrixXd power = Eigen::MatrixXd::Identity(m, m), next(m, m);
  for (int j = 1; j <= kDegree; ++j) {
    next.noalias() = power * x;
    power.swap(next);
    out.exp += inverse_factorial[j] * power;
    for (int k = 1; k <= kHighest; ++k) out.phi[k - 1] += inverse_factorial[j + k] * power.rightCols(columns);
  }
  std::array<Eigen::MatrixXd, kHighest> doubled;
  for (int i = 0; i < s; ++i) {
    for (int k = 1; k <= kHighest; ++k) {
      doubled[k - 1].noalias() = out.exp * out.phi[k - 1];
      for (int j = 1; j <= k; ++j) doubled[k - 1] += inverse_factorial[k - j] * out.phi[j - 1];
      doubled[k - 1] *= std::ldexp(1.0, -k);
    }
    for (int k = 0; k < kHighest; ++k) out.phi[k].swap(doubled[k]);
    next.noalias() = out.exp * out.exp;
    out.exp.swap(next);
  }
  return out;
}

}  // namespace bearing_sim::detail
