#pragma once
// 5-DOF quasi-static equilibrium of the moving ring (docs/model.md section 6).
#include <vector>

#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim {

// Above this maximum contact pressure the static load exceeds the usual permissible
// limit for ball bearings (ISO 76).
constexpr double kPermissibleContactPressurePa = 4200e6;

struct StaticSolution {
  Vector5 displacement = Vector5::Zero();  // x, y, z, theta_x, theta_y (m, rad)
  Matrix5 stiffness = Matrix5::Zero();     // -d(contact force)/dq, SI
  std::vector<BallState> balls;
  double max_ball_load_N = 0.0;
  double max_contact_pressure_Pa = 0.0;
  double residual_norm = 0.0;  // |F_ext + F_contact| with moments divided by the pitch radius, N
  int iterations = 0;
  bool exceeds_permissible_pressure() const { return max_contact_pressure_Pa > kPermissibleContactPressurePa; }
};

struct StaticSolverOptions {
  int max_iterations = 200;
  double force_tolerance_N = 1e-9;  // absolute, added to a relative 1e-12 of the load
};

// Solves F_ext + F_contact(q) = 0 by damped Newton with the analytic Jacobian.
// `load` is (Fx, Fy, Fz, Mx, My) on the moving ring, N and N*m.
// Throws LoadNotCarriedError when no equilibrium exists, InvalidInputError for a
// non-finite load.
StaticSolution solve_static(const BearingModel& model, const Vector5& load, const RollingPhase& phase,
                            const StaticSolverOptions& options = {}, const Vector5* initial_guess = nullptr);
inline StaticSolution solve_static(const BearingModel& model, const Vector5& load, double cage_angle_rad = 0.0,
                                   const StaticSolverOptions& options = {}, const Vector5* initial_guess = nullptr) {
  return solve_static(model, load, RollingPhase{cage_angle_rad}, options, initial_guess);
}

}  // namespace bearing_sim
