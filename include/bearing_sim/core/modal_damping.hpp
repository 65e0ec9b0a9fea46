#pragma once
// Damping of the radial mode of the moving ring on its contacts (docs/model.md section 7.3):
// the ratio a per-contact damping c_n gives, and the c_n that gives a ratio.
#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim {

struct RadialMode {
  double omega_rad_s = 0.0;         // undamped, of M^-1 K at the static equilibrium
  Vector5 shape = Vector5::Zero();  // mass-normalised: shape^T M shape = 1
  // Kinetic energy share of the translation along the radial load (x without one), 0..1.
  double radial_share = 0.0;
  // zeta = c_n * ratio_per_damping: phi^T G phi / (2 omega), G = C / c_n the contacts' geometry.
  double ratio_per_damping_m_per_Ns = 0.0;
};

// The radial mode at the static equilibrium under `load`: of the undamped modes, the one
// with the largest kinetic energy share in translation along the radial load. Throws
// LoadNotCarriedError for a load without equilibrium and InvalidInputError when the ring has
// no rotating_mass_kg or no radial stiffness there (no ball in contact).
RadialMode radial_mode(const BearingModel& model, const Vector5& load);

// Modal damping ratio of the radial mode with the model's contact_damping_Ns_per_m.
double radial_mode_damping_ratio(const BearingModel& model, const Vector5& load);

// c_n (N*s/m per loaded contact) that gives the radial mode the damping ratio `zeta` (in
// [0, 1)): c_n = 2 omega zeta / (phi^T G phi). Linear in zeta.
double contact_damping_for_ratio(const BearingModel& model, const Vector5& load, double zeta);

}  // namespace bearing_sim
