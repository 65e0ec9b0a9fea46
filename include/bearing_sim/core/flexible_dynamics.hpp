#pragma once
// Dynamics of a bearing with a flexible rotating ring (docs/model.md section 18.3):
// M x'' = F_ext + F_contact(x, x', t) - K_ring x - C_ring x' with x = (q, eta), integrated by
// the exponential Adams method in the load's frame (FlexibleAdams, the default) or by
// classical RK4 with a fixed internal step from the highest natural frequency at the static
// equilibrium (the reference).
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Dense>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/flexible_adams.hpp"
#include "bearing_sim/core/flexible_bearing.hpp"

namespace bearing_sim {

struct FlexibleSample {
  double time_s = 0.0;
  RollingPhase phase;
  Eigen::VectorXd coordinates;    // x = (q, eta), m and rad
  Eigen::VectorXd velocities;     // x'
  Eigen::VectorXd accelerations;  // x''
};

class FlexibleDynamics {
 public:
  // Starts at the static equilibrium under `load` (on the moving ring) with the rotating ring
  // at ring_speed_rad_s. substeps = 0: automatic (rk4: from the highest natural frequency,
  // |omega| h <= 0.5; adams_pec: kAdamsStepsPerSample). method: ExponentialAdamsPec or Rk4.
  // Throws LoadNotCarriedError, InvalidInputError (no rotating_mass_kg, bad rate, speed or
  // method).
  FlexibleDynamics(FlexibleBearing bearing, const Vector5& load, double ring_speed_rad_s,
                   double sample_rate_hz = 10000.0, int substeps = 0,
                   IntegrationMethod method = IntegrationMethod::ExponentialAdamsPec);

  // One output sample. Throws DivergenceError on a non-finite state.
  const FlexibleSample& step();

  const FlexibleSample& current() const { return current_; }
  const FlexibleBearing& bearing() const { return bearing_; }
  const FlexibleStaticSolution& equilibrium() const { return equilibrium_; }
  int substeps() const { return substeps_; }
  double internal_step_s() const { return 1.0 / (sample_rate_hz_ * substeps_); }
  double highest_frequency_rad_s() const { return highest_frequency_rad_s_; }
  IntegrationMethod method() const { return method_; }
  static constexpr double kStepTimesOmegaMax = 0.5;  // as BearingDynamics' RK4
  static constexpr int kAdamsStepsPerSample = 1;

 private:
  Eigen::VectorXd acceleration(const Eigen::VectorXd& x, const Eigen::VectorXd& v, const RollingPhase& phase) const;
  RollingPhase advanced(const RollingPhase& phase, double dt) const;
  // The acceleration with the ring's modal pairs in the load's frame, b = R(n psi) a, at time t
  // (FlexibleAdams' coordinates; docs/model.md 18.4). to_ring_frame: z, z' -> x, x'.
  Eigen::VectorXd load_frame_acceleration(const Eigen::VectorXd& z, const Eigen::VectorXd& z_dot, double t) const;
  void to_ring_frame(const Eigen::VectorXd& z, const Eigen::VectorXd& z_dot, const Eigen::VectorXd* z_ddot, double t,
                     Eigen::VectorXd* x, Eigen::VectorXd* x_dot, Eigen::VectorXd* x_ddot) const;
  void step_rk4();
  void step_adams();
  double ring_rate_rad_s() const;
  // Each pair's rate as the ring's material sees it, in the load's frame: R a' = b' - w J b
  // (w = n Omega, J = [0 -1; 1 0]); the rigid coordinates' rates as they are.
  void material_rate(const Eigen::VectorXd& z, const Eigen::VectorXd& z_dot, Eigen::VectorXd* rate_out) const;

  FlexibleBearing bearing_;
  Vector5 load_;
  Eigen::VectorXd external_, k_ring_, c_ring_;
  Eigen::LDLT<Eigen::MatrixXd> mass_;
  double sample_rate_hz_;
  double inner_speed_ = 0.0, outer_speed_ = 0.0, cage_speed_ = 0.0, spin_speed_ = 0.0;
  FlexibleStaticSolution equilibrium_;
  double highest_frequency_rad_s_ = 0.0;
  int substeps_ = 1;
  IntegrationMethod method_ = IntegrationMethod::ExponentialAdamsPec;
  mutable Eigen::VectorXd material_rate_;     // load_frame_acceleration's scratch
  mutable std::vector<double> contact_work_;  // the contact kernel's
  std::optional<FlexibleAdams> adams_;  // holds no reference to this: copies step on their own
  std::uint64_t sample_index_ = 0;
  FlexibleSample current_;
};

}  // namespace bearing_sim
