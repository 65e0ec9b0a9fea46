#include "bearing_sim/core/hertz_contact.hpp"

#include <cmath>

#include "bearing_sim/core/constants.hpp"

namespace bearing_sim {

HertzContact hertz_contact(double inv_rx, double inv_ry, double youngs_modulus_Pa, double poisson_ratio) {
  HertzContact c;
  c.curvature_sum_per_m = inv_rx + inv_ry;
  c.radius_ratio = inv_rx / inv_ry;  // Ry / Rx
  c.ellipticity = 1.0339 * std::pow(c.radius_ratio, 0.636);
  c.elliptic_E = 1.0003 + 0.5968 / c.radius_ratio;
  c.elliptic_F = 1.5277 + 0.6023 * std::log(c.radius_ratio);
  c.effective_modulus_Pa = youngs_modulus_Pa / (1.0 - poisson_ratio * poisson_ratio);
  const double R = 1.0 / c.curvature_sum_per_m;
  c.stiffness_N_per_m15 = kPi * c.ellipticity * c.effective_modulus_Pa *
                          std::sqrt(2.0 * c.elliptic_E * R / (9.0 * std::pow(c.elliptic_F, 3)));
  return c;
}

double HertzContact::semi_major_m(double load_N) const {
  const double R = 1.0 / curvature_sum_per_m;
  return std::cbrt(6.0 * ellipticity * ellipticity * elliptic_E * load_N * R / (kPi * effective_modulus_Pa));
}

double HertzContact::semi_minor_m(double load_N) const {
  const double R = 1.0 / curvature_sum_per_m;
  return std::cbrt(6.0 * elliptic_E * load_N * R / (kPi * ellipticity * effective_modulus_Pa));
}

double HertzContact::max_pressure_Pa(double load_N) const {
  if (load_N <= 0.0) return 0.0;
  return 3.0 * load_N / (2.0 * kPi * semi_major_m(load_N) * semi_minor_m(load_N));
}

HertzContact inner_race_contact(double d, double dm, double a0, double fi, double E, double nu) {
  const double gamma = d * std::cos(a0) / dm;
  const double inv_rx = 2.0 / d + 2.0 * std::cos(a0) / (dm * (1.0 - gamma));
  const double inv_ry = 2.0 / d - 1.0 / (fi * d);
  return hertz_contact(inv_rx, inv_ry, E, nu);
}

HertzContact outer_race_contact(double d, double dm, double a0, double fo, double E, double nu) {
  const double gamma = d * std::cos(a0) / dm;
  const double inv_rx = 2.0 / d - 2.0 * std::cos(a0) / (dm * (1.0 + gamma));
  const double inv_ry = 2.0 / d - 1.0 / (fo * d);
  return hertz_contact(inv_rx, inv_ry, E, nu);
}

double series_stiffness(double k_inner, double k_outer) {
  return std::pow(std::pow(1.0 / k_inner, 2.0 / 3.0) + std::pow(1.0 / k_outer, 2.0 / 3.0), -1.5);
}

}  // namespace bearing_sim
