#pragma once
// Eigen's 5 x 5 symmetric eigensolvers, compiled once in the core (symmetric_eigen.cpp): their
// instantiation is most of the compile time of a file that uses them (the step-size choice,
// the radial mode, the sweep's ring modes, the runtime's check of the dynamics).
#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim {

struct SymmetricEigen5 {
  Vector5 eigenvalues = Vector5::Zero();   // ascending
  Matrix5 eigenvectors = Matrix5::Zero();  // columns; only when asked for
  bool converged = false;
};

// a x = lambda x for a symmetric `a` (its lower triangle is read).
SymmetricEigen5 symmetric_eigen(const Matrix5& a, bool with_eigenvectors);

// a x = lambda b x for a symmetric `a` and a symmetric positive definite `b`; the eigenvectors
// are b-normalised.
SymmetricEigen5 generalized_symmetric_eigen(const Matrix5& a, const Matrix5& b, bool with_eigenvectors);

}  // namespace bearing_sim
