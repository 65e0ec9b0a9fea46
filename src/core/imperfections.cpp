#include "bearing_sim/core/imperfections.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <random>
#include <sstream>

#include <unsupported/Eigen/FFT>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "harmonic_sums.hpp"
#include "smooth_noise.hpp"

namespace bearing_sim {
namespace {
// Round to nearest, ties to even: std::nearbyint in the default rounding mode, bit for bit,
// without its library call (the sum's rounding does it; |x| < 2^51).
inline double round_to_nearest(double x) {
  constexpr double kShift = 6755399441055744.0;  // 1.5 * 2^52
  return (x + kShift) - kShift;
}

// std::floor and std::ceil of |x| < 2^62, as integers, without their library calls.
inline long floor_to_long(double x) {
  const long t = static_cast<long>(x);  // truncates towards zero
  return static_cast<double>(t) > x ? t - 1 : t;
}
inline long ceil_to_long(double x) {
  const long t = static_cast<long>(x);
  return static_cast<double>(t) < x ? t + 1 : t;
}

// Angle of the ring that carries a race surface (outer race: outer ring, else inner ring).
inline double ring_angle(const RollingPhase& phase, Surface race) {
  return race == Surface::OuterRace ? phase.outer_ring : phase.inner_ring;
}

// Dip of a spall centred at 0 of angular width w, at angle x (|x| < w/2): a half-sine of the
// effective depth (rounded edges), or with sharp edges the ball's drop pivoting on the nearer
// edge, geometric_depth (1 - 2|x| / w)^2, at most the effective depth (the spall's floor).
// Sharp edges with a rim of height h and angular width r: -h sin^2(pi (|x| - w/2) / r) for
// w/2 <= |x| < w/2 + r (the rim raises the ball).
// A round pit's rim is a ring whose crest circles the pit at c = w/2 + r/2: inside it the ball
// rides the crest where the ring passes beside the contact's centre line, sqrt(c^2 - x^2)
// across, and keeps h - ring_drop (c^2 - x^2) of the lift (ring_drop: the across-track gap
// per rad^2 of the race, across_drop(2 R)), unless the pit's own drop is the smaller.
inline double spall_dip(double x, double angular_width, double depth, bool sharp_edges, double geometric_depth,
                        double rim_height = 0.0, double rim_angle = 0.0, double ring_drop = 0.0) {
  const double ax = std::abs(x), half = 0.5 * angular_width;
  const auto pivoting_drop = [&] {
    const double u = 1.0 - ax / half;
    return std::min(depth, geometric_depth * u * u);
  };
  const double crest = half + 0.5 * rim_angle;
  if (ring_drop > 0.0 && ax < crest)
    return std::min(ring_drop * (crest * crest - ax * ax) - rim_height, ax < half ? pivoting_drop() : 0.0);
  if (!(ax < half)) {
    if (!(rim_height > 0.0 && ax < half + rim_angle)) return 0.0;
    if (half == 0.0) {  // a ring rim passed beside its pit: one bump, 2 r long
      const double c = std::cos(0.5 * kPi * ax / rim_angle);
      return -rim_height * c * c;
    }
    const double v = std::sin(kPi * (ax - half) / rim_angle);
    return -rim_height * v * v;
  }
  if (!sharp_edges) return depth * std::cos(kPi * x / angular_width);
  return pivoting_drop();
}
}  // namespace

const char* surface_name(Surface s) {
  switch (s) {
    case Surface::OuterRace:
      return "outer_race";
    case Surface::InnerRace:
      return "inner_race";
    case Surface::Ball:
      return "ball";
  }
  return "?";
}

Surface parse_surface(const std::string& name) {
  if (name == "outer_race") return Surface::OuterRace;
  if (name == "inner_race") return Surface::InnerRace;
  if (name == "ball") return Surface::Ball;
  throw InvalidInputError("surface must be outer_race, inner_race or ball, got '" + name + "'");
}

Imperfections::Imperfections(const ImperfectionSpec& spec, const Geometry& g) : spec_(spec), geometry_(g) {
  const int n_balls = g.rows * g.balls_per_row;
  if (static_cast<int>(g.base_azimuth.size()) != n_balls)
    throw InvalidInputError("imperfections: one base azimuth per ball expected");
  std::mt19937_64 rng(spec.seed);

  ball_diameter_deviation_.assign(n_balls, 0.0);
  if (spec.ball_diameter_variation_m > 0.0) {
    std::normal_distribution<double> normal(0.0, spec.ball_diameter_variation_m);
    for (double& dev : ball_diameter_deviation_) dev = normal(rng);
  }
  // How far the balls sit from even spacing relative to ball 0 of their row, for the
  // spall's index search.
  const double pitch = kTwoPi / g.balls_per_row;
  for (int row = 0; row < g.rows; ++row)
    for (int j = 0; j < g.balls_per_row; ++j)
      max_spacing_error_ = std::max(
          max_spacing_error_,
          std::abs(std::remainder(
              g.base_azimuth[row * g.balls_per_row + j] - g.base_azimuth[row * g.balls_per_row] - j * pitch, kTwoPi)));
  ball_phase_.resize(n_balls);
  std::uniform_real_distribution<double> uniform_angle(0.0, kTwoPi);
  for (double& p : ball_phase_) p = uniform_angle(rng);

  const auto check_row = [&g](int row, const char* what) {
    if (row < -1 || row >= g.rows)
      throw InvalidInputError(std::string(what) + ": row " + std::to_string(row) + " is not a row of the bearing (" +
                              (g.rows == 1 ? "0" : "0 or 1") + ")");
  };
  check_row(spec.roughness_row, "roughness");
  for (const Waviness& w : spec.waviness) {
    check_row(w.row, "waviness");
    Harmonic h{w.surface, w.order, w.amplitude_m, {}, {}};
    if (w.surface == Surface::Ball) {
      // The diameter along the contact line changes by r(psi) + r(psi + pi): 2 a cos(k psi + p)
      // for even orders, nothing for odd ones.
      if (w.order % 2 != 0) continue;
      h.amplitude_m = 2.0 * w.amplitude_m;
    }
    for (int b = 0; b < n_balls; ++b) {
      const double angle = w.surface == Surface::Ball ? ball_phase_[b] : g.base_azimuth[b];
      // A harmonic of one row: zero terms for the other row's balls (no test in the loop).
      const bool on_row = w.row < 0 || b / g.balls_per_row == w.row;
      h.cos_phase.push_back(on_row ? std::cos(w.order * angle + w.phase_rad) : 0.0);
      h.sin_phase.push_back(on_row ? std::sin(w.order * angle + w.phase_rad) : 0.0);
    }
    const int surface = static_cast<int>(w.surface);
    slope_[surface] += h.amplitude_m * w.order;
    peak_to_peak_[surface] += 2.0 * h.amplitude_m;
    (w.surface == Surface::Ball ? ball_waviness_ : race_waviness_).push_back(std::move(h));
  }
  for (const auto* harmonics : {&race_waviness_, &ball_waviness_})
    for (const Harmonic& h : *harmonics) waviness_amplitudes_.push_back(h.amplitude_m);

  // Roughness: random-phase harmonics of equal amplitude between orders Z and N/4 on each
  // race, scaled to the RMS asked for, tabulated for linear interpolation.
  if (spec.roughness_rms_m > 0.0) {
    has_roughness_ = true;
    roughness_row_ = spec.roughness_row;
    const int k_min = std::max(2, g.balls_per_row), k_max = kProfilePoints / 4;
    for (int race = 0; race < 2; ++race) {
      std::vector<std::complex<double>> spectrum(kProfilePoints, 0.0);
      for (int k = k_min; k <= k_max; ++k) {
        spectrum[k] = std::polar(1.0, uniform_angle(rng));
        spectrum[kProfilePoints - k] = std::conj(spectrum[k]);
      }
      std::vector<double> profile;
      Eigen::FFT<double> fft;
      fft.inv(profile, spectrum);
      double sum_sq = 0.0;
      for (double v : profile) sum_sq += v * v;
      const double scale = spec.roughness_rms_m / std::sqrt(sum_sq / kProfilePoints);
      for (double& v : profile) v *= scale;
      double slope = 0.0;
      for (int i = 0; i < kProfilePoints; ++i)
        slope = std::max(slope, std::abs(profile[(i + 1) % kProfilePoints] - profile[i]) * kProfilePoints / kTwoPi);
      const auto [lo, hi] = std::minmax_element(profile.begin(), profile.end());
      slope_[race] += slope;
      peak_to_peak_[race] += *hi - *lo;
      roughness_profile_[race] = std::move(profile);
    }
  }
  std::vector<int> every_ball(n_balls);
  for (int b = 0; b < n_balls; ++b) every_ball[b] = b;
  all_balls_ = ball_set(every_ball);
  for (const Spall& s : spec.spalls) add_spall(s);
}

SpallLimit spall_limit(Surface surface, double ball_diameter_m, double outer_race_radius_m,
                       double inner_race_radius_m) {
  SpallLimit l;
  l.max_depth_m = 0.25 * ball_diameter_m;
  l.max_width_m = surface == Surface::Ball        ? 0.25 * kPi * ball_diameter_m
                  : surface == Surface::OuterRace ? 0.5 * kPi * outer_race_radius_m
                                                  : 0.5 * kPi * inner_race_radius_m;
  return l;
}

void Imperfections::validate(const Spall& s) const {
  const auto& g = geometry_;
  const auto number = [](double v) {
    std::ostringstream text;
    text << v;
    return text.str();
  };
  if (spalls_.size() >= static_cast<std::size_t>(kMaxSpalls))
    throw InvalidInputError("defect: " + std::to_string(spalls_.size()) + " spalls are present, at most " +
                            std::to_string(kMaxSpalls) + " may be at once (clear them first)");
  if (!std::isfinite(s.position_rad) || !std::isfinite(s.width_m) || !std::isfinite(s.depth_m))
    throw InvalidInputError("defect: position, width and depth must be finite");
  if (std::abs(s.position_rad) > kMaxAngleRad)
    throw InvalidInputError("defect: position " + number(s.position_rad) + " rad is beyond +-" + number(kMaxAngleRad) +
                            " rad (give it within a turn)");
  if (s.width_m < kMinSpallSizeM || s.depth_m < kMinSpallSizeM)
    throw InvalidInputError("defect: " + number(s.width_m * 1e6) + " um wide and " + number(s.depth_m * 1e6) +
                            " um deep: a spall is at least " + number(kMinSpallSizeM * 1e6) +
                            " um wide and deep (smaller is roughness)");
  const SpallLimit limit = spall_limit(s.surface, g.ball_diameter_m, g.outer_race_radius_m, g.inner_race_radius_m);
  if (!(s.depth_m > 0.0) || s.depth_m > limit.max_depth_m)
    throw InvalidInputError("defect: depth must be > 0 and at most a quarter of the ball diameter (" +
                            std::to_string(limit.max_depth_m * 1e6) + " um)");
  if (s.surface == Surface::Ball) {
    if (s.ball < 0 || s.ball >= g.rows * g.balls_per_row)
      throw InvalidInputError("defect: ball index " + std::to_string(s.ball) + " is not in [0, " +
                              std::to_string(g.rows * g.balls_per_row) + ")");
    if (!(s.width_m > 0.0) || s.width_m > limit.max_width_m)
      throw InvalidInputError(
          "defect: a ball spall must be wider than 0 and at most a quarter of the ball "
          "circumference (" +
          std::to_string(limit.max_width_m * 1e3) + " mm)");
  } else {
    if (s.row < 0 || s.row >= g.rows)
      throw InvalidInputError("defect: row " + std::to_string(s.row) + " is not a row of the bearing (" +
                              (g.rows == 1 ? "0" : "0 or 1") + ")");
    if (!(s.width_m > 0.0) || s.width_m > limit.max_width_m)
      throw InvalidInputError("defect: a race spall must be wider than 0 and at most a quarter of the raceway (" +
                              std::to_string(limit.max_width_m * 1e3) + " mm)");
  }
  // A spall that would grow from nothing to the largest the bearing holds in under 1 s is no
  // fatigue spall (real ones grow over hours; the compressed-time scenarios use <= 0.1 mm/s);
  // faster rates only made the state diverge. NaN and inf fail the same test.
  const double max_width_rate = limit.max_width_m / 1.0, max_depth_rate = limit.max_depth_m / 1.0;
  if (!(s.width_growth_m_per_s >= 0.0 && s.width_growth_m_per_s <= max_width_rate))
    throw InvalidInputError("defect: width growth must be finite and in [0, " + std::to_string(max_width_rate * 1e3) +
                            "] mm/s (the largest spall in no less than 1 s)");
  if (!(s.depth_growth_m_per_s >= 0.0 && s.depth_growth_m_per_s <= max_depth_rate))
    throw InvalidInputError("defect: depth growth must be finite and in [0, " + std::to_string(max_depth_rate * 1e6) +
                            "] um/s (the largest spall in no less than 1 s)");
  // The pit grown to its largest and its rims within a quarter turn either side of its centre
  // (the windows' asin, and a ball spall meets a race every half turn).
  const double largest = s.width_growth_m_per_s > 0.0 ? limit.max_width_m : s.width_m;
  const double reach = 0.5 * largest / surface_radius(s.surface) + rim_angle(s);
  if (!(reach < 0.5 * kPi))
    throw InvalidInputError("defect: the spall's half width with its rims spans " + number(reach * 180.0 / kPi) +
                            " deg of its surface, less than 90 is possible (narrower rims: spall_rim_width_um)");
}

void Imperfections::add_spall(const Spall& spall) {
  validate(spall);
  SpallShape shape;
  // Without growth the size does not depend on time (grown_size is then min(size, limit)).
  shape.fixed = spall.width_growth_m_per_s == 0.0 && spall.depth_growth_m_per_s == 0.0;
  if (shape.fixed) {
    spall_size(spall, spall.created_at_s, &shape.angular_width, &shape.depth, &shape.geometric_depth);
    shape.sin_half_width = std::sin(0.5 * shape.angular_width + rim_angle(spall));
    shape.pi_over_width = kPi / shape.angular_width;
  }
  spalls_.push_back(spall);
  spall_shapes_.push_back(shape);
  if (spall.surface != Surface::Ball) ++race_spall_count_;
}

namespace {
// cos and sin of a spall's centre, kept per slot while the centre stays (a fixed ring's
// spall: no sincos per force evaluation).
struct CentreTrig {
  double centre = 0.0, c = 1.0, s = 0.0;
};
constexpr int kKeptCentres = 4;
thread_local CentreTrig kept_centres[kKeptCentres];

__attribute__((noinline)) void centre_trig(double centre, int slot, double* c, double* s) {
  *c = std::cos(centre);
  *s = std::sin(centre);
  if (slot < kKeptCentres) kept_centres[slot] = CentreTrig{centre, *c, *s};
}
}  // namespace

int Imperfections::spall_windows(const RollingPhase& phase, SpallWindow* windows, int capacity) const {
  if (race_spall_count_ > capacity) return -1;
  int count = 0;
  const std::size_t n = spalls_.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Spall& s = spalls_[i];
    if (s.surface == Surface::Ball) continue;
    const SpallShape& shape = spall_shapes_[i];
    SpallWindow& w = windows[count];
    if (shape.fixed) {
      w.depth = shape.depth;
      w.geometric_depth = shape.geometric_depth;
      w.sin_half_width = shape.sin_half_width;
      w.pi_over_width = shape.pi_over_width;
      w.half_width = 0.5 * shape.angular_width;
    } else {
      grown_window(s, phase.time_s, &w);
    }
    const double rim = rim_angle(s);
    w.rim_height = rim > 0.0 ? spec_.spall_rim_height_m : 0.0;
    w.rim_pi_over_width = rim > 0.0 ? kPi / rim : 0.0;
    w.ring_drop = ring_drop(s, s.surface);
    w.ring_crest = w.half_width + 0.5 * rim;
    double centre = ring_angle(phase, s.surface) + s.position_rad;
    if (spec_.ball_place_wander_m > 0.0)
      centre -= place_shift_rad(i, s, phase.cage - centre, std::asin(w.sin_half_width) * 2.0, phase.time_s);
    if (count < kKeptCentres && kept_centres[count].centre == centre) {
      w.cos_centre = kept_centres[count].c;
      w.sin_centre = kept_centres[count].s;
    } else {
      centre_trig(centre, count, &w.cos_centre, &w.sin_centre);
    }
    w.sharp_edges = spec_.spall_sharp_edges;
    w.row = s.row;
    w.row_groove_centre_z = 0.0;
    ++count;
  }
  return count;
}

double Imperfections::place_shift_rad(std::size_t index, const Spall& s, double start, double angular_width,
                                      double time_s) const {
  const int z = geometry_.balls_per_row;
  const double pitch = kTwoPi / z;
  // The ball of the row nearest the spall: ball j sits at base_0 + j pitch + start (mod 2 pi).
  const double nearest = -(start + geometry_.base_azimuth[s.row * z]) / pitch;
  long j = std::lround(nearest) % z;
  if (j < 0) j += z;
  const std::uint64_t key =
      detail::mix64(spec_.seed ^ 0x9a1b3c5d7e9f1a3bull) ^ detail::mix64(index * 4096 + s.row * z + j);
  const double pitch_radius = 0.5 * (geometry_.outer_race_radius_m + geometry_.inner_race_radius_m);
  const double shift = spec_.ball_place_wander_m / pitch_radius *
                       detail::smooth_normal(key, time_s / spec_.ball_place_wander_correlation_s);
  // The nearest ball changes half a pitch from the centre: no ball is over the spall there
  // as long as half its width plus the shift stays inside half a pitch.
  const double bound = std::max(0.0, 0.45 * pitch - 0.5 * angular_width);
  return std::clamp(shift, -bound, bound);
}

double Imperfections::struck_latitude(std::size_t index, double time_s) const {
  if (spec_.ball_spin_axis_wander_rad <= 0.0) return spec_.ball_spall_latitude_rad;
  const std::uint64_t key = detail::mix64(spec_.seed ^ 0x3c6ef372fe94f82bull) ^ detail::mix64(index);
  return spec_.ball_spall_latitude_rad +
         spec_.ball_spin_axis_wander_rad *
             detail::smooth_normal(key, time_s / spec_.ball_spin_axis_wander_correlation_s);
}

double Imperfections::drop_depth(double width_m, Surface race) const {
  const double curvature = race == Surface::OuterRace   ? -geometry_.cos_contact_angle / geometry_.outer_race_radius_m
                           : race == Surface::InnerRace ? geometry_.cos_contact_angle / geometry_.inner_race_radius_m
                                                        : 0.0;
  return 0.125 * width_m * width_m * (2.0 / geometry_.ball_diameter_m + curvature);
}

double Imperfections::rim_crest_span() const { return spec_.spall_rim_height_m > 0.0 ? spec_.spall_rim_width_m : 0.0; }

double Imperfections::across_drop(double width_m, Surface race) const {
  const double groove = race == Surface::OuterRace ? geometry_.outer_groove_radius_m : geometry_.inner_groove_radius_m;
  return 0.125 * width_m * width_m * (2.0 / geometry_.ball_diameter_m - 1.0 / groove);
}

double Imperfections::spin_slip_rad(std::size_t index, int ball, const RollingPhase& phase) const {
  // The ball's azimuth in the bearing frame since the start, from the middle of the unloaded
  // arc: its passages through that middle so far are the whole turns of it.
  const double azimuth = geometry_.base_azimuth[ball] + phase.cage + kTwoPi * static_cast<double>(phase.cage_turns) -
                         spec_.ball_spin_slip_azimuth_rad;
  const long passage = floor_to_long(azimuth / kTwoPi);
  const std::uint64_t key = detail::mix64(spec_.seed ^ 0x7f4a7c159e3779b9ull) ^ detail::mix64(index);
  // Made anew at each call (~40 hashes): a per-thread cache would take the core past the
  // static TLS space of a library loaded with dlopen (docs/performance.md).
  return spec_.ball_spin_slip_rad * detail::random_walk(key, passage);
}

void Imperfections::grown_window(const Spall& s, double time_s, SpallWindow* w) const {
  double angular_width = 0.0;
  spall_size(s, time_s, &angular_width, &w->depth, &w->geometric_depth);
  w->sin_half_width = std::sin(0.5 * angular_width + rim_angle(s));
  w->pi_over_width = kPi / angular_width;
  w->half_width = 0.5 * angular_width;
}

double Imperfections::surface_radius(Surface surface) const {
  return surface == Surface::Ball        ? 0.5 * geometry_.ball_diameter_m
         : surface == Surface::OuterRace ? geometry_.outer_race_radius_m
                                         : geometry_.inner_race_radius_m;
}

double Imperfections::ring_drop(const Spall& s, Surface race) const {
  return spec_.spall_round_pits && rim_angle(s) > 0.0 ? across_drop(2.0 * surface_radius(s.surface), race) : 0.0;
}

double Imperfections::rim_angle(const Spall& s) const {
  return spec_.spall_rim_height_m > 0.0 ? spec_.spall_rim_width_m / surface_radius(s.surface) : 0.0;
}

void Imperfections::spall_size(const Spall& s, double time_s, double* angular_width, double* depth,
                               double* geometric_depth) const {
  const double age = std::max(0.0, time_s - s.created_at_s);
  const SpallLimit limit =
      spall_limit(s.surface, geometry_.ball_diameter_m, geometry_.outer_race_radius_m, geometry_.inner_race_radius_m);
  // Growth stops at the largest spall the bearing holds.
  const double width = grown_size(s.width_m, s.width_growth_m_per_s, age, limit.max_width_m);
  // A ball drops until it rests on both edges, never more than the spall is deep.
  *geometric_depth = drop_depth(width, s.surface);
  *depth = grown_size(s.depth_m, s.depth_growth_m_per_s, age, limit.max_depth_m);
  if (s.surface != Surface::Ball) {
    *depth = std::min(*depth, *geometric_depth);
    // A rim's crest is half its width out from the edge: the ball rests on it.
    if (spec_.spall_round_pits) *depth = std::min(*depth, across_drop(width + rim_crest_span(), s.surface));
  }
  *angular_width = width / surface_radius(s.surface);
}

double Imperfections::max_offset_change_m(double outer_race_angle, double inner_race_angle, double spin_angle) const {
  const double angles[3] = {std::abs(outer_race_angle), std::abs(inner_race_angle), std::abs(spin_angle)};
  double change = 0.0;
  for (int i = 0; i < 3; ++i) change += std::min(slope_[i] * angles[i], peak_to_peak_[i]);
  return change;
}

Imperfections::BallSet Imperfections::ball_set(const std::vector<int>& balls) const {
  BallSet set;
  fill_ball_set(balls, &set);
  return set;
}

void Imperfections::fill_ball_set(const std::vector<int>& balls, BallSet* set) const {
  const std::size_t n = balls.size();
  set->ball = balls;  // assignments keep the capacity: no allocation when the set is refilled
  set->entry_of_ball.assign(geometry_.base_azimuth.size(), -1);
  set->base_azimuth.resize(n);
  for (std::size_t e = 0; e < n; ++e) {
    set->entry_of_ball[balls[e]] = static_cast<int>(e);
    set->base_azimuth[e] = geometry_.base_azimuth[balls[e]];
  }
  set->roughness_weight.clear();
  if (has_roughness_ && roughness_row_ >= 0)
    for (std::size_t e = 0; e < n; ++e)
      set->roughness_weight.push_back(balls[e] / geometry_.balls_per_row == roughness_row_ ? 1.0 : 0.0);
  set->harmonic_terms.resize(2 * n * (race_waviness_.size() + ball_waviness_.size()));
  double* column = set->harmonic_terms.data();
  // Two harmonics' cos and sin per pass over the balls: each entry read once per pass.
  std::array<const Harmonic*, 2> pair{};
  int paired = 0;
  const auto gather_pair = [&] {
    const int* entry = balls.data();
    const double* c0 = pair[0]->cos_phase.data();
    const double* s0 = pair[0]->sin_phase.data();
    if (paired == 1) {
      for (std::size_t e = 0; e < n; ++e) {
        column[e] = c0[entry[e]];
        column[n + e] = s0[entry[e]];
      }
    } else {
      const double* c1 = pair[1]->cos_phase.data();
      const double* s1 = pair[1]->sin_phase.data();
      double* next = column + 2 * n;
      for (std::size_t e = 0; e < n; ++e) {
        const int b = entry[e];
        column[e] = c0[b];
        column[n + e] = s0[b];
        next[e] = c1[b];
        next[n + e] = s1[b];
      }
    }
    column += 2 * n * static_cast<std::size_t>(paired);
    paired = 0;
  };
  for (const auto* harmonics : {&race_waviness_, &ball_waviness_})
    for (const Harmonic& h : *harmonics) {
      pair[paired++] = &h;
      if (paired == 2) gather_pair();
    }
  if (paired > 0) gather_pair();
}

void Imperfections::add_offsets(const RollingPhase& phase, const BallSet& set, const double* constant, double* out,
                                bool include_spalls) const {
  const int n = static_cast<int>(set.ball.size());
  const double* base = set.base_azimuth.data();
  // out = constant + the waviness (without waviness, a copy of constant). Per harmonic:
  // amplitude * (cos, sin) of its angle now. Race harmonics see the race-frame angle of ball
  // b, base_b + cage - ring; ball harmonics the spin angle.
  thread_local std::vector<double> angles, coefficients;
  angles.clear();
  for (const Harmonic& h : race_waviness_) angles.push_back(h.order * (phase.cage - ring_angle(phase, h.surface)));
  for (const Harmonic& h : ball_waviness_) angles.push_back(h.order * phase.ball_spin);
  const int harmonics = static_cast<int>(angles.size());
  coefficients.resize(2 * angles.size());
  detail::harmonic_coefficients(waviness_amplitudes_.data(), angles.data(), harmonics, coefficients.data());
  detail::add_harmonic_sums(coefficients.data(), harmonics, set.harmonic_terms.data(), n, constant, out);
  if (has_roughness_) {
    constexpr double kScale = kProfilePoints / kTwoPi;
    constexpr long kMask = kProfilePoints - 1;
    const double* outer = roughness_profile_[0].data();
    const double* inner = roughness_profile_[1].data();
    // Race-frame shifts wrapped to [0, 2 pi), so that the table index stays positive.
    const double to_outer = std::fmod(std::fmod(phase.cage - phase.outer_ring, kTwoPi) + 2.0 * kTwoPi, kTwoPi);
    const double to_inner = std::fmod(std::fmod(phase.cage - phase.inner_ring, kTwoPi) + 2.0 * kTwoPi, kTwoPi);
    const auto rough = [=](int b) {
      const double xo = (base[b] + to_outer) * kScale, xi = (base[b] + to_inner) * kScale;
      const long io = static_cast<long>(xo), ii = static_cast<long>(xi);  // x >= 0: truncation is floor
      const double fo = xo - static_cast<double>(io), fi = xi - static_cast<double>(ii);
      const double po = outer[io & kMask], po1 = outer[(io + 1) & kMask];
      const double pi = inner[ii & kMask], pi1 = inner[(ii + 1) & kMask];
      return po + fo * (po1 - po) + pi + fi * (pi1 - pi);
    };
    if (set.roughness_weight.empty()) {
#pragma omp simd
      for (int b = 0; b < n; ++b) out[b] += rough(b);
    } else {  // one rough row: weight 1 on it, 0 on the other
      const double* weight = set.roughness_weight.data();
#pragma omp simd
      for (int b = 0; b < n; ++b) out[b] += weight[b] * rough(b);
    }
  }
  if (!include_spalls) return;
  constexpr double kInverseTwoPi = 1.0 / kTwoPi;
  for (std::size_t i = 0; i < spalls_.size(); ++i) {
    const Spall& s = spalls_[i];
    const SpallShape& shape = spall_shapes_[i];
    double angular_width = shape.angular_width, depth = shape.depth, geometric_depth = shape.geometric_depth;
    if (!shape.fixed) spall_size(s, phase.time_s, &angular_width, &depth, &geometric_depth);
    const bool sharp = spec_.spall_sharp_edges;
    const double rim = rim_angle(s), rim_height = rim > 0.0 ? spec_.spall_rim_height_m : 0.0;
    // A round pit's rim is a ring: over the pit the ball rides its crest (spall_dip).
    const bool ring = spec_.spall_round_pits && rim_height > 0.0;
    if (s.surface == Surface::Ball) {
      // The spot faces the outer and the inner race once each per spin turn.
      const int entry = set.entry_of_ball[s.ball];
      if (entry < 0) continue;
      // The pit's latitude off the rolling track, as a distance on the ball (m).
      const double offset_m = std::abs(struck_latitude(i, phase.time_s)) * 0.5 * geometry_.ball_diameter_m;
      const double half_width_m = 0.25 * angular_width * geometry_.ball_diameter_m;
      if (offset_m >= half_width_m && !ring) continue;  // the track misses the pit and has no ring
      double spin = phase.ball_spin + ball_phase_[s.ball] - s.position_rad;
      if (spec_.ball_spin_slip_rad > 0.0) spin -= spin_slip_rad(i, s.ball, phase);
      const double x = std::remainder(spin, kPi);
      // Even half turns face the outer race, odd ones the inner: the drop against its curvature.
      const bool outer = (std::lround((spin - x) / kPi) & 1) == 0;
      const Surface race = outer ? Surface::OuterRace : Surface::InnerRace;
      if (offset_m >= half_width_m) {
        // The track passes beside the pit: the ring's nearest crest, e beyond the contact's
        // centre line, still lifts the ball by h - e^2 / 2 (2 / d - 1 / r_g) (the gap across).
        const double e = std::max(0.0, offset_m - half_width_m - 0.5 * rim_crest_span());
        const double height = rim_height - across_drop(2.0 * e, race);
        if (height > 0.0) out[entry] -= spall_dip(x, 0.0, 0.0, sharp, 0.0, height, rim);
        continue;
      }
      angular_width *= std::sqrt(1.0 - (offset_m * offset_m) / (half_width_m * half_width_m));  // the chord
      const double chord_m = angular_width * 0.5 * geometry_.ball_diameter_m;
      geometric_depth = drop_depth(chord_m, race);
      double reach = std::min(depth, geometric_depth);
      if (spec_.spall_round_pits) reach = std::min(reach, across_drop(chord_m + rim_crest_span(), race));
      out[entry] -= spall_dip(x, angular_width, reach, sharp, geometric_depth, rim_height, rim, ring_drop(s, race));
    } else {
      // Only the few balls within half a width of the spall centre: find them by index,
      // since the balls of a row are evenly spaced.
      double start = phase.cage - ring_angle(phase, s.surface) - s.position_rad;
      double shift = 0.0;
      if (spec_.ball_place_wander_m > 0.0) {
        shift = place_shift_rad(i, s, start, angular_width, phase.time_s);
        start += shift;  // the nearest ball's place error, as in spall_windows
      }
      const int z = geometry_.balls_per_row;
      const double* all_base = geometry_.base_azimuth.data();
      const double ring_gap = ring_drop(s, s.surface);
      const double pitches_per_rad = z / kTwoPi;
      // Ball j of a row sits within the spacing error of row_phase + j pitch: the spall's
      // half width plus that error, in pitches, either side of its centre. Floor and ceil
      // keep a ball of slack against rounding (two balls to look at for a narrow spall).
      const double reach = (0.5 * angular_width + rim + max_spacing_error_ + std::abs(shift)) * pitches_per_rad;
      {  // the spall's own row only
        const int row = s.row;
        const double centre = -(start + all_base[row * z]) * pitches_per_rad;
        long first = floor_to_long(centre - reach);
        long last = ceil_to_long(centre + reach);
        if (last - first + 1 >= z) {  // a spall wider than the row: every ball once
          first = 0;
          last = z - 1;
        }
        // first mod z by whole turns: the phases are wrapped every sample, so first lies
        // within a turn or two of the row (no 64-bit division, ~40 cycles, per call).
        long first_in_row = first;
        if (first_in_row < -4L * z || first_in_row > 4L * z) first_in_row %= z;  // unwrapped phases
        while (first_in_row < 0) first_in_row += z;
        while (first_in_row >= z) first_in_row -= z;
        int j = static_cast<int>(first_in_row);
        for (long k = first; k <= last; ++k, j = j + 1 == z ? 0 : j + 1) {
          const int entry = set.entry_of_ball[row * z + j];
          if (entry < 0) continue;
          const double angle = all_base[row * z + j] + start;
          // To [-pi, pi]; the product by 1/(2 pi) can round differently from the quotient
          // only next to +-pi, where no spall reaches (at most a quarter turn wide).
          const double x = angle - kTwoPi * round_to_nearest(angle * kInverseTwoPi);
          out[entry] -= spall_dip(x, angular_width, depth, sharp, geometric_depth, rim_height, rim, ring_gap);
        }
      }
    }
  }
}

}  // namespace bearing_sim
