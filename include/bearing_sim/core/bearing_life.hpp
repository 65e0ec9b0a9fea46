#pragma once
// Fatigue life (docs/model.md section 14; docs/health.md): ISO 281 basic rating life, a
// reference life in the manner of ISO/TS 16281 from the ball loads, and Palmgren-Miner
// damage over a load and speed history. Ball bearings only; sizes in the formulas of
// ISO 281 are in mm and N, everything at this interface is SI.
#include <vector>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/bearing_model.hpp"

namespace bearing_sim {

// Life data the bearing file does not carry (the file parser is shared; this stays apart).
struct LifeConfig {
  // Basic dynamic load rating C, N (catalogue value). 0: computed from the geometry by ISO 281.
  double dynamic_load_rating_N = 0.0;
  // b_m of ISO 281 for contemporary bearing steel: 1.3 for radial ball bearings.
  double material_factor = 1.3;
  // Life exponent p of L10 = (C/P)^p: 3 for ball bearings.
  double life_exponent = 3.0;
};

// ISO 281 Table 2 f_c for radial ball bearings at D_w cos(a) / D_pw, interpolated linearly;
// below 0.01 extrapolated as f_c(0.01) (ratio / 0.01)^0.3 (the slope of the theory there),
// above 0.40 held at the last value. double_row_deep_groove selects the second column.
double iso281_fc(double dw_cos_alpha_over_dpw, bool double_row_deep_groove);

// Reduction of f_c for groove radii above the 0.52 D_w (inner) and 0.53 D_w (outer) that
// ISO 281 Table 2 assumes, from the Lundberg-Palmgren closed form behind the table; 1 for
// radii at or below those (a tighter groove does not raise C).
double iso281_groove_radius_factor(const BearingConfig& bearing);

// C, N: the configured value, or b_m f_c (i cos a)^0.7 Z^(2/3) D_w^1.8 (D_w <= 25.4 mm),
// b_m f_c (i cos a)^0.7 Z^(2/3) 3.647 D_w^1.4 (above), D_w in mm, Z balls per row, f_c
// reduced by iso281_groove_radius_factor.
double basic_dynamic_load_rating_N(const BearingConfig& bearing, const LifeConfig& life = {});

// P = X Fr + Y Fa (ISO 281 Table 3), see docs/health.md for the rows used.
struct EquivalentLoad {
  double X = 1.0, Y = 0.0, e = 0.0;
  double load_N = 0.0;
};
// fr_N = radial force, fa_N = axial force (magnitudes; moments are not part of ISO 281 P).
EquivalentLoad equivalent_dynamic_load(const BearingConfig& bearing, double fr_N, double fa_N);

struct BasicRatingLife {
  double dynamic_load_rating_N = 0.0;  // C
  EquivalentLoad equivalent;           // P and its factors
  double life_million_rev = 0.0;       // L10 = (C/P)^p; infinity for P = 0
  double life_hours = 0.0;             // at the given relative ring speed; infinity at 0 speed
};
// From the load (Fx, Fy, Fz, ...): Fr = hypot(Fx, Fy), Fa = |Fz|; the relative ring speed in rad/s.
BasicRatingLife basic_rating_life(const BearingConfig& bearing, const Vector5& load, double relative_speed_rad_s,
                                  const LifeConfig& life = {});

// L10 = (C/P)^p million revolutions; infinity for P = 0.
double rating_life_million_rev(double dynamic_load_rating_N, double equivalent_load_N, double life_exponent = 3.0);

// Hours of a life in millions of revolutions at a speed (rad/s, sign ignored).
double life_hours(double life_million_rev, double speed_rad_s);

// --- Reference life in the manner of ISO/TS 16281 from the ball loads -----------------
// Per row and race: equivalent ball load Q_e = ((1/Z) sum Q_j^p)^(1/p) with p = 3 for the
// race that rotates relative to the load and p = 10/3 for the race that is stationary
// relative to it (Lundberg-Palmgren, as ISO/TS 16281 for point contact); the basic dynamic
// load rating of the contact Q_c (see the .cpp / docs/health.md); L_k = (Q_c/Q_e)^3 in
// millions of revolutions; combined L = (sum L_k^(-e))^(-1/e), e = 10/9.
struct RaceLife {
  int row = 0;
  Surface race = Surface::InnerRace;
  bool rotating_relative_to_load = false;
  double equivalent_ball_load_N = 0.0;  // Q_e
  double contact_rating_N = 0.0;        // Q_c
  double life_million_rev = 0.0;        // (Q_c / Q_e)^3
};
struct ReferenceLife {
  std::vector<RaceLife> races;    // row 0 inner, row 0 outer, row 1 inner, ...
  double life_million_rev = 0.0;  // combined
};
// Q_c of one ball/raceway contact, N.
double contact_dynamic_load_rating_N(const BearingConfig& bearing, Surface race, const LifeConfig& life = {});
// `balls` as from solve_static (load_N of every ball, row-major); the load is taken as fixed
// in the bearing frame, so the configured rotating ring rotates relative to it.
ReferenceLife reference_life(const BearingModel& model, const std::vector<BallState>& balls,
                             const LifeConfig& life = {});

// --- Palmgren-Miner damage --------------------------------------------------------------
// D = sum n_i / N_i over intervals of constant load and speed: n_i the revolutions in the
// interval, N_i the life at its load in revolutions (whichever life model gives it: the
// node uses the reference life).
class MinerDamage {
 public:
  // An interval of dt_s at relative ring speed (rad/s, sign ignored) under a load whose life
  // is life_million_rev (infinity: no damage). Throws InvalidInputError for a life <= 0,
  // a negative dt or non-finite values.
  void add(double life_million_rev, double speed_rad_s, double dt_s);
  double damage() const { return damage_; }
  double revolutions() const { return revolutions_; }
  double elapsed_s() const { return elapsed_s_; }
  // Damage per second in the last interval.
  double damage_rate_per_s() const { return rate_per_s_; }
  // (1 - D) at the current rate: seconds to D = 1; infinity at zero rate, 0 once D >= 1.
  double remaining_life_s() const;
  double remaining_life_hours() const { return remaining_life_s() / 3600.0; }
  void reset();

 private:
  double damage_ = 0.0, revolutions_ = 0.0, elapsed_s_ = 0.0, rate_per_s_ = 0.0;
};

}  // namespace bearing_sim
