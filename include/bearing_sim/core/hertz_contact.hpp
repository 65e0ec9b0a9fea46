#pragma once
// Hamrock-Brewe approximation of the Hertz point contact (docs/model.md section 4).

namespace bearing_sim {

struct HertzContact {
  double curvature_sum_per_m = 0.0;   // 1/R = 1/Rx + 1/Ry
  double radius_ratio = 0.0;          // ar = Ry / Rx
  double ellipticity = 0.0;           // k
  double elliptic_E = 0.0;            // second-kind elliptic integral approximation
  double elliptic_F = 0.0;            // first-kind elliptic integral approximation
  double effective_modulus_Pa = 0.0;  // E' = E / (1 - nu^2) for two bodies of the same steel
  double stiffness_N_per_m15 = 0.0;   // K in Q = K delta^1.5

  // Maximum (central) contact pressure for a normal load Q.
  double max_pressure_Pa(double load_N) const;
  // Semi-axes of the contact ellipse for a normal load Q.
  double semi_major_m(double load_N) const;
  double semi_minor_m(double load_N) const;
};

// Contact of a ball of diameter d with a raceway whose rolling-direction radius of
// curvature is given by 1/Rx (ball side included) and transverse by 1/Ry.
HertzContact hertz_contact(double inv_rx, double inv_ry, double youngs_modulus_Pa, double poisson_ratio);

HertzContact inner_race_contact(double ball_diameter_m, double pitch_diameter_m, double contact_angle_rad,
                                double inner_groove_curvature, double youngs_modulus_Pa, double poisson_ratio);
HertzContact outer_race_contact(double ball_diameter_m, double pitch_diameter_m, double contact_angle_rad,
                                double outer_groove_curvature, double youngs_modulus_Pa, double poisson_ratio);

// Inner and outer contacts in series: Kn = ((1/Ki)^(2/3) + (1/Ko)^(2/3))^(-3/2).
double series_stiffness(double k_inner, double k_outer);

}  // namespace bearing_sim
