// Radial mode and its damping ratio (docs/model.md section 7.3).
#include "bearing_sim/core/modal_damping.hpp"

#include <cmath>
#include <sstream>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/symmetric_eigen.hpp"

namespace bearing_sim {

RadialMode radial_mode(const BearingModel& model, const Vector5& load) {
  if (!model.config().has_dynamics())
    throw InvalidInputError("the radial mode needs the moving mass (rotating_mass_kg)");
  const StaticSolution s = solve_static(model, load);
  // G = C / c_n: the damping matrix of a unit damper per loaded contact. A copy of the bearing
  // with c_n = 1 keeps G independent of the damping the model happens to have (even 0).
  BearingConfig unit = model.config();
  unit.contact_damping_Ns_per_m = 1.0;
  BearingModel unit_model(unit);
  unit_model.set_deflection_offsets(model.deflection_offsets());
  Matrix5 g;
  unit_model.contact_force_and_stiffness(s.displacement, RollingPhase{}, nullptr, &g);

  const Matrix5 m = model.mass_matrix();
  const SymmetricEigen5 eigen = generalized_symmetric_eigen(0.5 * (s.stiffness + s.stiffness.transpose()), m, true);
  Eigen::Vector2d radial(load[0], load[1]);
  radial = radial.norm() > 0.0 ? Eigen::Vector2d(radial.normalized()) : Eigen::Vector2d(1.0, 0.0);
  const double lambda_max = eigen.eigenvalues.cwiseAbs().maxCoeff();
  RadialMode best;
  for (int i = 0; i < 5; ++i) {
    const double lambda = eigen.eigenvalues[i];
    if (!(lambda > 1e-9 * lambda_max)) continue;  // no stiffness in this shape
    Vector5 phi = eigen.eigenvectors.col(i);
    phi /= std::sqrt(phi.dot(m * phi));
    const double along = radial.x() * phi[0] + radial.y() * phi[1];
    const double share = m(0, 0) * along * along;  // translation's share, of a mass-normalized shape
    if (share > best.radial_share) {
      best.radial_share = share;
      best.omega_rad_s = std::sqrt(lambda);
      best.shape = phi;
    }
  }
  // A share this small is a tilt or axial mode with a trace of radial motion, not a radial mode.
  constexpr double kMinRadialShare = 0.1;
  if (best.radial_share < kMinRadialShare) {
    std::ostringstream why;
    why << "no radial mode at the load (" << load.transpose()
        << "): the ring has no radial stiffness there (no ball in contact along the load?)";
    throw InvalidInputError(why.str());
  }
  best.ratio_per_damping_m_per_Ns = best.shape.dot(g * best.shape) / (2.0 * best.omega_rad_s);
  return best;
}

double radial_mode_damping_ratio(const BearingModel& model, const Vector5& load) {
  return model.config().contact_damping_Ns_per_m * radial_mode(model, load).ratio_per_damping_m_per_Ns;
}

double contact_damping_for_ratio(const BearingModel& model, const Vector5& load, double zeta) {
  if (!(zeta >= 0.0 && zeta < 1.0)) {
    std::ostringstream why;
    why << "modal damping ratio " << zeta << " refused: must be in [0, 1) (1 is critical damping)";
    throw InvalidInputError(why.str());
  }
  const RadialMode mode = radial_mode(model, load);
  if (!(mode.ratio_per_damping_m_per_Ns > 0.0))
    throw InvalidInputError("the radial mode moves no loaded contact along its normal: no contact damping reaches it");
  return zeta / mode.ratio_per_damping_m_per_Ns;
}

}  // namespace bearing_sim
