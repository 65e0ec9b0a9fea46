#include "bearing_sim/core/bearing_model.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <random>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/thermal_clearance.hpp"
#include "contact_kernel.hpp"

namespace bearing_sim {

BearingModel::BearingModel(BearingConfig config) : config_(std::move(config)) {
  const auto& c = config_;
  const double d = c.ball_diameter_m;
  const double a0 = c.contact_angle_rad;
  const double E = c.material.youngs_modulus_Pa;
  const double nu = c.material.poisson_ratio;
  inner_contact_ = inner_race_contact(d, c.pitch_diameter_m, a0, c.inner_groove_curvature, E, nu);
  outer_contact_ = outer_race_contact(d, c.pitch_diameter_m, a0, c.outer_groove_curvature, E, nu);
  contact_stiffness_ = series_stiffness(inner_contact_.stiffness_N_per_m15, outer_contact_.stiffness_N_per_m15);
  groove_centre_distance_ = (c.inner_groove_curvature + c.outer_groove_curvature - 1.0) * d;
  clearance_m_ = operating_clearance_m(c);
  cos_a0_ = std::cos(a0);
  moving_sign_ = c.rotating_ring == RotatingRing::Outer ? 1.0 : -1.0;
  // The moving ring's displacement and moment arms are taken at its own groove centre:
  // P_o for a moving outer ring, P_i = P_o + A e0 for a moving inner ring (section 5.1).
  const bool inner_moves = c.rotating_ring == RotatingRing::Inner;
  const double arm_shift = inner_moves ? groove_centre_distance_ : 0.0;
  const double outer_centre_radius = c.pitch_diameter_m / 2.0 - (c.outer_groove_curvature - 0.5) * d * cos_a0_;
  groove_centre_radius_ = outer_centre_radius + arm_shift * cos_a0_;

  const int n = c.rows * c.balls_per_row;
  base_azimuth_.resize(n);
  balls_.ball.resize(n);
  balls_.row.resize(n);
  balls_.base_azimuth.resize(n);
  balls_.cos_base.resize(n);
  balls_.sin_base.resize(n);
  balls_.groove_centre_z.resize(n);
  balls_.normal_z.resize(n);
  balls_.deflection_offset.assign(n, 0.0);
  // Irregular ball spacing, from its own random stream so that the other seeded parts do
  // not change when it is switched on.
  std::mt19937_64 spacing_rng(c.imperfections.seed ^ 0x5bd1e995u);
  std::normal_distribution<double> spacing(0.0, 1.0);
  for (int r = 0; r < c.rows; ++r) {
    const double nz = row_contact_sign(r) * std::sin(a0);
    const double gz = row_axial_position_m(r) - (c.outer_groove_curvature - 0.5) * d * nz + arm_shift * nz;
    for (int j = 0; j < c.balls_per_row; ++j) {
      const int b = r * c.balls_per_row + j;
      const double jitter = c.imperfections.ball_spacing_jitter_m / (c.pitch_diameter_m / 2.0) * spacing(spacing_rng);
      const double azimuth =
          std::fmod(2.0 * kPi * j / c.balls_per_row + (r == 1 ? c.row_phase_rad : 0.0) + jitter + 2.0 * kPi, 2.0 * kPi);
      base_azimuth_[b] = azimuth < 0.0 ? azimuth + 2.0 * kPi : azimuth;  // in [0, 2 pi)
      balls_.ball[b] = b;
      balls_.row[b] = r;
      balls_.base_azimuth[b] = base_azimuth_[b];
      balls_.cos_base[b] = std::cos(base_azimuth_[b]);
      balls_.sin_base[b] = std::sin(base_azimuth_[b]);
      balls_.groove_centre_z[b] = gz;
      balls_.normal_z[b] = nz;
    }
    max_lever_arm_ = std::max(max_lever_arm_, std::hypot(groove_centre_radius_, gz));
  }

  Imperfections::Geometry g;
  g.balls_per_row = c.balls_per_row;
  g.rows = c.rows;
  g.ball_diameter_m = d;
  g.outer_race_radius_m = c.pitch_diameter_m / 2.0 + d / 2.0 * cos_a0_;
  g.inner_race_radius_m = c.pitch_diameter_m / 2.0 - d / 2.0 * cos_a0_;
  g.cos_contact_angle = cos_a0_;
  g.outer_groove_radius_m = c.outer_groove_curvature * d;
  g.inner_groove_radius_m = c.inner_groove_curvature * d;
  g.base_azimuth = base_azimuth_;
  try {
    imperfections_ = Imperfections(c.imperfections, g);
  } catch (const InvalidInputError& e) {
    throw ConfigError(c.name + ": " + e.what());
  }
  balls_.deflection_offset = imperfections_.ball_diameter_deviation();
  for (int r = 1; r < c.rows; ++r)
    if (balls_.groove_centre_z[r * c.balls_per_row] == balls_.groove_centre_z[0]) rows_apart_axially_ = false;
  update_race_spalls_in_kernel();
  stamp_ = next_stamp();
}

void BearingModel::update_race_spalls_in_kernel() {
  race_spalls_in_kernel_ =
      imperfections_.has_race_spalls() && !imperfections_.offsets_vary_without_race_spalls() && rows_apart_axially_;
  standing_window_count_ = 0;
  windows_follow_outer_ = windows_follow_inner_ = false;
  if (!race_spalls_in_kernel_) return;
  bool grows = false;
  for (const Spall& s : imperfections_.spalls()) {
    windows_follow_outer_ = windows_follow_outer_ || s.surface == Surface::OuterRace;
    windows_follow_inner_ = windows_follow_inner_ || s.surface == Surface::InnerRace;
    grows = grows || s.width_growth_m_per_s != 0.0 || s.depth_growth_m_per_s != 0.0;
  }
  if (grows || imperfections_.spall_windows_wander()) return;
  standing_window_count_ = make_kernel_windows(RollingPhase{}, standing_windows_);
}

int BearingModel::make_kernel_windows(const RollingPhase& phase, Imperfections::SpallWindow* windows) const {
  const int count = std::max(0, imperfections_.spall_windows(phase, windows, kMaxKernelWindows));
  // The row's balls are those at its groove centre's z.
  for (int i = 0; i < count; ++i)
    windows[i].row_groove_centre_z = balls_.groove_centre_z[windows[i].row * config_.balls_per_row];
  return count;
}

const Imperfections::SpallWindow* BearingModel::kernel_windows(const RollingPhase& phase,
                                                               Imperfections::SpallWindow* scratch, int* count) const {
  // The same windows as made anew: at ring angle 0 (or -0) a spall's centre is its position.
  if (standing_window_count_ > 0 && (!windows_follow_outer_ || phase.outer_ring == 0.0) &&
      (!windows_follow_inner_ || phase.inner_ring == 0.0)) {
    *count = standing_window_count_;
    return standing_windows_;
  }
  *count = make_kernel_windows(phase, scratch);
  return scratch;
}

std::uint64_t BearingModel::next_stamp() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

void BearingModel::add_spall(const Spall& spall) {
  imperfections_.add_spall(spall);
  update_race_spalls_in_kernel();
  stamp_ = next_stamp();
}

void BearingModel::clear_spalls() {
  imperfections_.clear_spalls();
  update_race_spalls_in_kernel();
  stamp_ = next_stamp();
}

void BallArrays::next_generation() {
  static std::atomic<std::uint64_t> generations{0};
  generation = ++generations;
}

void BallArrays::clear() {
  next_generation();
  ball.clear();
  row.clear();
  base_azimuth.clear();
  cos_base.clear();
  sin_base.clear();
  groove_centre_z.clear();
  normal_z.clear();
  deflection_offset.clear();
}

void BallArrays::push_back(const BallArrays& from, std::size_t i) {
  ball.push_back(from.ball[i]);
  row.push_back(from.row[i]);
  base_azimuth.push_back(from.base_azimuth[i]);
  cos_base.push_back(from.cos_base[i]);
  sin_base.push_back(from.sin_base[i]);
  groove_centre_z.push_back(from.groove_centre_z[i]);
  normal_z.push_back(from.normal_z[i]);
  deflection_offset.push_back(from.deflection_offset[i]);
}

void BallArrays::assign(const BallArrays& from, const int* entries, std::size_t n) {
  // Resized, not cleared first: a cleared vector's resize zero-fills all n entries before
  // the gather overwrites them.
  next_generation();
  ball.resize(n);
  row.resize(n);
  base_azimuth.resize(n);
  cos_base.resize(n);
  sin_base.resize(n);
  groove_centre_z.resize(n);
  normal_z.resize(n);
  deflection_offset.resize(n);
  // One pass over the entries for all eight arrays, through plain pointers (every split of a
  // large bearing that moves a ball rebuilds both sets): each entry is read once, and the
  // loop carries eight loads and stores per ball instead of eight loops' index loads and
  // counters.
  const int* from_ball = from.ball.data();
  const int* from_row = from.row.data();
  const double* from_base = from.base_azimuth.data();
  const double* from_cos = from.cos_base.data();
  const double* from_sin = from.sin_base.data();
  const double* from_z = from.groove_centre_z.data();
  const double* from_normal_z = from.normal_z.data();
  const double* from_offset = from.deflection_offset.data();
  int* to_ball = ball.data();
  int* to_row = row.data();
  double* to_base = base_azimuth.data();
  double* to_cos = cos_base.data();
  double* to_sin = sin_base.data();
  double* to_z = groove_centre_z.data();
  double* to_normal_z = normal_z.data();
  double* to_offset = deflection_offset.data();
  for (std::size_t k = 0; k < n; ++k) {
    const int e = entries[k];
    to_ball[k] = from_ball[e];
    to_row[k] = from_row[e];
    to_base[k] = from_base[e];
    to_cos[k] = from_cos[e];
    to_sin[k] = from_sin[e];
    to_z[k] = from_z[e];
    to_normal_z[k] = from_normal_z[e];
    to_offset[k] = from_offset[e];
  }
}

double BearingModel::row_axial_position_m(int row) const {
  if (config_.rows == 1) return 0.0;
  return row == 0 ? config_.row_spacing_m / 2.0 : -config_.row_spacing_m / 2.0;
}

int BearingModel::row_contact_sign(int row) const {
  if (config_.rows == 1) return 1;
  const int side = row == 0 ? 1 : -1;  // sign(z_r)
  return config_.arrangement == Arrangement::BackToBack ? -side : side;
}

Matrix5 BearingModel::mass_matrix() const {
  if (!config_.has_dynamics()) throw InvalidInputError(config_.name + ": rotating_mass_kg is required for dynamics");
  Vector5 ring;
  ring << config_.rotating_mass_kg, config_.rotating_mass_kg, config_.rotating_mass_kg, config_.tilt_inertia_kg_m2,
      config_.tilt_inertia_kg_m2;
  Matrix5 m = ring.asDiagonal();
  const CarriedBody& b = config_.carried_body;
  if (b.present()) {
    // Its centre of gravity (0, 0, z) moves by u + theta x (0, 0, z) = (x + z theta_y, y - z theta_x, z):
    // kinetic energy m/2 |that rate|^2 + J/2 (theta_x'^2 + theta_y'^2).
    const double mb = b.mass_kg, z = b.centre_of_gravity_axial_m, j = b.transverse_inertia_kg_m2;
    m(0, 0) += mb;
    m(1, 1) += mb;
    m(2, 2) += mb;
    m(3, 3) += j + mb * z * z;
    m(4, 4) += j + mb * z * z;
    m(0, 4) += mb * z;
    m(4, 0) += mb * z;
    m(1, 3) -= mb * z;
    m(3, 1) -= mb * z;
  }
  return m;
}

void BearingModel::set_deflection_offsets(const std::vector<double>& offsets_m) {
  if (static_cast<int>(offsets_m.size()) != ball_count())
    throw InvalidInputError("deflection offsets: expected one value per ball");
  for (double o : offsets_m)
    if (!std::isfinite(o)) throw InvalidInputError("deflection offsets: non-finite value");
  balls_.deflection_offset = offsets_m;
  stamp_ = next_stamp();
}

// The loops below share this kinematics (docs/model.md section 5); it is written once and
// inlined so that the force loop vectorizes.
namespace {
struct Kinematics {
  double px, py, pz;  // groove centre of the moving ring (P_o or P_i)
  double vx, vy, vz;  // loaded centre vector v = A e0 - u
  double norm;        // |v|
  double deflection;  // delta
};

inline Kinematics kinematics(double cphi, double sphi, double gz, double nz, double offset, double rho, double cos_a0,
                             double A, double g0, double sign, const double* q) {
  Kinematics k;
  k.px = rho * cphi;
  k.py = rho * sphi;
  k.pz = gz;
  const double ux = q[0] + q[4] * k.pz;
  const double uy = q[1] - q[3] * k.pz;
  const double uz = q[2] + q[3] * k.py - q[4] * k.px;
  k.vx = A * cos_a0 * cphi - sign * ux;
  k.vy = A * cos_a0 * sphi - sign * uy;
  k.vz = A * nz - sign * uz;
  k.norm = std::sqrt(k.vx * k.vx + k.vy * k.vy + k.vz * k.vz);
  k.deflection = k.norm - A - g0 + offset;
  return k;
}
}  // namespace

const double* BearingModel::offsets_at(const RollingPhase& phase, const BallArrays& balls, bool include_spalls) const {
  if (!imperfections_.time_varying()) return balls.deflection_offset.data();
  // The RK4 stages of a sample share phases (the mid stages, a step's end and the next
  // step's start), and a sample uses a few sets of balls (those integrated, those checked
  // for contact): keep the offsets of the last phase of each of a few sets, per thread.
  struct Entry {
    std::uint64_t stamp = 0;
    const BallArrays* set = nullptr;
    std::uint64_t generation = 0;
    Imperfections::BallSet terms;  // of this set of balls
    RollingPhase phase;
    // The use count beside the two flags, in one word: the cache is per thread, and its size
    // counts against the static TLS space (docs/performance.md). The count wraps after 2^32
    // uses, which only makes one eviction pick a recently used entry.
    std::uint32_t last_use = 0;
    bool include_spalls = false;
    bool has_values = false;
    std::vector<double> values;
  };
  thread_local std::array<Entry, 4> cache;
  thread_local std::uint32_t uses = 0;
  Entry* entry = nullptr;
  for (Entry& e : cache)
    if (e.stamp == stamp_ && e.set == &balls && e.generation == balls.generation) entry = &e;
  if (!entry) {
    entry = &*std::min_element(cache.begin(), cache.end(),
                               [](const Entry& a, const Entry& b) { return a.last_use < b.last_use; });
    entry->stamp = stamp_;
    entry->set = &balls;
    entry->generation = balls.generation;
    imperfections_.fill_ball_set(balls.ball, &entry->terms);
    entry->has_values = false;
  }
  entry->last_use = ++uses;
  const RollingPhase& p = entry->phase;
  const bool same = entry->has_values && entry->include_spalls == include_spalls && p.cage == phase.cage &&
                    p.inner_ring == phase.inner_ring && p.outer_ring == phase.outer_ring &&
                    p.ball_spin == phase.ball_spin && p.time_s == phase.time_s && p.cage_turns == phase.cage_turns;
  if (!same) {
    entry->values.resize(balls.size());
    imperfections_.add_offsets(phase, entry->terms, balls.deflection_offset.data(), entry->values.data(),
                               include_spalls);
    entry->phase = phase;
    entry->include_spalls = include_spalls;
    entry->has_values = true;
  }
  return entry->values.data();
}

Vector5 BearingModel::contact_force(const Vector5& q, const Vector5& q_dot, const RollingPhase& phase,
                                    const BallArrays& balls, ContactKernel kernel) const {
  // The stages of a sample come back to the same cage angle (mid stages, step ends).
  thread_local double last_cage = 0.0, cos_cage = 1.0, sin_cage = 0.0;
  if (phase.cage != last_cage) {
    last_cage = phase.cage;
    cos_cage = std::cos(phase.cage);
    sin_cage = std::sin(phase.cage);
  }
  return contact_force(q, q_dot, phase, balls, cos_cage, sin_cage, kernel);
}

Vector5 BearingModel::contact_force(const Vector5& q, const Vector5& q_dot, const RollingPhase& phase,
                                    const BallArrays& balls, double cos_cage, double sin_cage,
                                    ContactKernel kernel) const {
  // All balls in one kernel call, whatever their row (each carries its groove centre's z
  // and normal slope): one call per force evaluation keeps small bearings cheap. When only
  // race spalls vary, they go into the kernel as windows and the constant offsets need no
  // per-call lookup, copy and sum (on a 9-ball bearing those cost as much as the kernel).
  Imperfections::SpallWindow scratch[kMaxKernelWindows];
  const Imperfections::SpallWindow* windows = nullptr;
  int window_count = 0;
  const double* offsets = nullptr;
  if (race_spalls_in_kernel_) windows = kernel_windows(phase, scratch, &window_count);
  if (window_count > 0) offsets = balls.deflection_offset.data();
  else offsets = offsets_at(phase, balls);
  const detail::ContactKernelInput in{cos_cage,
                                      sin_cage,
                                      groove_centre_radius_,
                                      cos_a0_,
                                      groove_centre_distance_,
                                      clearance_m_,
                                      moving_sign_,
                                      contact_stiffness_,
                                      config_.contact_damping_Ns_per_m,
                                      q.data(),
                                      q_dot.data(),
                                      balls.cos_base.data(),
                                      balls.sin_base.data(),
                                      balls.groove_centre_z.data(),
                                      balls.normal_z.data(),
                                      offsets,
                                      static_cast<int>(balls.size()),
                                      windows,
                                      window_count};
  const detail::ContactSums s =
      kernel == ContactKernel::Fastest ? detail::contact_sums_simd(in) : detail::contact_sums_scalar(in);
  // force = sign sum s v; moment = sign sum s (p x v) with p = (rho cphi, rho sphi, z).
  const double rho = groove_centre_radius_;
  Vector5 f;
  f << s.x, s.y, s.z, rho * s.z_sin - s.y_z, s.x_z - rho * s.z_cos;
  return moving_sign_ * f;
}

Vector5 BearingModel::contact_force_and_stiffness(const Vector5& q, const RollingPhase& phase, Matrix5* stiffness,
                                                  Matrix5* damping) const {
  const double cc = std::cos(phase.cage), sc = std::sin(phase.cage);
  const double* off = offsets_at(phase, balls_);
  const double A = groove_centre_distance_, g0 = clearance_m_, sign = moving_sign_;
  const double kn = contact_stiffness_;
  Vector5 f = Vector5::Zero();
  if (stiffness) stiffness->setZero();
  if (damping) damping->setZero();
  for (int b = 0; b < ball_count(); ++b) {
    const double cphi = cc * balls_.cos_base[b] - sc * balls_.sin_base[b];
    const double sphi = sc * balls_.cos_base[b] + cc * balls_.sin_base[b];
    const Kinematics k = kinematics(cphi, sphi, balls_.groove_centre_z[b], balls_.normal_z[b], off[b],
                                    groove_centre_radius_, cos_a0_, A, g0, sign, q.data());
    if (k.deflection <= 0.0) continue;
    const double load = kn * k.deflection * std::sqrt(k.deflection);
    const Eigen::Vector3d e(k.vx / k.norm, k.vy / k.norm, k.vz / k.norm);
    // G maps q to the displacement of the groove centre: u = G q.
    Eigen::Matrix<double, 3, 5> G;
    G << 1, 0, 0, 0, k.pz,  //
        0, 1, 0, -k.pz, 0,  //
        0, 0, 1, k.py, -k.px;
    f += sign * load * (G.transpose() * e);
    if (stiffness) {
      const double load_slope = 1.5 * kn * std::sqrt(k.deflection);
      const Eigen::Matrix3d ee = e * e.transpose();
      const Eigen::Matrix3d kc = load_slope * ee + (load / k.norm) * (Eigen::Matrix3d::Identity() - ee);
      *stiffness += G.transpose() * kc * G;
    }
    // Damping force -c_n (e . du/dt) e on each loaded contact: C = sum c_n G^T e e^T G.
    if (damping) *damping += config_.contact_damping_Ns_per_m * (G.transpose() * e) * (e.transpose() * G);
  }
  return f;
}

// Also built for AVX2 and picked at load time (the default build is baseline x86-64);
// "avx2" without "fma" keeps the arithmetic, and so the results, identical.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
__attribute__((target_clones("avx2", "default")))
#endif
void BearingModel::deflections(const Vector5& q, const RollingPhase& phase, const BallArrays& balls,
                               std::vector<double>* out, bool include_spalls) const {
  const double cc = std::cos(phase.cage), sc = std::sin(phase.cage);
  const double rho = groove_centre_radius_, ca = cos_a0_, A = groove_centre_distance_;
  const double g0 = clearance_m_, sign = moving_sign_;
  const double* qp = q.data();
  const double* cb = balls.cos_base.data();
  const double* sb = balls.sin_base.data();
  const double* gzs = balls.groove_centre_z.data();
  const double* nzs = balls.normal_z.data();
  const double* off = offsets_at(phase, balls, include_spalls);
  const int n = static_cast<int>(balls.size());
  out->resize(n);
  double* d = out->data();
#pragma omp simd
  for (int b = 0; b < n; ++b) {
    const double cphi = cc * cb[b] - sc * sb[b];
    const double sphi = sc * cb[b] + cc * sb[b];
    d[b] = kinematics(cphi, sphi, gzs[b], nzs[b], off[b], rho, ca, A, g0, sign, qp).deflection;
  }
}

double BearingModel::split_by_deflection(const Vector5& q, const RollingPhase& phase, double margin_m,
                                         BallArrays* near_contact, BallArrays* clear) const {
  thread_local std::vector<double> deflection;
  thread_local std::vector<int> near_entries, clear_entries;
  // Without the spalls' dips: an upper bound of the deflection once their rims' height is
  // added, which the margin tracks.
  deflections(q, phase, balls_, &deflection, false);
  margin_m += imperfections_.max_rim_height_m();
  const std::size_t n = balls_.size();
  near_entries.resize(n);
  clear_entries.resize(n);
  std::size_t n_near = 0, n_clear = 0;
  double clear_max = -std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < n; ++b) {
    const double d = deflection[b];
    if (d > -margin_m) {
      near_entries[n_near++] = static_cast<int>(b);
    } else {
      clear_entries[n_clear++] = static_cast<int>(b);
      clear_max = std::max(clear_max, d);
    }
  }
  // The entries of the whole set are the ball indices, so the subsets' ball lists identify them.
  const auto same = [this](const BallArrays& set, const std::vector<int>& entries, std::size_t count) {
    return set.source_stamp == stamp_ && set.generation != 0 && set.size() == count &&
           std::equal(entries.begin(), entries.begin() + static_cast<std::ptrdiff_t>(count), set.ball.begin());
  };
  if (!same(*near_contact, near_entries, n_near) || !same(*clear, clear_entries, n_clear)) {
    near_contact->assign(balls_, near_entries.data(), n_near);
    clear->assign(balls_, clear_entries.data(), n_clear);
    near_contact->source_stamp = clear->source_stamp = stamp_;
  }
  return clear_max;
}

double BearingModel::max_deflection(const Vector5& q, const RollingPhase& phase, const BallArrays& balls) const {
  thread_local std::vector<double> deflection;
  deflections(q, phase, balls, &deflection);
  double worst = -std::numeric_limits<double>::infinity();
  for (double d : deflection) worst = std::max(worst, d);
  return worst;
}

std::vector<BallState> BearingModel::ball_states(const Vector5& q, const RollingPhase& phase) const {
  std::vector<BallState> balls(ball_count());
  const double* off = offsets_at(phase, balls_);
  for (int b = 0; b < ball_count(); ++b) {
    const double phi = phase.cage + base_azimuth_[b];
    const Kinematics k =
        kinematics(std::cos(phi), std::sin(phi), balls_.groove_centre_z[b], balls_.normal_z[b], off[b],
                   groove_centre_radius_, cos_a0_, groove_centre_distance_, clearance_m_, moving_sign_, q.data());
    BallState& s = balls[b];
    s.row = balls_.row[b];
    s.index_in_row = b % config_.balls_per_row;
    s.azimuth_rad = std::remainder(phi, 2.0 * kPi);
    s.deflection_m = k.deflection;
    s.load_N = k.deflection > 0.0 ? contact_stiffness_ * std::pow(k.deflection, 1.5) : 0.0;
    const double radial = k.vx * std::cos(phi) + k.vy * std::sin(phi);
    s.contact_angle_rad = std::atan2(std::abs(k.vz), radial);
    s.normal = Eigen::Vector3d(k.vx, k.vy, k.vz) / k.norm;
    s.pressure_Pa = std::max(inner_contact_.max_pressure_Pa(s.load_N), outer_contact_.max_pressure_Pa(s.load_N));
  }
  return balls;
}

double BearingModel::cage_speed_rad_s(double inner_rad_s, double outer_rad_s) const {
  const double gamma = config_.ball_diameter_m * cos_a0_ / config_.pitch_diameter_m;
  return inner_rad_s * (1.0 - gamma) / 2.0 + outer_rad_s * (1.0 + gamma) / 2.0;
}

double BearingModel::ball_spin_speed_rad_s(double inner_rad_s, double outer_rad_s) const {
  const double gamma = config_.ball_diameter_m * cos_a0_ / config_.pitch_diameter_m;
  return config_.pitch_diameter_m / (2.0 * config_.ball_diameter_m) * (1.0 - gamma * gamma) *
         std::abs(inner_rad_s - outer_rad_s);
}

double BearingModel::max_offset_change_m(double inner_rad_s, double outer_rad_s, double dt) const {
  const double wc = cage_speed_rad_s(inner_rad_s, outer_rad_s);
  return imperfections_.max_offset_change_m((wc - outer_rad_s) * dt, (wc - inner_rad_s) * dt,
                                            ball_spin_speed_rad_s(inner_rad_s, outer_rad_s) * dt);
}

void BearingModel::ring_speeds(double rotating_ring_rad_s, double* inner_rad_s, double* outer_rad_s) const {
  const bool outer = config_.rotating_ring == RotatingRing::Outer;
  *inner_rad_s = outer ? 0.0 : rotating_ring_rad_s;
  *outer_rad_s = outer ? rotating_ring_rad_s : 0.0;
}

Matrix6 bushing_matrix(const Matrix5& stiffness) {
  Matrix6 k = Matrix6::Zero();
  k.topLeftCorner<5, 5>() = stiffness;
  return k;
}

}  // namespace bearing_sim
