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

  // Inputs between samples, as BearingDynamics' (InvalidInputError when not finite). A load
  // given with its end value follows the straight line through the mid value at the sample's
  // middle and the end value at its end, then holds the end value. The Adams method's history
  // moves with a new load (as if it had always acted: the remainder is linear in it) and with
  // a new speed (its load-frame rates: the material's rate is what stays); its linear part is
  // made again when the load or the speed has moved far enough since the last (see below).
  void set_load(const Vector5& load);
  void set_load(const Vector5& load_over_sample, const Vector5& load_at_sample_end);
  void set_ring_speed(double ring_speed_rad_s);
  // Replace the bearing (clearance, damping, temperature; it must keep its flexible_ring
  // block) keeping the state; the Adams method linearizes again.
  void set_model(BearingModel model);
  // Spalls at runtime (a new one starts growing now); InvalidInputError for one that does not fit.
  void add_spall(Spall spall);
  void clear_spalls();
  // Back to the static equilibrium of the current load, the ring's shape standing in the load's
  // frame, keeping time and phases.
  void reset_to_equilibrium();

  const Vector5& load() const { return load_line_.load; }
  double ring_speed_rad_s() const { return ring_speed_; }
  double sample_rate_hz() const { return sample_rate_hz_; }
  std::uint64_t sample_index() const { return sample_index_; }
  // Linear parts made by the Adams method since construction (the first included).
  std::uint64_t linearizations() const { return linearizations_; }
  // The Adams method linearizes again (at the static equilibrium of the current load) when,
  // since the last linearization, the load has moved by more than kRelinearizeLoadChange of
  // its size then (the contacts' stiffness goes as F^(1/3): 20 % of load is 6 % of stiffness,
  // as the rigid ring's rule), or the highest ring order's turning rate n_max Omega by more than
  // kRelinearizeTurnChange of the lowest natural frequency then (the turning terms 2 n Omega
  // and (n Omega)^2 of the linear part are all the speed changes in it); at most once per
  // kSamplesPerLinearization samples (docs/model.md 18.5).
  static constexpr double kRelinearizeLoadChange = 0.2;
  static constexpr double kRelinearizeTurnChange = 0.05;
  static constexpr int kSamplesPerLinearization = 16;

  const FlexibleSample& current() const { return current_; }
  const FlexibleBearing& bearing() const { return bearing_; }
  const FlexibleStaticSolution& equilibrium() const { return equilibrium_; }
  int substeps() const { return substeps_; }
  double internal_step_s() const { return 1.0 / (sample_rate_hz_ * substeps_); }
  double highest_frequency_rad_s() const { return highest_frequency_rad_s_; }
  IntegrationMethod method() const { return method_; }
  static constexpr double kStepTimesOmegaMax = 0.5;  // as BearingDynamics' RK4
  static constexpr int kAdamsStepsPerSample = 1;
  // With a spall the remainder is rough within a step (a ball entering or leaving it): the CT
  // ring with a 1 mm x 20 um outer-race spall is +3.9 % off converged RK4 in a_rms at one step
  // per 10 kHz sample, +1.9 % at 2, -0.3 % at 4 (docs/model.md 18.5). Automatic mode takes 4
  // while a spall is present.
  static constexpr int kAdamsStepsPerSampleWithSpall = 4;

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
  // Ring-frame velocities of a static shape that stands in the load's frame while the ring turns.
  Eigen::VectorXd static_shape_velocities(const Eigen::VectorXd& coordinates) const;
  // The phases at time t (from the last speed change on, at the current speeds).
  RollingPhase phase_at(double t) const { return advanced(origin_, t - origin_.time_s); }
  void update_speeds();
  // The external force on x at time t (the load line's, zero on the ring's modes).
  const Eigen::VectorXd& external_at(double t) const;
  // The ring-frame coordinates x at ring angle psi in the load's frame, b = R(n psi) a.
  Eigen::VectorXd to_load_frame(const Eigen::VectorXd& x, double psi) const;
  void start_adams(const Eigen::VectorXd& z0, const Eigen::VectorXd& v0, double t0);
  // Automatic Adams steps per sample for the current bearing (with or without a spall), and
  // after a defect changes: the history evaluated again, or with a new step the method started
  // again from its state, linearized at the static equilibrium.
  int automatic_adams_steps() const;
  void defects_changed();
  bool automatic_substeps_ = false;
  void relinearize_adams();
  void linearization_steps(Eigen::VectorXd* z_step, Eigen::VectorXd* v_step) const;
  FlexibleAdams::Acceleration load_frame_function() {
    return [this](const Eigen::VectorXd& z, const Eigen::VectorXd& zd, double t) {
      return load_frame_acceleration(z, zd, t);
    };
  }
  // After a change of bearing: mass, ring stiffness and damping, speeds, lowest frequency.
  void bearing_changed();
  void change_load(const Vector5& load, const Vector5& rate, double mid_time_s);
  // The time of the state the next step starts from (the last sample's).
  double state_time_s() const { return static_cast<double>(sample_index_) / sample_rate_hz_; }
  // Each pair's rate as the ring's material sees it, in the load's frame: R a' = b' - w J b
  // (w = n Omega, J = [0 -1; 1 0]); the rigid coordinates' rates as they are.
  void material_rate(const Eigen::VectorXd& z, const Eigen::VectorXd& z_dot, Eigen::VectorXd* rate_out) const;

  FlexibleBearing bearing_;
  // The external load in time: load + rate (t - mid_time_s), as BearingDynamics'.
  struct LoadLine {
    Vector5 load = Vector5::Zero(), rate = Vector5::Zero();
    double mid_time_s = 0.0;
    Vector5 at(double t) const { return load + rate * (t - mid_time_s); }
  };
  LoadLine load_line_;
  mutable Eigen::VectorXd external_;
  Eigen::VectorXd k_ring_, c_ring_;
  double ring_speed_ = 0.0;
  RollingPhase origin_;  // the phases at the last speed change (time_s: its time)
  // At the last linearization: load, ring speed, lowest natural frequency (rad/s).
  Vector5 load_lin_ = Vector5::Zero();
  double speed_lin_ = 0.0, lowest_frequency_lin_rad_s_ = 0.0;
  int samples_since_linearization_ = 0;
  std::uint64_t linearizations_ = 0;
  int max_order_ = 0;
  Eigen::LDLT<Eigen::MatrixXd> mass_;
  Matrix5 inverse_rigid_mass_ = Matrix5::Identity();  // of the rigid-body block (M is block diagonal)
  double sample_rate_hz_;
  double inner_speed_ = 0.0, outer_speed_ = 0.0, cage_speed_ = 0.0, spin_speed_ = 0.0;
  FlexibleStaticSolution equilibrium_;
  double highest_frequency_rad_s_ = 0.0;
  int substeps_ = 1;
  IntegrationMethod method_ = IntegrationMethod::ExponentialAdamsPec;
  mutable Eigen::VectorXd material_rate_;     // load_frame_acceleration's scratch
  mutable std::vector<double> contact_work_;  // the contact kernel's
  std::optional<FlexibleAdams> adams_;        // holds no reference to this: copies step on their own
  std::uint64_t sample_index_ = 0;
  FlexibleSample current_;
};

}  // namespace bearing_sim
