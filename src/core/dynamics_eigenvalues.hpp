#pragma once
// The dense eigenvalue problems of BearingDynamics' step-size choice, in a translation unit of
// their own (dynamics_eigenvalues.cpp): Eigen's fixed-size eigensolvers are most of the
// compile time of the file that instantiates them. Internal to the core library.
#include <Eigen/Dense>

#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim::detail {

// sqrt of the eigenvalues of the symmetric part of `stiffness` relative to `mass` (negative
// ones as 0): the undamped natural frequencies, rad/s.
Vector5 undamped_natural_frequencies(const Matrix5& stiffness, const Matrix5& mass);

// The largest |lambda| of the 10 x 10 matrix `a`.
double largest_eigenvalue_magnitude(const Eigen::Matrix<double, 10, 10>& a);

}  // namespace bearing_sim::detail
