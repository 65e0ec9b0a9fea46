#pragma once
// Distributed imperfections and localised defects (docs/model.md section 9). Each one changes
// the contact deflection of the ball concerned at its current position.
#include <cstdint>
#include <string>
#include <vector>

namespace bearing_sim {

enum class Surface { OuterRace, InnerRace, Ball };
const char* surface_name(Surface s);
Surface parse_surface(const std::string& name);  // throws InvalidInputError

struct Waviness {
  Surface surface = Surface::OuterRace;
  int order = 1;             // lobes per revolution (of the race, or of the ball)
  double amplitude_m = 0.0;  // of the radius
  double phase_rad = 0.0;
  int row = -1;  // only the balls of this row (-1: every row, the same form)
};

// A spall: the ball loses contact depth while over it (half-sine profile).
struct Spall {
  Surface surface = Surface::OuterRace;
  double position_rad = 0.0;  // centre, in the race's own frame (ball: angle on the ball)
  int ball = 0;               // for a ball spall: index, row-major
  double width_m = 0.0;       // arc length along the rolling direction
  double depth_m = 0.0;
  double width_growth_m_per_s = 0.0;
  double depth_growth_m_per_s = 0.0;
  double created_at_s = 0.0;  // growth counts from here
  // For a race spall: the row whose raceway holds it (a spall is on one track). A ball
  // spall's row is that of its ball.
  int row = 0;
};

// Largest spall the bearing can hold (the single definition of the limit, used by the
// validation, the runtime growth and the scenario's growth law): ball spall at most a quarter
// of the ball circumference wide, race spall a quarter of the raceway; depth at most D/4.
struct SpallLimit {
  double max_width_m = 0.0;
  double max_depth_m = 0.0;
};
SpallLimit spall_limit(Surface surface, double ball_diameter_m, double outer_race_radius_m, double inner_race_radius_m);
// The smallest spall, width and depth alike: below a micrometre a dip is the surface's
// roughness (a ground raceway's is 0.05-0.2 um RMS), not a spall.
constexpr double kMinSpallSizeM = 1e-6;
// The most spalls present at once (a bearing file's defects, a scenario's, inject_defect):
// each is looked for under every ball at every force evaluation, and a bearing with dozens
// has long failed. With 64 the CT bearing runs ~11 times real time here (95 without any,
// 1.5 with 1000; 10,000 put the node ever further behind).
constexpr int kMaxSpalls = 64;
// Size grown at `rate` for `age` seconds, stopped at `max` (growth never passes the limit).
inline double grown_size(double size, double rate, double age_s, double max) {
  const double grown = size + rate * age_s;
  return grown < max ? grown : max;
}

struct ImperfectionSpec {
  std::uint64_t seed = 1;
  std::vector<Waviness> waviness;
  double ball_diameter_variation_m = 0.0;  // standard deviation of the ball diameters
  double roughness_rms_m = 0.0;            // RMS of a random profile on each race
  int roughness_row = -1;                  // only this row's raceways are rough (-1: every row)
  // Irregular ball spacing (cage pocket clearance) and cage slip: real bearings are not
  // perfectly periodic, which keeps distributed roughness from ringing at the ball-pass
  // frequencies.
  double ball_spacing_jitter_m = 0.0;     // standard deviation of each ball's place on the pitch circle
  double cage_slip = 0.0;                 // mean fraction the cage lags its kinematic speed
  double cage_slip_variation = 0.0;       // standard deviation of the slip fluctuation
  double cage_slip_correlation_s = 0.05;  // correlation time of the fluctuation
  // A ball's place in its cage pocket wanders within the pocket clearance: it meets a race
  // spall early or late by its place error, so the impacts scatter about their periodic grid
  // without the scatter accumulating (the cage keeps the mean period). Applied where a ball
  // meets a race spall's sharp edges; the smooth load distribution does not notice it.
  double ball_place_wander_m = 0.0;  // standard deviation along the pitch circle
  double ball_place_wander_correlation_s = 0.05;
  // A ball's spin axis wanders, carrying a ball spall in and out of the rolling track: the
  // spall is struck along a chord of its width at its latitude from the track, and not at
  // all while that latitude exceeds its half width.
  double ball_spin_axis_wander_rad = 0.0;  // standard deviation of the spall's latitude
  double ball_spin_axis_wander_correlation_s = 0.1;
  // Where the assembly left a ball spall: its mean latitude off the rolling track, about which
  // the wander moves it (a pit seeded at a random spot of the ball lies at any latitude: the
  // sine of a random spot's latitude is uniform). Every ball spall alike; 0: on the track.
  double ball_spall_latitude_rad = 0.0;
  // A ball's spin phase is kept only while the races drive it: out of the load zone it is
  // held by the cage and the lubricant alone, slows and skids back up on re-entry, so on
  // each passage through the unloaded arc it gains or loses an angle of spin. The angles of
  // successive passages are independent (standard deviation below); nothing pulls the spin
  // back, so a ball spall's phase is a random walk over the passages (docs/model.md 9.5).
  double ball_spin_slip_rad = 0.0;
  // Where a ball counts a passage: the middle of the unloaded arc, as an azimuth of the
  // bearing frame (the scenarios' radial load along x, azimuth 0, leaves it at pi).
  double ball_spin_slip_azimuth_rad = 3.14159265358979323846;  // pi
  // The spalls' edges. Rounded (false): the ball's deflection dips as a half-sine, a worn
  // spall's smooth entry and exit. Sharp (true, an EDM pit or a fresh spall): the ball pivots
  // on the nearer edge, its centre drops by min(h, D (1 - 2|x| / w)^2) (D = drop_depth, the
  // drop resting on both edges), steepest where it meets the far edge (docs/model.md 9.6).
  bool spall_sharp_edges = false;
  // Round pits (an EDM hole) narrower than the contact is wide: the ball drops at most until it
  // rests on the pit's sides across the track (Imperfections::across_drop).
  bool spall_round_pits = false;
  // A sharp edge's rim (sharp edges only): an EDM pit's recast lip or a fresh spall's raised
  // edge stands proud of the race, and a ball rolling over it gains deflection, struck
  // whatever its load. A raised-cosine bump of this height just outside each edge, as wide as
  // the contact's length along the track smooths the lip (the height is the one the contact
  // feels: docs/model.md 9.6). Round a round pit the rim is a ring: inside its crest circle
  // the ball rides the crest where it passes beside the contact. Zero: no rim.
  double spall_rim_height_m = 0.0;
  double spall_rim_width_m = 0.0;  // along the rolling direction; > 0 when there is a rim
  std::vector<Spall> spalls;
  bool empty() const {
    return waviness.empty() && ball_diameter_variation_m == 0.0 && roughness_rms_m == 0.0 && spalls.empty() &&
           ball_spacing_jitter_m == 0.0 && cage_slip == 0.0 && cage_slip_variation == 0.0 &&
           ball_place_wander_m == 0.0 && ball_spin_axis_wander_rad == 0.0 && ball_spin_slip_rad == 0.0;
  }
};

// A YAML text (or file) whose keys are a bearing file's `imperfections:` and `defects:`
// sections (either may be absent; config/imperfections/), for a bearing of `rows` rows (the
// `row:` keys must name one of them). A bearing file's own sections are read with it
// (bearing_config.hpp). Throws ConfigError naming `source` (the path) and the key.
ImperfectionSpec imperfections_from_string(const std::string& yaml_text, const std::string& source, int rows);
ImperfectionSpec load_imperfections(const std::string& path, int rows);

// Angles of the moving parts at one instant, rad.
struct RollingPhase {
  double cage = 0.0;
  double inner_ring = 0.0;
  double outer_ring = 0.0;
  double ball_spin = 0.0;  // spin of the balls relative to the cage
  double time_s = 0.0;
  // Whole turns taken off `cage` when the dynamics wraps it: cage + 2 pi cage_turns is the
  // cage's angle since the start, which counts the balls' passages (ball spin slip).
  std::int64_t cage_turns = 0;

  // The phase dt later at constant speeds (rad/s); the wrapped turns carried over.
  RollingPhase advanced(double cage_speed, double inner_speed, double outer_speed, double spin_speed, double dt) const {
    return RollingPhase{cage + cage_speed * dt,
                        inner_ring + inner_speed * dt,
                        outer_ring + outer_speed * dt,
                        ball_spin + spin_speed * dt,
                        time_s + dt,
                        cage_turns};
  }
};

// Precomputed race profiles and per-ball terms for one bearing.
class Imperfections {
 public:
  struct Geometry {
    int balls_per_row = 0;
    int rows = 1;
    double ball_diameter_m = 0.0;
    double outer_race_radius_m = 0.0;  // at the contact, for arc lengths
    double inner_race_radius_m = 0.0;
    // cos of the unloaded contact angle: a race's curvature along the rolling direction in the
    // contact plane is cos a0 / its radius at the contact (the ball's drop into a spall).
    double cos_contact_angle = 1.0;
    double outer_groove_radius_m = 0.0, inner_groove_radius_m = 0.0;  // across the track
    std::vector<double> base_azimuth;                                 // of every ball at cage angle 0, in [0, 2 pi)
  };
  Imperfections() = default;
  // Throws InvalidInputError for an imperfection or defect that does not fit the bearing.
  Imperfections(const ImperfectionSpec& spec, const Geometry& geometry);

  bool time_varying() const {
    return !race_waviness_.empty() || has_roughness_ || !ball_waviness_.empty() || !spalls_.empty();
  }
  bool has_roughness() const { return has_roughness_; }
  // Constant per-ball deflection change (ball diameter variation), m.
  const std::vector<double>& ball_diameter_deviation() const { return ball_diameter_deviation_; }
  // The per-ball terms add_offsets reads, gathered for a set of balls (every ball, or the
  // subset the dynamics integrates), so that a subset costs only its own balls.
  struct BallSet {
    std::vector<int> ball;           // bearing ball of each entry
    std::vector<int> entry_of_ball;  // inverse, per bearing ball; -1: not in the set
    std::vector<double> base_azimuth;
    std::vector<double> harmonic_terms;    // per harmonic: cos column, then sin column
    std::vector<double> roughness_weight;  // 1 on the rough row, 0 elsewhere; empty: every row
  };
  BallSet ball_set(const std::vector<int>& balls) const;
  void fill_ball_set(const std::vector<int>& balls, BallSet* set) const;  // reusing set's storage
  // Adds the time-varying deflection change of each ball of the set to out[0..set size).
  // Spalls only ever remove deflection, except their rims: leaving them out gives an upper
  // bound once max_rim_height_m() is added.
  void add_offsets(const RollingPhase& phase, const BallSet& set, double* out, bool include_spalls = true) const {
    add_offsets(phase, set, out, out, include_spalls);
  }
  // Same into out = base + change (base may be out).
  void add_offsets(const RollingPhase& phase, const BallSet& set, const double* base, double* out,
                   bool include_spalls = true) const;
  // A race spall at one rolling phase as the force kernel takes it when nothing else varies
  // the offsets: a ball of its row whose azimuth phi is within half the width w of the
  // centre psi loses depth cos(pi (phi - psi) / w) of deflection (the dip of add_offsets).
  struct SpallWindow {
    double cos_centre, sin_centre;  // psi, in the bearing frame
    double sin_half_width;          // sin(w / 2 + r): the window holds the pit and its rims
    double pi_over_width, depth;    // rad^-1, m
    // Sharp edges (ImperfectionSpec::spall_sharp_edges): the dip is
    // min(depth, geometric_depth (1 - 2|x| / w)^2), geometric_depth the drop resting on both
    // edges (drop_depth), in metres.
    bool sharp_edges;
    double geometric_depth;
    // Sharp edges with a rim (ImperfectionSpec::spall_rim_height_m): for w/2 <= |x| < w/2 + r
    // the dip is -rim_height sin^2(pi (|x| - w/2) / r), r the rim's angular width.
    double half_width;         // w / 2, rad
    double rim_height;         // m; 0: no rim, the window is the pit alone
    double rim_pi_over_width;  // pi / r, rad^-1
    int row;
    double row_groove_centre_z;  // set by the model: the row's balls are the ones at this z
    // Round pits with a rim: a ring whose crest circles the pit at ring_crest = w / 2 + r / 2
    // (rad); for |x| < ring_crest the dip is min(ring_drop (ring_crest^2 - x^2) - rim_height,
    // the pit's dip (0 past the edge)), ring_drop the across-track gap per rad^2 (m). 0: none.
    double ring_drop = 0.0;
    double ring_crest = 0.0;
  };
  // The race spalls at `phase` into windows[0..count), count returned; -1 when there are
  // more than `capacity`.
  int spall_windows(const RollingPhase& phase, SpallWindow* windows, int capacity) const;
  bool has_race_spalls() const { return race_spall_count_ > 0; }
  // Whether a fixed-size spall's window still moves with time (the balls' place wander).
  bool spall_windows_wander() const { return spec_.ball_place_wander_m > 0.0 && race_spall_count_ > 0; }
  // Whether anything but race spalls moves the offsets (waviness, roughness, ball spalls).
  bool offsets_vary_without_race_spalls() const {
    return !race_waviness_.empty() || has_roughness_ || !ball_waviness_.empty() ||
           spalls_.size() > static_cast<std::size_t>(race_spall_count_);
  }
  // Same, for every ball of the bearing.
  void add_offsets(const RollingPhase& phase, double* out, bool include_spalls = true) const {
    add_offsets(phase, all_balls_, out, include_spalls);
  }

  void add_spall(const Spall& spall);  // validates; throws InvalidInputError
  void clear_spalls() {
    spalls_.clear();
    spall_shapes_.clear();
    race_spall_count_ = 0;
  }
  const std::vector<Spall>& spalls() const { return spalls_; }
  // The most a spall's rim adds to a ball's deflection (0 without spalls or rims), m.
  double max_rim_height_m() const { return spalls_.empty() ? 0.0 : spec_.spall_rim_height_m; }
  const ImperfectionSpec& spec() const { return spec_; }
  // Bound on the change of a ball's deflection offset (spalls left out) when it travels
  // the given angles over the outer race, the inner race and its own surface (spin), for
  // the contact margin of the dynamics, m.
  double max_offset_change_m(double outer_race_angle, double inner_race_angle, double spin_angle) const;

 private:
  void validate(const Spall& s) const;
  // Width, effective depth and the drop resting on both edges (drop_depth) of a spall at time
  // t. For a ball spall, which meets both races, depth is the spall's own and the drop that of
  // a flat race: add_offsets takes the chord's drop against the race it faces.
  void spall_size(const Spall& s, double time_s, double* angular_width, double* depth, double* geometric_depth) const;
  // How far a ball's centre drops into a spall w long when it rests on both edges: the gap
  // between the ball and the race across w, w^2 / 8 (2 / d + k), k the race's curvature along
  // the rolling direction (the outer race curves towards the ball, -cos a0 / R_o; the inner
  // away from it, +cos a0 / R_i; a flat race 0, w^2 / (4 d)).
  double drop_depth(double width_m, Surface race) const;
  // A round pit's drop across the track: the groove nearly conforms to the ball, so over a
  // pit w across the ball rests on its sides after w^2 / 8 (2 / d - 1 / r_g), r_g the groove's
  // radius (spall_round_pits).
  double across_drop(double width_m, Surface race) const;
  double rim_crest_span() const;  // what the rims' crests add to a pit's width across, m
  // The angle the rims' width spans on the spall's surface (0 without rims), rad.
  double rim_angle(const Spall& s) const;
  // A round pit's ring (none: 0): the across-track gap against `race` per rad^2 of the pit's
  // surface, across_drop(2 radius), which the ball keeps off the ring's crest (spall_dip).
  double ring_drop(const Spall& s, Surface race) const;
  double surface_radius(Surface surface) const;  // at the contact (ball: its radius), m
  // A growing spall's window terms at time t (spall_windows).
  void grown_window(const Spall& s, double time_s, SpallWindow* w) const;
  // How far the ball nearest race spall `index` is from its even place at time t, as an
  // angle, for a spall of that angular width (bounded so that the nearest ball changes only
  // while no ball is over the spall). `start` is cage - ring - spall position.
  double place_shift_rad(std::size_t index, const Spall& s, double start, double angular_width, double time_s) const;
  // A ball spall's latitude off the rolling track at time t (its spin axis wanders), rad.
  double struck_latitude(std::size_t index, double time_s) const;
  // The spin angle ball spall `index` (on `ball`) has lost by `phase`: the slips of its
  // ball's passages through the unloaded arc so far, rad.
  double spin_slip_rad(std::size_t index, int ball, const RollingPhase& phase) const;

  ImperfectionSpec spec_;
  Geometry geometry_;
  static constexpr int kProfilePoints = 1 << 14;
  // One harmonic seen by every ball: amplitude * cos(order * angle + phase_b), where the
  // angle is that of the race frame (races) or the spin angle (balls).
  struct Harmonic {
    Surface surface;
    int order;
    double amplitude_m;
    std::vector<double> cos_phase, sin_phase;  // per ball
  };
  std::vector<Harmonic> race_waviness_, ball_waviness_;
  std::vector<double> waviness_amplitudes_;  // of race_waviness_ then ball_waviness_, the order of add_offsets
  bool has_roughness_ = false;
  int roughness_row_ = -1;                    // -1: every row
  std::vector<double> roughness_profile_[2];  // 0 outer, 1 inner: radius deviation, m
  std::vector<double> ball_diameter_deviation_;
  std::vector<double> ball_phase_;  // random initial spin angle of each ball
  std::vector<Spall> spalls_;
  // Per spall: its size when it does not grow (the common case), computed once instead of
  // at every rolling phase.
  struct SpallShape {
    bool fixed = false;
    double angular_width = 0.0, depth = 0.0, sin_half_width = 0.0, pi_over_width = 0.0, geometric_depth = 0.0;
  };
  std::vector<SpallShape> spall_shapes_;
  int race_spall_count_ = 0;
  BallSet all_balls_;
  double max_spacing_error_ = 0.0;  // largest deviation of a ball from even spacing, rad
  // Per surface (outer race, inner race, ball): largest slope (m/rad) and largest
  // peak-to-peak change (m) of the offsets, spalls left out.
  double slope_[3] = {0.0, 0.0, 0.0};
  double peak_to_peak_[3] = {0.0, 0.0, 0.0};
};

}  // namespace bearing_sim
