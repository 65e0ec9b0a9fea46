#pragma once
// A bearing whose rotating ring is a flexible thin ring (docs/model.md section 18): the rigid
// ring's 5 coordinates q plus two modal coordinates (cos, sin) per ring mode, x = (q, eta).
// The ring's radial and axial displacement at each ball's place on it adds to the rigid
// displacement of that ball's groove centre; the ball loads project back onto the modes by
// the same map (virtual work). Its own contact loop: the rigid model's SIMD kernel is left alone.
#include <vector>

#include <Eigen/Dense>

#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/ring_modes.hpp"

namespace bearing_sim {

class FlexibleBearing {
 public:
  // Throws InvalidInputError when the bearing file has no flexible_ring block.
  explicit FlexibleBearing(BearingModel model);

  const BearingModel& model() const { return model_; }
  const std::vector<RingMode>& modes() const { return modes_; }
  int size() const { return 5 + 2 * static_cast<int>(modes_.size()); }  // of x

  // M = diag(rigid mass matrix, modal masses); throws InvalidInputError without rotating_mass_kg.
  Eigen::MatrixXd mass_matrix() const;
  // The ring's own stiffness (bending and seat) and damping per coordinate: 0 for the rigid ones.
  Eigen::VectorXd ring_stiffness() const;
  Eigen::VectorXd ring_damping() const;

  // Generalized contact force on x (forces, moments, modal forces), with contact damping.
  Eigen::VectorXd contact_force(const Eigen::VectorXd& x, const Eigen::VectorXd& x_dot,
                                const RollingPhase& phase) const;
  // Without damping, and the stiffness -dF/dx (analytic) if asked for.
  Eigen::VectorXd contact_force_and_stiffness(const Eigen::VectorXd& x, const RollingPhase& phase,
                                              Eigen::MatrixXd* stiffness) const;
  // The same with the modal pairs in the load's frame, b = R(n psi) a (docs/model.md 18.4):
  // the shapes taken at the balls' azimuths. rates: q' and each pair's rate as the ring's
  // material sees it, R a' = b' - n Omega J b. simd: the Highway kernel, else the scalar loop.
  // work: scratch the caller keeps between calls (none: allocated per call).
  Eigen::VectorXd contact_force_load_frame(const Eigen::VectorXd& z, const Eigen::VectorXd& rates,
                                           const RollingPhase& phase, bool simd = true,
                                           std::vector<double>* work = nullptr) const;
  std::vector<BallState> ball_states(const Eigen::VectorXd& x, const RollingPhase& phase) const;

  // Displacement of the ring's centre line at angle theta of the ring's own (material) frame:
  // radial (outwards) and axial, m.
  double radial_displacement_m(const Eigen::VectorXd& x, double theta_rad) const;
  double axial_displacement_m(const Eigen::VectorXd& x, double theta_rad) const;
  // Angle the flexible (rotating) ring has turned at a phase: ball azimuth phi sits at
  // theta = phi - ring_angle on the ring.
  double ring_angle_rad(const RollingPhase& phase) const;
  // The centre line's displacement at `points` azimuths phi_i = 2 pi i / points of the bearing
  // frame (the material angle theta = phi - ring_angle): what the display draws. Throws
  // InvalidInputError for points < 1.
  struct Deformation {
    double ring_angle_rad = 0.0;
    std::vector<double> azimuth_rad, radial_m, axial_m;
  };
  Deformation deformation(const Eigen::VectorXd& x, const RollingPhase& phase, int points) const;

 private:
  // The sum over the modes of one direction of their (cos, sin) coordinates at theta.
  double displacement_m(const Eigen::VectorXd& x, double theta_rad, RingModeDirection direction) const;
  template <bool kDamped, bool kStiffness>
  void contact_loop(const Eigen::VectorXd& x, const Eigen::VectorXd* x_dot, const RollingPhase& phase,
                    Eigen::VectorXd* force, Eigen::MatrixXd* stiffness, std::vector<BallState>* states) const;
  BearingModel model_;
  std::vector<RingMode> modes_;
  std::vector<int> mode_orders_, mode_radial_;  // for the load-frame kernel
  std::vector<int> radial_mode_of_order_, axial_mode_of_order_;  // per order: its mode, -1 if none
  // cos k beta_b, sin k beta_b of the balls' base azimuths, k = 0..max order, rows of stride_.
  std::vector<double> base_cos_n_, base_sin_n_;
  int stride_ = 0;
  // Rows whose balls share azimuths (1 or 2), balls per shared row, and their scratch row.
  int rows_sharing_ = 1, azimuths_ = 0, row_stride_ = 0;
  int max_order_ = 0;
  double groove_radius_ = 0.0, cos_a0_ = 1.0;
};

struct FlexibleStaticSolution {
  // q, stiffness condensed onto q (the ring's modes statically eliminated: what the bearing
  // offers the rigid-body coordinates), ball loads and pressures, with the flexible ring.
  StaticSolution rigid_coordinates;
  Eigen::VectorXd coordinates;  // x = (q, eta)
  Eigen::MatrixXd stiffness;    // full: contacts plus the ring's own, -dF/dx
};

// Solves F_ext + F_contact(x) - K_ring eta = 0 (rigid coordinates and modes) by damped Newton
// from the rigid ring's equilibrium. Throws LoadNotCarriedError as solve_static does.
FlexibleStaticSolution solve_flexible_static(const FlexibleBearing& bearing, const Vector5& load,
                                             const RollingPhase& phase = RollingPhase{});

// Natural frequencies (rad/s, ascending) of the linearized system at a solution: rigid ring
// and ring modes on the loaded contacts, with the ring's seat.
Eigen::VectorXd flexible_natural_frequencies_rad_s(const FlexibleBearing& bearing,
                                                   const FlexibleStaticSolution& solution);

}  // namespace bearing_sim
