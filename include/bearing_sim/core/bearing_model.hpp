#pragma once
// Geometry, Hertz constants and contact forces of one bearing (docs/model.md sections 3-5).
// Everything derived from the bearing file is computed here, once.
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/hertz_contact.hpp"
#include "bearing_sim/core/imperfections.hpp"

namespace bearing_sim {

// Generalized coordinates of the moving ring relative to the fixed ring:
// (x, y, z, theta_x, theta_y) in m and rad; loads in the same order in N and N*m.
using Vector5 = Eigen::Matrix<double, 5, 1>;
using Matrix5 = Eigen::Matrix<double, 5, 5>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

struct BallState {
  int row = 0;  // 0 or 1
  int index_in_row = 0;
  double azimuth_rad = 0.0;
  double load_N = 0.0;                               // normal contact force Q
  double deflection_m = 0.0;                         // delta (negative: gap)
  double contact_angle_rad = 0.0;                    // loaded contact angle
  double pressure_Pa = 0.0;                          // largest of the inner and outer maximum Hertz pressures
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // contact line, inner to outer
};

// Per-ball constants in the structure-of-arrays layout of the vectorized force loop;
// either every ball of the bearing or a subset of them.
struct BallArrays {
  std::vector<int> ball;  // index into the bearing's balls
  std::vector<int> row;
  std::vector<double> base_azimuth;        // azimuth at cage angle 0, rad
  std::vector<double> cos_base, sin_base;  // of base_azimuth
  std::vector<double> groove_centre_z;     // axial coordinate of the moving ring's groove centre
  std::vector<double> normal_z;            // c_r sin a0
  std::vector<double> deflection_offset;   // constant extra deflection (ball size), m
  std::uint64_t generation = 0;            // changes whenever the subset changes
  std::uint64_t source_stamp = 0;          // of the model's arrays a subset was taken from
  std::size_t size() const { return ball.size(); }
  void clear();
  void push_back(const BallArrays& from, std::size_t i);
  // The entries from[entries[0..n)] (ascending), replacing the content (a new generation).
  void assign(const BallArrays& from, const int* entries, std::size_t n);

 private:
  void next_generation();
};

class BearingModel {
 public:
  // Throws InvalidInputError when the ring temperature difference takes the clearance out of range.
  explicit BearingModel(BearingConfig config);

  const BearingConfig& config() const { return config_; }
  int ball_count() const { return static_cast<int>(balls_.size()); }
  int balls_per_row() const { return config_.balls_per_row; }
  int rows() const { return config_.rows; }

  double groove_centre_distance_m() const { return groove_centre_distance_; }  // A
  // g0 in use: the file's clearance changed by the ring temperature difference (section 3.7).
  double clearance_m() const { return clearance_m_; }
  double contact_stiffness() const { return contact_stiffness_; }  // Kn, N/m^1.5
  const HertzContact& inner_contact() const { return inner_contact_; }
  const HertzContact& outer_contact() const { return outer_contact_; }
  double pitch_radius_m() const { return config_.pitch_diameter_m / 2.0; }
  // Radial coordinate of the moving ring's groove centres (P_o or P_i), m.
  double groove_centre_radius_m() const { return groove_centre_radius_; }
  double row_axial_position_m(int row) const;  // z_r of the ball centres
  int row_contact_sign(int row) const;         // c_r
  int row_of_ball(int ball) const { return balls_.row[ball]; }
  double base_azimuth_rad(int ball) const { return base_azimuth_[ball]; }
  // +1 when the outer ring is the moving body, -1 for the inner ring.
  double moving_sign() const { return moving_sign_; }

  // Mass matrix diag(m, m, m, J, J) of the moving ring.
  // Mass matrix of the moving ring in q = (x, y, z, theta_x, theta_y) about the bearing
  // centre: the ring's mass and tilt inertia, plus the carried body's rigid-body mass matrix
  // with its centre of gravity's axial offset coupling x with theta_y and y with theta_x
  // (docs/model.md 7.1). Throws InvalidInputError without rotating_mass_kg.
  Matrix5 mass_matrix() const;

  // Constant extra contact deflection per ball (ball diameter variation by default).
  void set_deflection_offsets(const std::vector<double>& offsets_m);
  const std::vector<double>& deflection_offsets() const { return balls_.deflection_offset; }
  const BallArrays& balls() const { return balls_; }

  // Waviness, roughness and spalls; their offsets move with the rolling phase.
  const Imperfections& imperfections() const { return imperfections_; }
  void add_spall(const Spall& spall);  // throws InvalidInputError
  void clear_spalls();

  // Contact forces and moments on the moving ring, with contact damping (hot path),
  // over every ball or a subset (the others known to be out of contact).
  // Fastest: the SIMD kernel for this CPU's best target (run-time dispatch); Scalar: the plain
  // reference loop, for checking it.
  enum class ContactKernel { Fastest, Scalar };
  Vector5 contact_force(const Vector5& q, const Vector5& q_dot, const RollingPhase& phase, const BallArrays& balls,
                        ContactKernel kernel = ContactKernel::Fastest) const;
  // Same, with cos and sin of phase.cage given (an integrator that advances the cage by
  // a fixed angle can rotate them instead of calling sincos at every stage).
  Vector5 contact_force(const Vector5& q, const Vector5& q_dot, const RollingPhase& phase, const BallArrays& balls,
                        double cos_cage, double sin_cage, ContactKernel kernel = ContactKernel::Fastest) const;
  Vector5 contact_force(const Vector5& q, const Vector5& q_dot, const RollingPhase& phase) const {
    return contact_force(q, q_dot, phase, balls_);
  }
  Vector5 contact_force(const Vector5& q, const Vector5& q_dot, double cage_angle_rad) const {
    return contact_force(q, q_dot, RollingPhase{cage_angle_rad}, balls_);
  }
  // Same, without damping, and the stiffness K = -d(force)/dq (analytic) and the damping
  // matrix C = -d(force)/d(q_dot) of the loaded contacts, each if asked for.
  Vector5 contact_force_and_stiffness(const Vector5& q, const RollingPhase& phase, Matrix5* stiffness,
                                      Matrix5* damping = nullptr) const;
  Vector5 contact_force_and_stiffness(const Vector5& q, double cage_angle_rad, Matrix5* stiffness) const {
    return contact_force_and_stiffness(q, RollingPhase{cage_angle_rad}, stiffness);
  }
  // Per-ball detail at a static configuration.
  std::vector<BallState> ball_states(const Vector5& q, const RollingPhase& phase) const;
  std::vector<BallState> ball_states(const Vector5& q, double cage_angle_rad) const {
    return ball_states(q, RollingPhase{cage_angle_rad});
  }
  // Contact deflection of each ball of a subset (without the spalls' dips: an upper bound).
  void deflections(const Vector5& q, const RollingPhase& phase, const BallArrays& balls, std::vector<double>* out,
                   bool include_spalls = true) const;
  // Splits the balls into those whose deflection, spalls left out, exceeds -margin_m and
  // the rest (spalls only remove deflection, so the rest stays clear of contact). Returns
  // the largest of those deflections over the rest (-infinity if none). When the split is
  // the one both sets already hold, they are left as they are (same generation: the
  // imperfection terms cached for them stay valid).
  double split_by_deflection(const Vector5& q, const RollingPhase& phase, double margin_m, BallArrays* near_contact,
                             BallArrays* clear) const;
  // Largest contact deflection over a subset (negative: all clear).
  double max_deflection(const Vector5& q, const RollingPhase& phase, const BallArrays& balls) const;
  // Largest distance of a moving-ring groove centre from the bearing centre, m.
  double max_lever_arm_m() const { return max_lever_arm_; }
  // Bound on how much any ball's imperfection offset (spalls left out) can change in dt
  // at these ring speeds, m.
  double max_offset_change_m(double inner_rad_s, double outer_rad_s, double dt) const;
  // Spin speed of the balls relative to the cage, rad/s.
  double ball_spin_speed_rad_s(double inner_rad_s, double outer_rad_s) const;

  // Nominal cage speed for the given ring speeds (docs/model.md section 7.2).
  double cage_speed_rad_s(double inner_rad_s, double outer_rad_s) const;
  // Inner and outer ring speeds (rad/s) for a speed of the rotating ring.
  void ring_speeds(double rotating_ring_rad_s, double* inner_rad_s, double* outer_rad_s) const;

 private:
  BearingConfig config_;
  HertzContact inner_contact_, outer_contact_;
  double contact_stiffness_ = 0.0;
  double groove_centre_distance_ = 0.0;
  double clearance_m_ = 0.0;
  // Radial coordinate of the moving ring's groove centre (outer ring: P_o, inner ring:
  // P_i), where its displacement and moment arms are taken.
  double groove_centre_radius_ = 0.0;
  double cos_a0_ = 1.0;
  double moving_sign_ = 1.0;
  // Per ball (structure of arrays, for the vectorized force loop).
  double max_lever_arm_ = 0.0;
  std::vector<double> base_azimuth_;
  BallArrays balls_;
  Imperfections imperfections_;
  // Identifies the per-ball offsets' content, for the cache of offsets_at.
  std::uint64_t stamp_ = 0;
  static std::uint64_t next_stamp();
  // Total constant and time-varying offsets of a subset at a phase, in a reused buffer.
  const double* offsets_at(const RollingPhase& phase, const BallArrays& balls, bool include_spalls = true) const;
  // The rows' groove-centre z are distinct (the force kernel tells a spall's row by it).
  bool rows_apart_axially_ = true;
  // Only race spalls vary the offsets (no waviness, roughness or ball spall), and the kernel
  // can tell their rows apart: the force kernel takes them as windows (set with the spalls).
  bool race_spalls_in_kernel_ = false;
  // Those windows made once with the spalls, for ring angles of zero: while the rings that
  // carry spalls stand there (a fixed ring, as the 6205's outer ring) and no spall grows, a
  // force evaluation takes them as they are (making them anew took a twentieth of the 6205's
  // instructions). Members, not a per-thread cache: the model is shared read-only by threads.
  static constexpr int kMaxKernelWindows = 4;
  Imperfections::SpallWindow standing_windows_[kMaxKernelWindows] = {};
  int standing_window_count_ = 0;  // 0: none kept
  bool windows_follow_outer_ = false, windows_follow_inner_ = false;
  void update_race_spalls_in_kernel();
  // The race spalls' windows at `phase` with their rows' z, into windows[0..count) (0: more
  // than kMaxKernelWindows, the offsets then carry the spalls).
  int make_kernel_windows(const RollingPhase& phase, Imperfections::SpallWindow* windows) const;
  // The kernel's windows at `phase` (into `scratch` unless the standing ones serve), *count.
  const Imperfections::SpallWindow* kernel_windows(const RollingPhase& phase, Imperfections::SpallWindow* scratch,
                                                   int* count) const;
};

// 6x6 Bushing stiffness (x, y, z, rx, ry, rz) with a zero row and column for rz.
Matrix6 bushing_matrix(const Matrix5& stiffness);

}  // namespace bearing_sim
