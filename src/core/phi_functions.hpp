#pragma once
// The exponential and the phi functions of a matrix, phi_0(A) = e^A and
// phi_k(A) = sum_j A^j / (j + k)!, by scaling and modified squaring (Skaflestad and Wright,
// Appl. Numer. Math. 59, 2009): a Taylor polynomial at A / 2^s, then s doublings of
// phi_k(2A) = 2^-k (phi_0(A) phi_k(A) + sum_{j=1..k} phi_j(A) / (k - j)!). The same numbers
// as the first block row of the exponential of [A I 0 ..; 0 0 I ..; ..; 0] at (k + 1) times
// the size, for about a hundredth of its cost (docs/model.md 18.5).
#include <array>

#include <Eigen/Dense>

namespace bearing_sim::detail {

struct PhiFunctions {
  static constexpr int kHighest = 4;
  Eigen::MatrixXd exp;                        // phi_0(A) = e^A, whole
  std::array<Eigen::MatrixXd, kHighest> phi;  // phi[k - 1]: the last `columns` columns of phi_k(A)
};

// A square; columns <= A's size: how many of the last columns of phi_1..4 are wanted (their
// squaring needs only those, e^A whole).
PhiFunctions phi_functions(const Eigen::MatrixXd& a, Eigen::Index columns);

}  // namespace bearing_sim::detail
