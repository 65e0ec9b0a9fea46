#include "bearing_sim/core/bearing_life.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"

namespace bearing_sim {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// ISO 281:2007 Table 2, radial ball bearings: D_w cos(a) / D_pw and f_c for
// (1) single-row radial and single/double-row angular contact ball bearings,
// (2) double-row deep groove ball bearings.
constexpr double kFcRatio[] = {0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.10, 0.12, 0.14, 0.16,
                               0.18, 0.20, 0.22, 0.24, 0.26, 0.28, 0.30, 0.32, 0.34, 0.36, 0.38, 0.40};
constexpr double kFcSingle[] = {29.1, 35.8, 40.3, 43.8, 46.7, 49.1, 51.1, 52.8, 54.3, 55.5, 57.5, 58.8, 59.6,
                                59.9, 59.9, 59.6, 59.0, 58.2, 57.1, 56.0, 54.6, 53.2, 51.7, 50.0, 48.4};
constexpr double kFcDouble[] = {27.5, 33.9, 38.2, 41.5, 44.2, 46.5, 48.4, 50.0, 51.4, 52.6, 54.5, 55.7, 56.5,
                                56.8, 56.8, 56.5, 55.9, 55.1, 54.1, 53.0, 51.8, 50.4, 48.9, 47.4, 45.8};

// ISO 281 Table 3, deep groove (a = 0): f0 Fa / C0r = Fa / (i Z D_w^2 cos a) in N/mm^2
// (C0r = f0 i Z D_w^2 cos a by ISO 76, so f0 cancels), e and Y for Fa/Fr > e (X = 0.56).
constexpr double kDgArg[] = {0.172, 0.345, 0.689, 1.03, 1.38, 2.07, 3.45, 5.17, 6.89};
constexpr double kDgE[] = {0.19, 0.22, 0.26, 0.28, 0.30, 0.34, 0.38, 0.42, 0.44};
constexpr double kDgY[] = {2.30, 1.99, 1.71, 1.55, 1.45, 1.31, 1.15, 1.04, 1.00};

// ISO 281 Table 3, angular contact 20..45 deg: e; single row X, Y for Fa/Fr > e;
// double row (and pairs DB/DF) Y1 for Fa/Fr <= e (X = 1), X2, Y2 for Fa/Fr > e.
constexpr double kAcAngle[] = {20, 25, 30, 35, 40, 45};
constexpr double kAcE[] = {0.57, 0.68, 0.80, 0.95, 1.14, 1.34};
constexpr double kAcX1[] = {0.43, 0.41, 0.39, 0.37, 0.35, 0.33};
constexpr double kAcY1[] = {1.00, 0.87, 0.76, 0.66, 0.57, 0.50};
constexpr double kAcY1Double[] = {1.09, 0.92, 0.78, 0.66, 0.55, 0.47};
constexpr double kAcX2Double[] = {0.70, 0.67, 0.63, 0.60, 0.57, 0.54};
constexpr double kAcY2Double[] = {1.63, 1.41, 1.24, 1.07, 0.93, 0.81};

// Linear interpolation in a table, held at the ends.
template <std::size_t N>
double interpolate(const double (&x)[N], const double (&y)[N], double v) {
  if (v <= x[0]) return y[0];
  if (v >= x[N - 1]) return y[N - 1];
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(std::begin(x), std::end(x), v) - std::begin(x));
  const double t = (v - x[i - 1]) / (x[i] - x[i - 1]);
  return y[i - 1] + t * (y[i] - y[i - 1]);
}

void check_life_config(const LifeConfig& l) {
  if (!(l.dynamic_load_rating_N >= 0.0) || !std::isfinite(l.dynamic_load_rating_N))
    throw InvalidInputError("life: the dynamic load rating must be >= 0 N (0: from the geometry)");
  if (!(l.material_factor > 0.0) || !(l.life_exponent > 0.0))
    throw InvalidInputError("life: the material factor and the life exponent must be > 0");
}
}  // namespace

double iso281_fc(double ratio, bool double_row_deep_groove) {
  if (!(ratio > 0.0)) throw InvalidInputError("ISO 281 f_c: D_w cos(a) / D_pw must be > 0");
  const auto& table = double_row_deep_groove ? kFcDouble : kFcSingle;
  if (ratio < kFcRatio[0]) return table[0] * std::pow(ratio / kFcRatio[0], 0.3);
  return interpolate(kFcRatio, table, ratio);
}

double iso281_groove_radius_factor(const BearingConfig& b) {
  // ISO 281 Table 2 holds for groove radii up to 0.52 D_w (inner) and 0.53 D_w (outer); a
  // wider groove lowers C, a tighter one does not raise it. The factor is the closed form
  // behind the table (Lundberg-Palmgren, ISO/TR 1281-1) at the actual radii over the same at
  // the table's: f_c ~ Q_ci [1 + (Q_ci/Q_ce)^(10/3)]^(-0.3), the inner and outer contact
  // ratings combined into the ring's rating.
  const auto ring_rating = [&](double fi, double fe) {
    BearingConfig g = b;
    g.inner_groove_curvature = fi;
    g.outer_groove_curvature = fe;
    const double qi = contact_dynamic_load_rating_N(g, Surface::InnerRace);
    const double qe = contact_dynamic_load_rating_N(g, Surface::OuterRace);
    return qi * std::pow(1.0 + std::pow(qi / qe, 10.0 / 3.0), -0.3);
  };
  constexpr double kTableInner = 0.52, kTableOuter = 0.53;
  return ring_rating(std::max(b.inner_groove_curvature, kTableInner), std::max(b.outer_groove_curvature, kTableOuter)) /
         ring_rating(kTableInner, kTableOuter);
}

double basic_dynamic_load_rating_N(const BearingConfig& b, const LifeConfig& life) {
  check_life_config(life);
  if (life.dynamic_load_rating_N > 0.0) return life.dynamic_load_rating_N;
  const double dw_mm = b.ball_diameter_m * 1e3;
  const double cos_a = std::cos(b.contact_angle_rad);
  const double ratio = b.ball_diameter_m * cos_a / b.pitch_diameter_m;
  const bool double_row_deep_groove = b.rows == 2 && b.contact_angle_rad == 0.0;
  const double fc = iso281_fc(ratio, double_row_deep_groove);
  const double common = life.material_factor * fc * iso281_groove_radius_factor(b) * std::pow(b.rows * cos_a, 0.7) *
                        std::pow(static_cast<double>(b.balls_per_row), 2.0 / 3.0);
  return dw_mm <= 25.4 ? common * std::pow(dw_mm, 1.8) : common * 3.647 * std::pow(dw_mm, 1.4);
}

EquivalentLoad equivalent_dynamic_load(const BearingConfig& b, double fr, double fa) {
  if (!(fr >= 0.0) || !(fa >= 0.0) || !std::isfinite(fr) || !std::isfinite(fa))
    throw InvalidInputError("equivalent load: Fr and Fa must be finite and >= 0");
  EquivalentLoad q;
  const double alpha_deg = b.contact_angle_rad * 180.0 / kPi;
  const double ratio = fr > 0.0 ? fa / fr : kInf;
  if (alpha_deg < 10.0) {
    // Deep groove table (its argument carries cos a, so small angles stay close).
    const double dw_mm = b.ball_diameter_m * 1e3;
    const double arg = fa / (b.rows * b.balls_per_row * dw_mm * dw_mm * std::cos(b.contact_angle_rad));
    q.e = interpolate(kDgArg, kDgE, arg);
    if (ratio > q.e) {
      q.X = 0.56;
      q.Y = interpolate(kDgArg, kDgY, arg);
    }
  } else {
    // Angular contact: 10..20 deg use the 20 deg row (the 5-15 deg rows of ISO 281 need
    // C0r); 20..45 interpolated; beyond 45 the 45 deg row.
    const double a = std::clamp(alpha_deg, 20.0, 45.0);
    q.e = interpolate(kAcAngle, kAcE, a);
    if (b.rows == 2) {
      if (ratio <= q.e) {
        q.Y = interpolate(kAcAngle, kAcY1Double, a);
      } else {
        q.X = interpolate(kAcAngle, kAcX2Double, a);
        q.Y = interpolate(kAcAngle, kAcY2Double, a);
      }
    } else if (ratio > q.e) {
      q.X = interpolate(kAcAngle, kAcX1, a);
      q.Y = interpolate(kAcAngle, kAcY1, a);
    }
  }
  q.load_N = q.X * fr + q.Y * fa;
  return q;
}

double rating_life_million_rev(double rating_N, double load_N, double exponent) {
  return load_N > 0.0 ? std::pow(rating_N / load_N, exponent) : kInf;
}

double life_hours(double life_million_rev, double speed_rad_s) {
  const double rev_per_hour = std::abs(speed_rad_s) / (2.0 * kPi) * 3600.0;
  if (rev_per_hour == 0.0) return kInf;
  return life_million_rev * 1e6 / rev_per_hour;
}

BasicRatingLife basic_rating_life(const BearingConfig& b, const Vector5& load, double speed_rad_s,
                                  const LifeConfig& life) {
  if (!load.allFinite() || !std::isfinite(speed_rad_s)) throw InvalidInputError("life: load and speed must be finite");
  BasicRatingLife r;
  r.dynamic_load_rating_N = basic_dynamic_load_rating_N(b, life);
  r.equivalent = equivalent_dynamic_load(b, std::hypot(load[0], load[1]), std::abs(load[2]));
  r.life_million_rev = rating_life_million_rev(r.dynamic_load_rating_N, r.equivalent.load_N, life.life_exponent);
  r.life_hours = life_hours(r.life_million_rev, speed_rad_s);
  return r;
}

// Lundberg-Palmgren contact rating as in ISO/TS 16281 and the background of ISO 281
// (ISO/TR 1281-1), D_w in mm, result in N:
//   Q_c = 98.1 lambda b_m (2f/(2f-1))^0.41 (1 -+ g)^1.39 / (1 +- g)^(1/3) (D_w/D_pw)^0.3 D_w^1.8 Z^(-1/3)
// upper signs inner race, lower outer race, g = D_w cos(a)/D_pw, lambda = 0.95 the
// reduction factor of ISO 281 for radial ball bearings. With the ISO 281 load distribution
// (0.407 = J_r/J_1 at epsilon = 0.5) this gives C_i = 0.407 Q_ci Z cos a, the analytic f_c
// behind ISO 281 Table 2 (37.91 = 0.407 x 98.1 x 0.95).
double contact_dynamic_load_rating_N(const BearingConfig& b, Surface race, const LifeConfig& life) {
  check_life_config(life);
  if (race == Surface::Ball) throw InvalidInputError("contact rating: a raceway (inner or outer) is needed");
  constexpr double kLambda = 0.95;
  const double dw_mm = b.ball_diameter_m * 1e3;
  const double g = b.ball_diameter_m * std::cos(b.contact_angle_rad) / b.pitch_diameter_m;
  const bool inner = race == Surface::InnerRace;
  const double f = inner ? b.inner_groove_curvature : b.outer_groove_curvature;
  const double conformity = std::pow(2.0 * f / (2.0 * f - 1.0), 0.41);
  const double shape =
      inner ? std::pow(1.0 - g, 1.39) / std::cbrt(1.0 + g) : std::pow(1.0 + g, 1.39) / std::cbrt(1.0 - g);
  return 98.1 * kLambda * life.material_factor * conformity * shape *
         std::pow(b.ball_diameter_m / b.pitch_diameter_m, 0.3) * std::pow(dw_mm, 1.8) /
         std::cbrt(static_cast<double>(b.balls_per_row));
}

ReferenceLife reference_life(const BearingModel& model, const std::vector<BallState>& balls, const LifeConfig& life) {
  const BearingConfig& b = model.config();
  const int z = b.balls_per_row;
  if (static_cast<int>(balls.size()) != b.rows * z)
    throw InvalidInputError("reference life: one ball state per ball expected");
  const bool inner_rotates = b.rotating_ring == RotatingRing::Inner;
  constexpr double kWeibull = 10.0 / 9.0;  // e, Weibull slope of ball bearings
  ReferenceLife r;
  double sum = 0.0;
  for (int row = 0; row < b.rows; ++row) {
    for (Surface race : {Surface::InnerRace, Surface::OuterRace}) {
      RaceLife k;
      k.row = row;
      k.race = race;
      k.rotating_relative_to_load = (race == Surface::InnerRace) == inner_rotates;
      const double p = k.rotating_relative_to_load ? 3.0 : 10.0 / 3.0;
      double s = 0.0;
      for (const BallState& ball : balls) {
        if (ball.row != row) continue;
        if (!(ball.load_N >= 0.0) || !std::isfinite(ball.load_N))
          throw InvalidInputError("reference life: ball loads must be finite and >= 0");
        s += std::pow(ball.load_N, p);
      }
      k.equivalent_ball_load_N = std::pow(s / z, 1.0 / p);
      k.contact_rating_N = contact_dynamic_load_rating_N(b, race, life);
      k.life_million_rev =
          k.equivalent_ball_load_N > 0.0 ? std::pow(k.contact_rating_N / k.equivalent_ball_load_N, 3.0) : kInf;
      if (std::isfinite(k.life_million_rev)) sum += std::pow(k.life_million_rev, -kWeibull);
      r.races.push_back(k);
    }
  }
  r.life_million_rev = sum > 0.0 ? std::pow(sum, -1.0 / kWeibull) : kInf;
  return r;
}

void MinerDamage::add(double life_million_rev, double speed_rad_s, double dt_s) {
  if (!(life_million_rev > 0.0) || !std::isfinite(speed_rad_s) || !(dt_s >= 0.0) || !std::isfinite(dt_s))
    throw InvalidInputError("Miner damage: a life > 0, a finite speed and dt >= 0 s expected");
  const double revs = std::abs(speed_rad_s) / (2.0 * kPi) * dt_s;
  const double per_rev = 1e-6 / life_million_rev;  // 0 for an infinite life
  damage_ += revs * per_rev;
  revolutions_ += revs;
  elapsed_s_ += dt_s;
  if (dt_s > 0.0) rate_per_s_ = revs * per_rev / dt_s;
}

double MinerDamage::remaining_life_s() const {
  if (damage_ >= 1.0) return 0.0;
  if (rate_per_s_ <= 0.0) return kInf;
  return (1.0 - damage_) / rate_per_s_;
}

void MinerDamage::reset() { damage_ = revolutions_ = elapsed_s_ = rate_per_s_ = 0.0; }

}  // namespace bearing_sim
