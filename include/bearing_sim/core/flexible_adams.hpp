#pragma once
// Exponential Adams integrator of the flexible-ring bearing (docs/model.md section 18.4).
// The ring's modal coordinates are taken in the load's (space-fixed) frame, b = R(n psi) a
// per (cos, sin) pair: there the loaded contacts' stiffness stands still while the ring turns
// under it, so one linearization at the static equilibrium holds for the whole run, and the
// ring's turning adds constant Coriolis and centrifugal terms to it. The linear part is
// integrated exactly (matrix exponential and phi functions), the remainder (varying
// compliance, the contacts' nonlinearity) by an ETD-AB4 predictor and ETD-AM4 corrector with
// one force evaluation per step (PEC, as the rigid ring's default integrator).
#include <array>
#include <functional>

#include <Eigen/Dense>

namespace bearing_sim {

class FlexibleAdams {
 public:
  // accel(z, z_dot, t) -> z'' in the space frame. The linear part is its Jacobian at
  // (z_lin, 0, t0) by central differences (z_scale, v_scale: the steps per coordinate).
  using Acceleration = std::function<Eigen::VectorXd(const Eigen::VectorXd&, const Eigen::VectorXd&, double)>;
  // The state starts at (z0, v0) at time t0. accel is passed to every call rather than kept,
  // so that a copy of the owner (which the function refers to) stays valid.
  FlexibleAdams(const Acceleration& accel, const Eigen::VectorXd& z_lin, const Eigen::VectorXd& z_scale,
                const Eigen::VectorXd& v_scale, const Eigen::VectorXd& z0, const Eigen::VectorXd& v0, double step_s,
                double t0);

  // One step of step_s from the current state.
  void step(const Acceleration& accel);
  // A new linear part at (z_lin, 0) at the current time, for an acceleration function that
  // changed (load, speed, bearing): the Jacobian, e^{hL} and the phi weights again, and the
  // remainders of the history evaluated again at their states and times with `accel` (4
  // force evaluations), so that the method keeps its order across the change.
  void relinearize(const Acceleration& accel, const Eigen::VectorXd& z_lin, const Eigen::VectorXd& z_scale,
                   const Eigen::VectorXd& v_scale);
  // The history's remainders evaluated again with `accel` (a spall added or cleared: the
  // remainder jumps), keeping the linear part.
  void refresh(const Acceleration& accel);
  // Adds delta(t) to the first 5 coordinates (the rigid body's) of the remainder of each
  // history entry at its time t and of the current acceleration (a changed external load: as
  // if the new one had always acted; r is linear in it).
  void add_to_rigid_remainders(const std::function<Eigen::Matrix<double, 5, 1>(double)>& delta);
  // change(z, v) adds to v what a change of frame speed makes of it, for the state and the
  // history's states (the ring's speed changed: the load frame's rate of the same material
  // motion moves by dw J b).
  void change_velocities(const std::function<void(const Eigen::VectorXd&, Eigen::VectorXd&)>& change);
  const Eigen::VectorXd& linearization_point() const { return z_lin_; }
  const Eigen::VectorXd& position() const { return z_; }
  const Eigen::VectorXd& velocity() const { return v_; }
  const Eigen::VectorXd& acceleration() const { return a_; }
  double time_s() const { return t_; }
  // The highest |eigenvalue| of the linear part, rad/s.
  double highest_rate_rad_s() const { return highest_rate_; }

 private:
  void linearize(const Acceleration& accel, const Eigen::VectorXd& z_scale, const Eigen::VectorXd& v_scale, double t);
  // r = z'' - lin (z - z_lin, z'), and z'' in *accel.
  Eigen::VectorXd remainder(const Acceleration& accel, const Eigen::VectorXd& z, const Eigen::VectorXd& v, double t,
                            Eigen::VectorXd* a) const;

  int n_ = 0;
  double h_ = 0.0, t0_ = 0.0, t_ = 0.0;
  long steps_ = 0;
  Eigen::VectorXd z_lin_;
  Eigen::MatrixXd lin_;  // n x 2n: z'' = lin (z - z_lin, z') + remainder
  Eigen::MatrixXd exp_;  // 2n x 2n: e^{hL}
  // For the methods of order 1..4 (the first steps have fewer remainders), times h: the
  // predictor's weights of the remainders at the step's start and the 3 steps before,
  // [P0 P1 P2 P3], and the corrector's of those at its end and the 3 before, [C0 C1 C2 C3]
  // (2n x 4n each, zero columns beyond the order).
  std::array<Eigen::MatrixXd, 4> predictor_, corrector_;
  // [r_end | r_0 r_-1 r_-2 r_-3]: the remainders, newest first, with a slot in front for the
  // predicted end's, so that both products read one contiguous vector.
  Eigen::VectorXd remainders_;
  int known_ = 0;  // how many of the 4 are known
  // The states and times the 4 history remainders were evaluated at, newest first (columns).
  Eigen::MatrixXd history_z_, history_v_;
  std::array<double, 4> history_t_{};
  Eigen::VectorXd y_, free_, yp_, yc_, a_end_;  // work vectors (no allocation per step)
  mutable Eigen::VectorXd remainder_y_, minus_remainder_;
  Eigen::VectorXd z_, v_, a_;
  double highest_rate_ = 0.0;
};

}  // namespace bearing_sim
