#include "bearing_sim/core/symmetric_eigen.hpp"

#include <Eigen/Eigenvalues>

namespace bearing_sim {
namespace {

template <typename Solver>
SymmetricEigen5 result_of(const Solver& solver, bool with_eigenvectors) {
  SymmetricEigen5 r;
  r.converged = solver.info() == Eigen::Success;
  r.eigenvalues = solver.eigenvalues();
  if (with_eigenvectors) r.eigenvectors = solver.eigenvectors();
  return r;
}

int options(bool with_eigenvectors) { return with_eigenvectors ? Eigen::ComputeEigenvectors : Eigen::EigenvaluesOnly; }

}  // namespace

SymmetricEigen5 symmetric_eigen(const Matrix5& a, bool with_eigenvectors) {
  return result_of(Eigen::SelfAdjointEigenSolver<Matrix5>(a, options(with_eigenvectors)), with_eigenvectors);
}

SymmetricEigen5 generalized_symmetric_eigen(const Matrix5& a, const Matrix5& b, bool with_eigenvectors) {
  return result_of(Eigen::GeneralizedSelfAdjointEigenSolver<Matrix5>(a, b, options(with_eigenvectors)),
                   with_eigenvectors);
}

}  // namespace bearing_sim
