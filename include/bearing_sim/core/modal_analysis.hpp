#pragma once
// Natural frequencies and mode shapes of a rigid body on bearing stiffness: the modal
// comparison of the INS paper (its table 2; docs/model.md section 6.5), with and without the bearings'
// angular stiffness. Generalized eigenproblem K phi = w^2 M phi in the six rigid-body
// coordinates (x, y, z, rx, ry, rz) of the body's centre of mass, axes parallel to the
// bearing frame (z along the bearing axis).
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim {

using Vector6 = Eigen::Matrix<double, 6, 1>;

// The rigid bodies and bearing places a modal analysis accepts (bearing_tool modes, Python
// modes): from a gram to ten thousand tonnes (a bearing's own ring weighs more than the one,
// a ship's shaft line less than the other), inertias from a gram at 1 mm (1e-9 kg*m^2) to
// 1e9 kg*m^2, bearings within 100 m of the centre of mass. Beyond, K/m overflows or no
// machine is meant (a mass of 1e-300 kg gave "not finite" naming a mass never given).
constexpr double kMinBodyMassKg = 1e-3, kMaxBodyMassKg = 1e7;
constexpr double kMinBodyInertiaKgM2 = 1e-9, kMaxBodyInertiaKgM2 = 1e9;
constexpr double kMaxSupportDistanceM = 100.0;

struct RigidBody {
  double mass_kg = 0.0;
  Eigen::Vector3d inertia_kg_m2 = Eigen::Vector3d::Zero();  // principal, about the centre of mass: Ixx, Iyy, Izz
};

// One bearing as a 6x6 Bushing spring (bushing_matrix of the static stiffness) at a
// point of the body, relative to its centre of mass (m).
struct BushingSupport {
  Matrix6 stiffness = Matrix6::Zero();  // SI: N/m, N/rad, N*m/m, N*m/rad
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
};

struct ModalOptions {
  // Zero the rows and columns of the rotations (rx, ry, rz) of every bushing before
  // assembly: the "no angular stiffness" bearing model of the INS paper (translational
  // springs only, still acting at the bushing's position).
  bool zero_angular_stiffness = false;
};

struct Mode {
  double frequency_hz = 0.0;                  // 0 for a free (rigid-body) mode
  bool free = false;                          // eigenvalue below 1e-9 of the largest: unrestrained motion
  Vector6 shape = Vector6::Zero();            // mass-normalised (phi^T M phi = 1)
  Vector6 energy_fraction = Vector6::Zero();  // kinetic energy share of each coordinate, sums to 1
  int dominant_dof = 0;                       // index of the largest share
};

struct ModalResult {
  Matrix6 mass = Matrix6::Zero();
  Matrix6 stiffness = Matrix6::Zero();  // assembled, at the centre of mass
  std::vector<Mode> modes;              // ascending frequency
};

// Stiffness of a Bushing at `position` (relative to the centre of mass) in the body's
// centre-of-mass coordinates: T^T K T with the rigid-body map T = [I, -[r]x; 0, I].
Matrix6 transform_bushing(const Matrix6& bushing, const Eigen::Vector3d& position_m);

// Throws InvalidInputError for a mass, inertia or support position outside the limits
// above (naming the value and the limit), a non-symmetric or non-finite bushing, or no supports.
ModalResult solve_modes(const RigidBody& body, const std::vector<BushingSupport>& supports,
                        const ModalOptions& options = {});

// "x", "y", "z", "rx", "ry", "rz".
const char* rigid_dof_name(int dof);

}  // namespace bearing_sim
