#include "dynamics_eigenvalues.hpp"

#include "bearing_sim/core/symmetric_eigen.hpp"

namespace bearing_sim::detail {

Vector5 undamped_natural_frequencies(const Matrix5& stiffness, const Matrix5& mass) {
  return generalized_symmetric_eigen(0.5 * (stiffness + stiffness.transpose()), mass, false)
      .eigenvalues.cwiseMax(0.0)
      .cwiseSqrt();
}

double largest_eigenvalue_magnitude(const Eigen::Matrix<double, 10, 10>& a) {
  return Eigen::EigenSolver<Eigen::Matrix<double, 10, 10>>(a, false).eigenvalues().cwiseAbs().maxCoeff();
}

}  // namespace bearing_sim::detail
