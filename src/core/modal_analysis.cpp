// Rigid body on Bushing springs: K phi = w^2 M phi (see modal_analysis.hpp).
#include "bearing_sim/core/modal_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {
namespace {

void require_within(double v, double min, double max, const std::string& what, const char* unit) {
  if (!(v >= min && v <= max)) {  // NaN fails too
    std::ostringstream os;
    os << "modal analysis: " << what << " " << v << " " << unit << " is outside [" << min << ", " << max << "] "
       << unit;
    throw InvalidInputError(os.str());
  }
}

}  // namespace

const char* rigid_dof_name(int dof) {
  static const char* const names[6] = {"x", "y", "z", "rx", "ry", "rz"};
  return (dof >= 0 && dof < 6) ? names[dof] : "?";
}

Matrix6 transform_bushing(const Matrix6& bushing, const Eigen::Vector3d& r) {
  // Displacement of the bushing point: u_p = t + rot x r = t - [r]x rot.
  Matrix6 t = Matrix6::Identity();
  Eigen::Matrix3d rx;
  rx << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  t.block<3, 3>(0, 3) = -rx;
  return t.transpose() * bushing * t;
}

ModalResult solve_modes(const RigidBody& body, const std::vector<BushingSupport>& supports,
                        const ModalOptions& options) {
  require_within(body.mass_kg, kMinBodyMassKg, kMaxBodyMassKg, "mass", "kg");
  const char* const axes[3] = {"Ixx", "Iyy", "Izz"};
  for (int a = 0; a < 3; ++a)
    require_within(body.inertia_kg_m2[a], kMinBodyInertiaKgM2, kMaxBodyInertiaKgM2, std::string("inertia ") + axes[a],
                   "kg*m^2");
  if (supports.empty()) throw InvalidInputError("modal analysis: no bearing (Bushing) supports given");
  for (std::size_t i = 0; i < supports.size(); ++i)
    for (int a = 0; a < 3; ++a)
      require_within(supports[i].position_m[a], -kMaxSupportDistanceM, kMaxSupportDistanceM,
                     "support " + std::to_string(i + 1) + " position " + "xyz"[a], "m");

  ModalResult result;
  result.mass.diagonal() << body.mass_kg, body.mass_kg, body.mass_kg, body.inertia_kg_m2.x(), body.inertia_kg_m2.y(),
      body.inertia_kg_m2.z();
  for (std::size_t i = 0; i < supports.size(); ++i) {
    Matrix6 k = supports[i].stiffness;
    if (!k.allFinite() || !supports[i].position_m.allFinite())
      throw InvalidInputError("modal analysis: support " + std::to_string(i + 1) + " has non-finite values");
    const double scale = std::max(k.cwiseAbs().maxCoeff(), 1e-300);
    if ((k - k.transpose()).cwiseAbs().maxCoeff() > 1e-6 * scale)
      throw InvalidInputError("modal analysis: the stiffness of support " + std::to_string(i + 1) +
                              " is not symmetric");
    k = 0.5 * (k + k.transpose());
    if (options.zero_angular_stiffness) {
      k.block<3, 6>(3, 0).setZero();
      k.block<6, 3>(0, 3).setZero();
    }
    result.stiffness += transform_bushing(k, supports[i].position_m);
  }

  Eigen::GeneralizedSelfAdjointEigenSolver<Matrix6> solver(result.stiffness, result.mass);
  if (solver.info() != Eigen::Success || !solver.eigenvalues().allFinite())
    throw InvalidInputError(
        "modal analysis: the eigenvalues K/M are not finite numbers (a stiffness overflows "
        "against the mass and inertia given)");
  const Vector6 lambda = solver.eigenvalues();
  const double lambda_max = std::max(lambda.cwiseAbs().maxCoeff(), 1e-300);
  for (int i = 0; i < 6; ++i) {
    Mode m;
    m.free = lambda[i] < 1e-9 * lambda_max;
    m.frequency_hz = m.free ? 0.0 : std::sqrt(lambda[i]) / kTwoPi;
    m.shape = solver.eigenvectors().col(i);
    const double norm = std::sqrt(m.shape.dot(result.mass * m.shape));
    if (norm > 0.0) m.shape /= norm;
    // Sign: the largest component positive, for reproducible output.
    Eigen::Index big = 0;
    m.shape.cwiseAbs().maxCoeff(&big);
    if (m.shape[big] < 0.0) m.shape = -m.shape;
    const Vector6 e = m.shape.cwiseProduct(result.mass * m.shape);
    m.energy_fraction = e / std::max(e.sum(), 1e-300);
    Eigen::Index dom = 0;
    m.energy_fraction.maxCoeff(&dom);
    m.dominant_dof = static_cast<int>(dom);
    result.modes.push_back(m);
  }
  return result;
}

}  // namespace bearing_sim
