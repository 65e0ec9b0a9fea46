#pragma once
// Dynamics of a bearing with a flexible rotating ring (docs/model.md section 18.3):
// M x'' = F_ext + F_contact(x, x', t) - K_ring x - C_ring x' with x = (q, eta), integrated by
// classical RK4 with a fixed internal step from the highest natural frequency at the static
// equilibrium. Clear rather than fast: an offline (bearing_tool) model; the node and
// BearingDynamics keep the rigid ring.
#include <cstdint>

#include <Eigen/Dense>

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
  // at ring_speed_rad_s. substeps = 0: from the highest natural frequency, |omega| h <= 0.5.
  // Throws LoadNotCarriedError, InvalidInputError (no rotating_mass_kg, bad rate or speed).
  FlexibleDynamics(FlexibleBearing bearing, const Vector5& load, double ring_speed_rad_s,
                   double sample_rate_hz = 10000.0, int substeps = 0);

  // One output sample. Throws DivergenceError on a non-finite state.
  const FlexibleSample& step();

  const FlexibleSample& current() const { return current_; }
  const FlexibleBearing& bearing() const { return bearing_; }
  const FlexibleStaticSolution& equilibrium() const { return equilibrium_; }
  int substeps() const { return substeps_; }
  double internal_step_s() const { return 1.0 / (sample_rate_hz_ * substeps_); }
  double highest_frequency_rad_s() const { return highest_frequency_rad_s_; }
  static constexpr double kStepTimesOmegaMax = 0.5;  // as BearingDynamics' RK4

 private:
  Eigen::VectorXd acceleration(const Eigen::VectorXd& x, const Eigen::VectorXd& v, const RollingPhase& phase) const;
  RollingPhase advanced(const RollingPhase& phase, double dt) const;

  FlexibleBearing bearing_;
  Vector5 load_;
  Eigen::VectorXd external_, k_ring_, c_ring_;
  Eigen::LDLT<Eigen::MatrixXd> mass_;
  double sample_rate_hz_;
  double inner_speed_ = 0.0, outer_speed_ = 0.0, cage_speed_ = 0.0, spin_speed_ = 0.0;
  FlexibleStaticSolution equilibrium_;
  double highest_frequency_rad_s_ = 0.0;
  int substeps_ = 1;
  std::uint64_t sample_index_ = 0;
  FlexibleSample current_;
};

}  // namespace bearing_sim
