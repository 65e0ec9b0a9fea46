// Integrator study: force evaluations per output sample against accuracy, for the ring
// dynamics M q'' = F_ext + f(q, q', t) at a fixed output rate (10 kHz).
//
// Every method integrates the same right-hand side (all balls, the same rolling phases)
// from the same static equilibrium; the reference is classical RK4 with 16 steps per
// sample. Accuracy: a_rms of the x acceleration over the second half of the run (mean
// removed), the level L = 20 lg(a_rms / 9.81e-3 m/s^2), and the largest level error of
// the octave bands (63 Hz .. 4 kHz) of the acceleration spectrum that hold >= 1 % of its
// energy. Cost: evaluations of f per output sample (the end-of-sample acceleration, which
// is output anyway, is the first stage of the next sample), and the real-time factor.
//
// Usage: bearing_sim_integrator_study [duration_s (default 0.3)] [case name part] [method name part]
//        bearing_sim_integrator_study production [duration_s]  (BearingDynamics, every method)
//        bearing_sim_integrator_study spall_steps [duration_s]  (race spalls on the CT bearing at whole steps)
//        bearing_sim_integrator_study barrier
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <yaml-cpp/yaml.h>
#include <unsupported/Eigen/MatrixFunctions>

#include "bearing_6205_yaml.hpp"
#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/simulation_run.hpp"
#include "bearing_sim/core/spectrum.hpp"
#include "reference_cases.hpp"

namespace {
using namespace bearing_sim;
using Vector10 = Eigen::Matrix<double, 10, 1>;
using Matrix10 = Eigen::Matrix<double, 10, 10>;

struct Case {
  std::string name;
  BearingConfig config;
  Vector5 load;
  double ring_speed_rad_s;
};

BearingConfig bearing(const std::string& file) {
  return load_bearing_config(std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings/" + file);
}

Vector5 load5(double fx, double fy, double fz, double mx, double my) {
  Vector5 l;
  l << fx, fy, fz, mx, my;
  return l;
}

std::vector<Case> cases() {
  std::vector<Case> out;
  const double ct_speed = 180.0 * 2.0 * kPi / 60.0;
  out.push_back({"CT smooth", bearing("ct_gantry_lyc.yaml"), load5(6800, 0, 0, 0, 2100), ct_speed});
  const BearingConfig defects = test::ct_gantry_with_defects(BEARING_SIM_SOURCE_DIR);
  out.push_back({"CT waviness + spall", defects, load5(6800, 0, 0, 0, 2100), ct_speed});
  const BearingConfig small = bearing_config_from_string(
      test::kBearing6205Yaml + "defects: [{surface: outer_race, position_deg: 0, width_mm: 1.0, depth_um: 30}]\n",
      "study 6205");
  out.push_back({"6205 outer spall 30 um", small, load5(1000, 0, 200, 0, 0), 1800.0 * 2.0 * kPi / 60.0});
  BearingConfig shallow = small;
  shallow.imperfections.spalls.at(0).depth_m = 3e-6;
  out.push_back({"6205 outer spall 3 um", shallow, load5(1000, 0, 200, 0, 0), 1800.0 * 2.0 * kPi / 60.0});
  // The INS pair of the benchmark: smooth, but its tilt mode is stiff (|lambda| h ~ 5 per sample).
  out.push_back(
      {"INS 618/22 pair", bearing("ins_618_22_db.yaml"), load5(3400, 0, 1750, 0, 0), 60.0 * 2.0 * kPi / 60.0});
  return out;
}

// The right-hand side, counting its evaluations.
class System {
 public:
  System(const BearingModel& model, const Vector5& load, double ring_speed) : model_(model), load_(load) {
    inverse_mass_ = model.mass_matrix().inverse();
    model.ring_speeds(ring_speed, &inner_, &outer_);
    cage_ = model.cage_speed_rad_s(inner_, outer_);
    spin_ = model.ball_spin_speed_rad_s(inner_, outer_);
  }
  Vector5 acceleration(const Vector5& q, const Vector5& v, const RollingPhase& p) const {
    ++evaluations;
    return inverse_mass_ * (load_ + model_.contact_force(q, v, p));
  }
  RollingPhase advanced(const RollingPhase& p, double dt) const {
    const double slip = cage_ * (1.0 - model_.config().imperfections.cage_slip);
    return RollingPhase{p.cage + slip * dt, p.inner_ring + inner_ * dt, p.outer_ring + outer_ * dt,
                        p.ball_spin + spin_ * dt, p.time_s + dt};
  }
  const BearingModel& model() const { return model_; }
  const Vector5& load() const { return load_; }
  const Matrix5& inverse_mass() const { return inverse_mass_; }
  mutable long long evaluations = 0;

 private:
  const BearingModel& model_;
  Vector5 load_;
  Matrix5 inverse_mass_;
  double inner_ = 0, outer_ = 0, cage_ = 0, spin_ = 0;
};

struct State {
  Vector5 q, v, a;
  RollingPhase phase;
};

// One output sample of length H; a is the acceleration at the start and is replaced by
// the one at the end.
using Stepper = std::function<void(const System&, State&, double H)>;

// Explicit Runge-Kutta with a Butcher tableau on (q, v), n steps per sample.
struct Tableau {
  std::vector<std::vector<double>> a;
  std::vector<double> b, c;
};

Tableau rk4() { return {{{}, {0.5}, {0, 0.5}, {0, 0, 1}}, {1 / 6.0, 1 / 3.0, 1 / 3.0, 1 / 6.0}, {0, 0.5, 0.5, 1}}; }

Tableau dopri5() {
  return {{{},
           {1 / 5.0},
           {3 / 40.0, 9 / 40.0},
           {44 / 45.0, -56 / 15.0, 32 / 9.0},
           {19372 / 6561.0, -25360 / 2187.0, 64448 / 6561.0, -212 / 729.0},
           {9017 / 3168.0, -355 / 33.0, 46732 / 5247.0, 49 / 176.0, -5103 / 18656.0}},
          {35 / 384.0, 0, 500 / 1113.0, 125 / 192.0, -2187 / 6784.0, 11 / 84.0},
          {0, 1 / 5.0, 3 / 10.0, 4 / 5.0, 8 / 9.0, 1}};
}

Stepper runge_kutta(const Tableau& t, int n) {
  return [t, n](const System& sys, State& s, double H) {
    const double h = H / n;
    const std::size_t stages = t.b.size();
    std::vector<Vector5> kq(stages), kv(stages);
    for (int step = 0; step < n; ++step) {
      for (std::size_t i = 0; i < stages; ++i) {
        Vector5 q = s.q, v = s.v;
        for (std::size_t j = 0; j < i; ++j) {
          if (t.a[i][j] == 0.0) continue;
          q += h * t.a[i][j] * kq[j];
          v += h * t.a[i][j] * kv[j];
        }
        kq[i] = v;
        kv[i] = i == 0 ? s.a : sys.acceleration(q, v, sys.advanced(s.phase, t.c[i] * h));
      }
      for (std::size_t i = 0; i < stages; ++i) {
        s.q += h * t.b[i] * kq[i];
        s.v += h * t.b[i] * kv[i];
      }
      s.phase = sys.advanced(s.phase, h);
      s.a = sys.acceleration(s.q, s.v, s.phase);
    }
  };
}

// Exponential integrators around the linearisation at the static equilibrium y* = (q*, 0):
// y' = L (y - y*) + N(y, t), L = [0 I; -M^-1 K  -M^-1 C] exact (matrix exponential and
// phi functions, computed once), N = F(y, t) - L (y - y*) the remainder, explicit. N has
// no displacement part (q' = v is linear), so only its acceleration part is kept.
struct PhiFunctions {
  Matrix10 e, phi1, phi2, phi3;
};

PhiFunctions phi_functions(const Matrix10& L, double h) {
  // exp of [hL I 0 0; 0 0 I 0; 0 0 0 I; 0 0 0 0] holds e^{hL}, phi1..phi3(hL) in its first block row.
  Eigen::Matrix<double, 40, 40> w = Eigen::Matrix<double, 40, 40>::Zero();
  w.block<10, 10>(0, 0) = h * L;
  w.block<10, 10>(0, 10).setIdentity();
  w.block<10, 10>(10, 20).setIdentity();
  w.block<10, 10>(20, 30).setIdentity();
  const Eigen::Matrix<double, 40, 40> x = w.exp();
  return {x.block<10, 10>(0, 0), x.block<10, 10>(0, 10), x.block<10, 10>(0, 20), x.block<10, 10>(0, 30)};
}

struct Linearisation {
  Vector5 q_eq;
  Matrix10 L;
};

Linearisation linearise(const BearingModel& model, const Vector5& load) {
  const StaticSolution st = solve_static(model, load);
  Matrix5 k, c;
  model.contact_force_and_stiffness(st.displacement, RollingPhase{}, &k, &c);
  const Matrix5 inv_m = model.mass_matrix().inverse();
  Linearisation lin;
  lin.q_eq = st.displacement;
  lin.L.setZero();
  lin.L.topRightCorner<5, 5>().setIdentity();
  lin.L.bottomLeftCorner<5, 5>() = -(inv_m * k);
  lin.L.bottomRightCorner<5, 5>() = -(inv_m * c);
  return lin;
}

struct Exponential {
  Linearisation lin;
  PhiFunctions full, half;
  Vector10 y(const State& s) const {
    Vector10 u;
    u << s.q - lin.q_eq, s.v;
    return u;
  }
  // Remainder as a 10-vector (zero displacement part).
  Vector10 remainder(const Vector10& u, const Vector5& a) const {
    Vector10 n = Vector10::Zero();
    n.tail<5>() = a - lin.L.bottomRows<5>() * u;
    return n;
  }
  void store(const System& sys, State& s, const Vector10& u, const RollingPhase& p) const {
    s.q = lin.q_eq + u.head<5>();
    s.v = u.tail<5>();
    s.phase = p;
    s.a = sys.acceleration(s.q, s.v, p);
  }
  Vector5 accel(const System& sys, const Vector10& u, const RollingPhase& p) const {
    return sys.acceleration(lin.q_eq + u.head<5>(), u.tail<5>(), p);
  }
  // One ETDRK4 step (Cox and Matthews) of h = the step `full` and `half` are for, from u at
  // phase p with the remainder nu there.
  Vector10 etdrk4_step(const System& sys, const Vector10& u, const Vector10& nu, const RollingPhase& p,
                       double h) const {
    const RollingPhase mid = sys.advanced(p, 0.5 * h), end = sys.advanced(p, h);
    const Vector10 a = half.e * u + 0.5 * h * half.phi1 * nu;
    const Vector10 na = remainder(a, accel(sys, a, mid));
    const Vector10 b = half.e * u + 0.5 * h * half.phi1 * na;
    const Vector10 nb = remainder(b, accel(sys, b, mid));
    const Vector10 c = half.e * a + 0.5 * h * half.phi1 * (2 * nb - nu);
    const Vector10 nc = remainder(c, accel(sys, c, end));
    return full.e * u + h * ((full.phi1 - 3 * full.phi2 + 4 * full.phi3) * nu +
                             2 * (full.phi2 - 2 * full.phi3) * (na + nb) + (4 * full.phi3 - full.phi2) * nc);
  }
};

// Exponential Euler (ETD1), 1 evaluation per step.
Stepper etd1(const Exponential& x, int n) {
  return [x, n](const System& sys, State& s, double H) {
    const double h = H / n;
    for (int i = 0; i < n; ++i) {
      const Vector10 u = x.y(s);
      const Vector10 un = x.full.e * u + h * x.full.phi1 * x.remainder(u, s.a);
      x.store(sys, s, un, sys.advanced(s.phase, h));
    }
  };
}

// ETD2RK (Cox and Matthews), 2 evaluations per step.
Stepper etd2rk(const Exponential& x, int n) {
  return [x, n](const System& sys, State& s, double H) {
    const double h = H / n;
    for (int i = 0; i < n; ++i) {
      const Vector10 u = x.y(s);
      const Vector10 n0 = x.remainder(u, s.a);
      const RollingPhase end = sys.advanced(s.phase, h);
      const Vector10 a = x.full.e * u + h * x.full.phi1 * n0;
      const Vector10 na = x.remainder(a, x.accel(sys, a, end));
      const Vector10 un = a + h * x.full.phi2 * (na - n0);
      x.store(sys, s, un, end);
    }
  };
}

// ETDRK4 (Cox and Matthews), 4 evaluations per step.
Stepper etdrk4(const Exponential& x, int n) {
  return [x, n](const System& sys, State& s, double H) {
    const double h = H / n;
    for (int i = 0; i < n; ++i) {
      const Vector10 u = x.y(s);
      x.store(sys, s, x.etdrk4_step(sys, u, x.remainder(u, s.a), s.phase, h), sys.advanced(s.phase, h));
    }
  };
}

// Exponential Adams methods (ETD multistep, Cox and Matthews): the remainder over a step is
// the polynomial through its values at the last steps, so a step costs one evaluation
// (explicit, ETD-AB) or two (predictor-corrector, PECE: ETD-AB predictor, ETD-Adams-Moulton
// corrector at the predicted end, then the end's evaluation, which is the output anyway).
// With backward differences nabla^j of the remainder, y_{n+1} = e^{hL} y_n + h sum_j W_j nabla^j:
// ETD-AB (at t_n): W = phi1, phi2, phi3 + phi2/2, phi4 + phi3 + phi2/3;
// ETD-AM (at t_{n+1}): W = phi1, phi2 - phi1, phi3 - phi2/2, phi4 - phi2/6.
// The first steps (too little history) are ETDRK4 steps. PEC: the corrector without the
// end's evaluation, 1 evaluation per step: the end's acceleration is the predicted one moved
// by the linear part, a_p + A (y_c - y_p), and the next step's remainder is the predicted one.
// e^{hL} and phi_1..phi_4(hL): the first block row of the exponential of
// [hL I 0 0 0; 0 0 I 0 0; ...; 0].
struct PhiAll {
  Matrix10 e, phi[4];
};

PhiAll phi_all(const Matrix10& L, double h) {
  Eigen::Matrix<double, 50, 50> w = Eigen::Matrix<double, 50, 50>::Zero();
  w.block<10, 10>(0, 0) = h * L;
  for (int k = 0; k < 4; ++k) w.block<10, 10>(10 * k, 10 * (k + 1)).setIdentity();
  const Eigen::Matrix<double, 50, 50> x = w.exp();
  PhiAll p;
  p.e = x.block<10, 10>(0, 0);
  for (int k = 0; k < 4; ++k) p.phi[k] = x.block<10, 10>(0, 10 * (k + 1));
  return p;
}

Matrix10 phi4_function(const Matrix10& L, double h) { return phi_all(L, h).phi[3]; }

enum class AdamsMode { Explicit, Pece, Pec };

Stepper etd_adams(const Exponential& x, const Matrix10& phi4, int n, int order, AdamsMode mode) {
  const PhiFunctions& f = x.full;
  std::vector<Matrix10> ab = {f.phi1, f.phi2, f.phi3 + 0.5 * f.phi2, phi4 + f.phi3 + f.phi2 / 3.0};
  std::vector<Matrix10> am = {f.phi1, f.phi2 - f.phi1, f.phi3 - 0.5 * f.phi2, phi4 - f.phi2 / 6.0};
  auto history = std::make_shared<std::vector<Vector10>>();  // remainders, newest first
  return [=](const System& sys, State& s, double H) {
    const double h = H / n;
    static const double binomial[4][4] = {{1, 0, 0, 0}, {1, -1, 0, 0}, {1, -2, 1, 0}, {1, -3, 3, -1}};
    // sum_j W_j nabla^j of the values v[0] (newest), v[1], ...
    const auto combine = [&](const std::vector<Matrix10>& w, const Vector10* v) {
      Vector10 sum = Vector10::Zero();
      for (int j = 0; j < order; ++j) {
        Vector10 nabla = Vector10::Zero();
        for (int i = 0; i <= j; ++i) nabla += binomial[j][i] * v[i];
        sum += w[j] * nabla;
      }
      return sum;
    };
    for (int i = 0; i < n; ++i) {
      const Vector10 u = x.y(s);
      const Vector10 nu = x.remainder(u, s.a);
      history->insert(history->begin(), nu);
      if (static_cast<int>(history->size()) > order) history->pop_back();
      const RollingPhase end = sys.advanced(s.phase, h);
      if (static_cast<int>(history->size()) < order) {
        x.store(sys, s, x.etdrk4_step(sys, u, nu, s.phase, h), end);
        continue;
      }
      const Vector10 eu = x.full.e * u;
      Vector10 un = eu + h * combine(ab, history->data());
      if (mode != AdamsMode::Explicit) {
        std::vector<Vector10> v(order);
        const Vector5 a_p = x.accel(sys, un, end);
        v[0] = x.remainder(un, a_p);
        for (int k = 1; k < order; ++k) v[k] = (*history)[k - 1];
        const Vector10 predicted = un;
        un = eu + h * combine(am, v.data());
        if (mode == AdamsMode::Pec) {
          s.q = x.lin.q_eq + un.head<5>();
          s.v = un.tail<5>();
          s.phase = end;
          s.a = a_p + x.lin.L.bottomRows<5>() * (un - predicted);
          continue;
        }
      }
      x.store(sys, s, un, end);
    }
  };
}

// Exponential Adams PEC with a step that does not divide the sample: n steps per m samples
// (h = m H / n), the output at the sample times from the corrector's interpolant within the
// step that holds them: y(t_n + theta h) = e^{theta h L} y_n + h int_0^theta e^{(theta - s) h L} p(s) ds,
// p the cubic through the remainders at s = 1, 0, -1, -2, and a = A y + p(theta).
Stepper etd_pec_dense(const Exponential& x0, int n, int m, double H) {
  struct Dense {
    bool started = false;
    long long steps = 0, samples = 0;
    Vector10 y, y_prev;
    Vector5 a;
    RollingPhase phase, phase_prev;
    std::vector<Vector10> history;                        // remainders at the last step starts, newest first
    std::vector<std::pair<long long, PhiAll>> theta_phi;  // keyed by the numerator theta * m
  };
  const double h = H * m / n;
  Exponential x = x0;
  x.full = phi_functions(x0.lin.L, h);
  x.half = phi_functions(x0.lin.L, 0.5 * h);
  const Matrix10 phi4 = phi4_function(x0.lin.L, h);
  const PhiFunctions& f = x.full;
  const std::vector<Matrix10> ab = {f.phi1, f.phi2, f.phi3 + 0.5 * f.phi2, phi4 + f.phi3 + f.phi2 / 3.0};
  const std::vector<Matrix10> am = {f.phi1, f.phi2 - f.phi1, f.phi3 - 0.5 * f.phi2, phi4 - f.phi2 / 6.0};
  // Monomial coefficients of the Lagrange cubic through s = 1, 0, -1, -2.
  Eigen::Matrix4d vandermonde;
  const double nodes[4] = {1, 0, -1, -2};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) vandermonde(i, k) = std::pow(nodes[i], k);
  const Eigen::Matrix4d to_monomial = vandermonde.inverse();
  auto st = std::make_shared<Dense>();
  return [=](const System& sys, State& s, double) {
    static const double binomial[4][4] = {{1, 0, 0, 0}, {1, -1, 0, 0}, {1, -2, 1, 0}, {1, -3, 3, -1}};
    const auto combine = [&](const std::vector<Matrix10>& w, const Vector10* v) {
      Vector10 sum = Vector10::Zero();
      for (int j = 0; j < 4; ++j) {
        Vector10 nabla = Vector10::Zero();
        for (int i = 0; i <= j; ++i) nabla += binomial[j][i] * v[i];
        sum += w[j] * nabla;
      }
      return sum;
    };
    Dense& d = *st;
    if (!d.started) {
      d.started = true;
      d.y = x.y(s);
      d.a = s.a;
      d.phase = s.phase;
    }
    ++d.samples;
    while (d.steps * m < d.samples * n) {
      ++d.steps;
      const Vector10 u = d.y;
      const Vector10 nu = x.remainder(u, d.a);
      d.history.insert(d.history.begin(), nu);
      if (d.history.size() > 4) d.history.pop_back();
      d.y_prev = u;
      d.phase_prev = d.phase;
      const RollingPhase end = sys.advanced(d.phase, h);
      if (d.history.size() < 4) {
        d.y = x.etdrk4_step(sys, u, nu, d.phase, h);
        d.a = x.accel(sys, d.y, end);
      } else {
        const Vector10 eu = x.full.e * u;
        const Vector10 yp = eu + h * combine(ab, d.history.data());
        const Vector5 a_p = x.accel(sys, yp, end);
        std::vector<Vector10> v(4);
        v[0] = x.remainder(yp, a_p);
        for (int k = 1; k < 4; ++k) v[k] = d.history[k - 1];
        d.y = eu + h * combine(am, v.data());
        d.a = a_p + x.lin.L.bottomRows<5>() * (d.y - yp);
      }
      d.phase = end;
    }
    // The sample lies at theta = (samples n - (steps - 1) m) / m of the last step.
    const long long num = d.samples * n - (d.steps - 1) * m;
    if (num == m || d.history.size() < 3) {
      // At the step's end; while starting (no interpolant yet) the step end's values stand
      // in (the first half of the run is not compared).
      s.q = x.lin.q_eq + d.y.head<5>();
      s.v = d.y.tail<5>();
      s.a = d.a;
      s.phase = d.phase;
      return;
    }
    const double theta = static_cast<double>(num) / m;
    auto it = std::find_if(d.theta_phi.begin(), d.theta_phi.end(), [&](const auto& e) { return e.first == num; });
    if (it == d.theta_phi.end()) {
      d.theta_phi.emplace_back(num, phi_all(x.lin.L, theta * h));
      it = d.theta_phi.end() - 1;
    }
    const PhiAll& p = it->second;
    const Vector10 r_end = x.remainder(d.y, d.a);
    const Vector10 r[4] = {r_end, d.history[0], d.history[1], d.history[2]};
    Vector10 out = p.e * d.y_prev;
    Vector10 r_theta = Vector10::Zero();
    double factorial = 1.0;
    for (int k = 0; k < 4; ++k) {
      if (k > 0) factorial *= k;
      Vector10 c = Vector10::Zero();
      for (int i = 0; i < 4; ++i) c += to_monomial(k, i) * r[i];
      out += h * std::pow(theta, k + 1) * factorial * (p.phi[k] * c);
      r_theta += std::pow(theta, k) * c;
    }
    s.q = x.lin.q_eq + out.head<5>();
    s.v = out.tail<5>();
    s.a = x.lin.L.bottomRows<5>() * out + r_theta.tail<5>();
    s.phase = sys.advanced(d.phase_prev, theta * h);
  };
}

struct Result {
  double a_rms = 0, level_db = 0, evals_per_sample = 0, realtime_factor = 0;
  std::vector<double> ax;
  bool diverged = false;
};

Result run(const Case& c, const BearingModel& model, const Stepper& stepper, double duration, double rate) {
  System sys(model, c.load, c.ring_speed_rad_s);
  State s;
  s.q = solve_static(model, c.load).displacement;
  s.v.setZero();
  s.phase = RollingPhase{};
  s.a = sys.acceleration(s.q, s.v, s.phase);
  sys.evaluations = 0;
  const auto samples = static_cast<std::size_t>(std::lround(duration * rate));
  Result r;
  r.ax.reserve(samples);
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < samples; ++i) {
    stepper(sys, s, 1.0 / rate);
    if (!s.a.allFinite() || s.q.norm() > 1e-2) {
      r.diverged = true;
      return r;
    }
    r.ax.push_back(s.a(0));
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.realtime_factor = duration / wall;
  r.evals_per_sample = static_cast<double>(sys.evaluations) / samples;
  r.ax.erase(r.ax.begin(), r.ax.begin() + samples / 2);  // start transient
  double mean = 0;
  for (double x : r.ax) mean += x;
  mean /= r.ax.size();
  double ss = 0;
  for (double& x : r.ax) {
    x -= mean;
    ss += x * x;
  }
  r.a_rms = std::sqrt(ss / r.ax.size());
  r.level_db = 20.0 * std::log10(r.a_rms / 9.81e-3);
  return r;
}

// Largest level error (dB) of the octave bands 63 Hz .. 4 kHz holding >= 1 % of the energy.
double band_error_db(const std::vector<double>& x, const std::vector<double>& ref, double rate) {
  const std::size_t n = fft_friendly_length(ref.size());
  const std::vector<double> xa(x.end() - n, x.end()), ra(ref.end() - n, ref.end());
  const Spectrum sx = amplitude_spectrum(xa, rate), sr = amplitude_spectrum(ra, rate);
  double total = 0;
  for (double a : sr.amplitude) total += a * a;
  double worst = 0;
  for (double centre = 62.5; centre <= 4000.0 * 1.01; centre *= 2) {
    double ex = 0, er = 0;
    for (std::size_t k = 0; k < sr.amplitude.size(); ++k) {
      const double f = sr.frequency_hz(k);
      if (f < centre / std::sqrt(2.0) || f >= centre * std::sqrt(2.0)) continue;
      ex += sx.amplitude[k] * sx.amplitude[k];
      er += sr.amplitude[k] * sr.amplitude[k];
    }
    if (er < 0.01 * total) continue;
    worst = std::max(worst, std::abs(10.0 * std::log10(ex / er)));
  }
  return worst;
}

}  // namespace

// Round trip of a two-thread spin barrier (the cost of splitting one force evaluation
// over two cores: one release and one join per evaluation), median of 2000 batches.
void barrier_round_trip() {
  std::atomic<long> go{0}, done{0};
  std::atomic<bool> stop{false};
  std::thread worker([&] {
    long seen = 0;
    while (!stop.load(std::memory_order_relaxed)) {
      const long g = go.load(std::memory_order_acquire);
      if (g == seen) continue;
      seen = g;
      done.store(g, std::memory_order_release);
    }
  });
  std::vector<double> ns;
  long k = 0;
  for (int batch = 0; batch < 2000; ++batch) {
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < 100; ++i) {
      go.store(++k, std::memory_order_release);
      while (done.load(std::memory_order_acquire) != k) {
      }
    }
    ns.push_back(std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - t0).count() / 100.0);
  }
  stop = true;
  worker.join();
  std::sort(ns.begin(), ns.end());
  std::printf("two-thread spin barrier round trip: median %.0f ns, 10th percentile %.0f ns, 90th percentile %.0f ns\n",
              ns[ns.size() / 2], ns[ns.size() / 10], ns[9 * ns.size() / 10]);
}

// The production path (BearingDynamics: ball subsets, automatic step), both methods,
// against its own RK4 x16; a_rms and L of run_simulation.
void production(const Case& c, double duration) {
  const BearingModel model(c.config);
  const auto run_it = [&](IntegrationMethod m, int substeps) {
    SimulationRequest req;
    req.load = c.load;
    req.ring_speed_rad_s = c.ring_speed_rad_s;
    req.duration_s = duration;
    req.substeps = substeps;
    req.method = m;
    return run_simulation(model, req);
  };
  const SimulationSummary ref = run_it(IntegrationMethod::Rk4, 16);
  for (const auto& [name, m] : {std::pair<const char*, IntegrationMethod>{"RK4", IntegrationMethod::Rk4},
                                {"ETDRK4", IntegrationMethod::ExponentialRk4},
                                {"exponential Adams PECE", IntegrationMethod::ExponentialAdams},
                                {"exponential Adams PEC", IntegrationMethod::ExponentialAdamsPec}}) {
    const SimulationSummary s = run_it(m, 0);
    const int per_step = m == IntegrationMethod::ExponentialAdams      ? 2
                         : m == IntegrationMethod::ExponentialAdamsPec ? 1
                                                                       : 4;
    const double evaluations = per_step * s.substeps;
    std::printf("| %s | BearingDynamics %s, automatic (x%g) | %g | %+.2f %% | %+.3f | - | %.2f |\n", c.name.c_str(),
                name, s.substeps, evaluations, 100.0 * (s.a_rms_x / ref.a_rms_x - 1.0), s.level_db - ref.level_db,
                s.realtime_factor);
    std::fflush(stdout);
  }
}

// Race spalls on the CT bearing at whole steps (the production path, 1 and 2 steps per
// sample forced) against RK4 x16 at the same output rate: a_rms of x and, in brackets, the
// worst octave band; * marks the steps the automatic rule takes. Why a spall keeps the CT
// bearing at 2 steps per sample (docs/model.md 10.5).
void spall_steps(double duration, const std::string& only) {
  struct Variant {
    std::string name;
    BearingConfig config;
    Vector5 load;
    double rpm;
  };
  const Vector5 paper = load5(6800, 0, 0, 0, 2100);
  const BearingConfig defects = test::ct_gantry_with_defects(BEARING_SIM_SOURCE_DIR);
  const auto with_spall = [](BearingConfig c, Surface surface, double width_m, double depth_m) {
    Spall& s = c.imperfections.spalls.at(0);
    s.surface = surface;
    s.width_m = width_m;
    s.depth_m = depth_m;
    if (surface == Surface::OuterRace) s.position_rad = 0.0;
    return c;
  };
  BearingConfig spall_only = bearing("ct_gantry_lyc.yaml");
  spall_only.imperfections.spalls = defects.imperfections.spalls;
  BearingConfig physical = bearing("ct_gantry_physical.yaml");
  physical.imperfections = defects.imperfections;
  const std::vector<Variant> variants{
      {"waviness + 2 mm x 20 um inner-race spall", defects, paper, 180.0},
      {"the same at 0.3 times the load", defects, Vector5(0.3 * paper), 180.0},
      {"the same at 3 times the load", defects, Vector5(3.0 * paper), 180.0},
      {"the same at 60 rpm", defects, paper, 60.0},
      {"waviness + 2 mm x 20 um outer-race spall", with_spall(defects, Surface::OuterRace, 2e-3, 20e-6), paper, 180.0},
      {"waviness + 6 mm x 50 um inner-race spall", with_spall(defects, Surface::InnerRace, 6e-3, 50e-6), paper, 180.0},
      {"waviness + 1 mm x 10 um inner-race spall", with_spall(defects, Surface::InnerRace, 1e-3, 10e-6), paper, 180.0},
      {"waviness + 0.5 mm x 10 um inner-race spall", with_spall(defects, Surface::InnerRace, 0.5e-3, 10e-6), paper,
       180.0},
      {"2 mm x 20 um inner-race spall alone", spall_only, paper, 180.0},
      {"with the rotor: waviness + 2 mm x 20 um spall", physical, paper, 180.0},
      {"with the rotor: waviness + 1 mm x 10 um spall", with_spall(physical, Surface::InnerRace, 1e-3, 10e-6), paper,
       180.0},
  };
  const double rates[] = {10000.0, 8000.0, 7000.0, 12000.0};
  std::printf("| case | largest ball's load share | lambda h per sample at 10 kHz |");
  for (const double rate : rates) std::printf(" %.0f kHz x1 | %.0f kHz x2 |", rate / 1000.0, rate / 1000.0);
  std::printf("\n|---|---|---|");
  for (std::size_t i = 0; i < 2 * std::size(rates); ++i) std::printf("---|");
  std::printf("\n");
  for (const Variant& v : variants) {
    if (!only.empty() && v.name.find(only) == std::string::npos) continue;
    const BearingModel model(v.config);
    const StaticSolution statics = solve_static(model, v.load);
    double largest = 0.0, total = 0.0;
    for (const BallState& b : statics.balls) {
      largest = std::max(largest, b.load_N);
      total += b.load_N;
    }
    std::printf("| %s | %.2f %% | %.2f |", v.name.c_str(), 100.0 * largest / total,
                BearingDynamics::fastest_rate_rad_s(model, v.load) / 10000.0);
    for (const double rate : rates) {
      const auto run_it = [&](IntegrationMethod m, int substeps, std::vector<double>* ax) {
        SimulationRequest req;
        req.load = v.load;
        req.ring_speed_rad_s = v.rpm * 2.0 * kPi / 60.0;
        req.duration_s = duration;
        req.sample_rate_hz = rate;
        req.substeps = substeps;
        req.method = m;
        return run_simulation(model, req, [ax](const DynamicSample& s) { ax->push_back(s.acceleration(0)); });
      };
      std::vector<double> ref_ax;
      const SimulationSummary ref = run_it(IntegrationMethod::Rk4, 16, &ref_ax);
      ref_ax.erase(ref_ax.begin(), ref_ax.begin() + ref_ax.size() / 2);  // start transient, as run_simulation's a_rms
      const int automatic =
          BearingDynamics::choose_step_ratio(model, v.load, rate, IntegrationMethod::ExponentialAdamsPec).steps;
      for (const int steps : {1, 2}) {
        std::vector<double> ax;
        const SimulationSummary s = run_it(IntegrationMethod::ExponentialAdamsPec, steps, &ax);
        ax.erase(ax.begin(), ax.begin() + ax.size() / 2);
        std::printf(" %s%+.2f %% (%.2f) |", steps == automatic ? "*" : "", 100.0 * (s.a_rms_x / ref.a_rms_x - 1.0),
                    band_error_db(ax, ref_ax, rate));
      }
    }
    std::printf("\n");
    std::fflush(stdout);
  }
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "production") {
    const double duration = argc > 2 ? std::stod(argv[2]) : 0.3;
    std::printf(
        "| case | method | evaluations per sample | a_rms error | L error (dB) | worst octave band (dB) | real-time "
        "factor |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    for (const Case& c : cases()) production(c, duration);
    // Cost of one relinearization (static solution and two matrix exponentials): the
    // sample after a load change of 30%, less an ordinary sample.
    const Case ct = cases().front();
    BearingDynamics d(BearingModel(ct.config), ct.load, ct.ring_speed_rad_s);
    for (int i = 0; i < 100; ++i) d.step();
    double with = 0, without = 0;
    for (int i = 0; i < 200; ++i) {
      for (int k = 0; k < BearingDynamics::kSamplesPerLinearization; ++k) d.step();
      d.set_load(i % 2 ? ct.load : Vector5(1.3 * ct.load));
      auto t0 = std::chrono::steady_clock::now();
      d.step();
      auto t1 = std::chrono::steady_clock::now();
      d.step();
      auto t2 = std::chrono::steady_clock::now();
      with += std::chrono::duration<double, std::micro>(t1 - t0).count();
      without += std::chrono::duration<double, std::micro>(t2 - t1).count();
    }
    {
      const BearingModel m(ct.config);
      const auto t0 = std::chrono::steady_clock::now();
      for (int i = 0; i < 20; ++i) linearise(m, ct.load);
      const auto t1 = std::chrono::steady_clock::now();
      const Linearisation lin = linearise(m, ct.load);
      for (int i = 0; i < 20; ++i) phi_functions(lin.L, 1e-4);
      const auto t2 = std::chrono::steady_clock::now();
      std::printf("static solution and stiffness %.0f us, one 40x40 matrix exponential %.0f us\n",
                  std::chrono::duration<double, std::micro>(t1 - t0).count() / 20,
                  std::chrono::duration<double, std::micro>(t2 - t1).count() / 20);
    }
    std::printf("\nCT bearing: a sample with a relinearization %.0f us, without %.0f us (%llu linearizations)\n",
                with / 200, without / 200, static_cast<unsigned long long>(d.linearizations()));
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "spall_steps") {
    spall_steps(argc > 2 ? std::stod(argv[2]) : 0.3, argc > 3 ? argv[3] : "");
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "barrier") {
    barrier_round_trip();
    return 0;
  }
  double duration = 0.3;
  if (argc > 1) {
    char* end = nullptr;
    duration = std::strtod(argv[1], &end);
    if (end == argv[1] || *end != '\0' || !(duration > 0.0)) {
      std::fprintf(
          stderr,
          "usage: bearing_sim_integrator_study [duration_s > 0] [case name part] [method name part]\n"
          "       bearing_sim_integrator_study production [duration_s] | spall_steps [duration_s] | barrier\n");
      return 2;
    }
  }
  const double rate = 10000.0;
  std::printf("Integrator study: %.2f s simulated per run, output %.0f Hz, all balls integrated\n\n", duration, rate);
  std::printf(
      "| case | method | evaluations per sample | a_rms error | L error (dB) | worst octave band (dB) | real-time "
      "factor |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  const std::string only = argc > 2 ? argv[2] : "";
  const std::string method_only = argc > 3 ? argv[3] : "";
  for (const Case& c : cases()) {
    if (!only.empty() && c.name.find(only) == std::string::npos) continue;
    const BearingModel model(c.config);
    const double rate_max = BearingDynamics::fastest_rate_rad_s(model, c.load);
    const Exponential x{linearise(model, c.load), {}, {}};
    // For n steps per sample.
    const auto exponential = [&x, rate](int n) {
      Exponential e = x;
      const double h = 1.0 / rate / n;
      e.full = phi_functions(x.lin.L, h);
      e.half = phi_functions(x.lin.L, 0.5 * h);
      return e;
    };
    std::fprintf(stderr, "%s: %d balls, fastest rate %.0f rad/s (x 100 us = %.2f), automatic RK4 steps %d\n",
                 c.name.c_str(), model.ball_count(), rate_max, rate_max / rate,
                 BearingDynamics::choose_substeps(model, c.load, rate));
    const Result ref = run(c, model, runge_kutta(rk4(), 16), duration, rate);
    std::fprintf(stderr, "%s: %.2f us per evaluation (all balls)\n", c.name.c_str(),
                 1e6 / (ref.realtime_factor * rate * ref.evals_per_sample));
    std::printf("| %s | RK4 x16 (reference) | %.0f | a_rms %.4e m/s^2 | L %.2f dB | - | %.2f |\n", c.name.c_str(),
                ref.evals_per_sample, ref.a_rms, ref.level_db, ref.realtime_factor);
    const std::vector<std::pair<std::string, Stepper>> methods = {
        {"RK4 x1", runge_kutta(rk4(), 1)},
        {"RK4 x2", runge_kutta(rk4(), 2)},
        {"RK4 x3", runge_kutta(rk4(), 3)},
        {"RK4 x4", runge_kutta(rk4(), 4)},
        {"RK4 x8", runge_kutta(rk4(), 8)},
        {"RK4 x32", runge_kutta(rk4(), 32)},
        {"DOPRI5 x1", runge_kutta(dopri5(), 1)},
        {"DOPRI5 x2", runge_kutta(dopri5(), 2)},
        {"ETD1 x1", etd1(exponential(1), 1)},
        {"ETD1 x2", etd1(exponential(2), 2)},
        {"ETD1 x4", etd1(exponential(4), 4)},
        {"ETD2RK x1", etd2rk(exponential(1), 1)},
        {"ETD2RK x2", etd2rk(exponential(2), 2)},
        {"ETDRK4 x1", etdrk4(exponential(1), 1)},
        {"ETDRK4 x2", etdrk4(exponential(2), 2)},
        {"ETDRK4 x3", etdrk4(exponential(3), 3)},
        {"ETDRK4 x4", etdrk4(exponential(4), 4)},
        {"ETDRK4 x6", etdrk4(exponential(6), 6)},
        {"ETD-AB2 x1", etd_adams(exponential(1), phi4_function(x.lin.L, 1.0 / rate), 1, 2, AdamsMode::Explicit)},
        {"ETD-AB3 x1", etd_adams(exponential(1), phi4_function(x.lin.L, 1.0 / rate), 1, 3, AdamsMode::Explicit)},
        {"ETD-AB4 x1", etd_adams(exponential(1), phi4_function(x.lin.L, 1.0 / rate), 1, 4, AdamsMode::Explicit)},
        {"ETD-AB4 x2", etd_adams(exponential(2), phi4_function(x.lin.L, 0.5 / rate), 2, 4, AdamsMode::Explicit)},
        {"ETD-ABM3 PECE x1", etd_adams(exponential(1), phi4_function(x.lin.L, 1.0 / rate), 1, 3, AdamsMode::Pece)},
        {"ETD-ABM4 PECE x1", etd_adams(exponential(1), phi4_function(x.lin.L, 1.0 / rate), 1, 4, AdamsMode::Pece)},
        {"ETD-ABM4 PECE x2", etd_adams(exponential(2), phi4_function(x.lin.L, 0.5 / rate), 2, 4, AdamsMode::Pece)},
        {"ETD-ABM4 PEC x1", etd_adams(exponential(1), phi4_function(x.lin.L, 1.0 / rate), 1, 4, AdamsMode::Pec)},
        {"ETD-ABM4 PEC x2", etd_adams(exponential(2), phi4_function(x.lin.L, 0.5 / rate), 2, 4, AdamsMode::Pec)},
        {"ETD-ABM4 PEC x3", etd_adams(exponential(3), phi4_function(x.lin.L, 1.0 / 3.0 / rate), 3, 4, AdamsMode::Pec)},
        {"ETD-ABM4 PEC x4", etd_adams(exponential(4), phi4_function(x.lin.L, 0.25 / rate), 4, 4, AdamsMode::Pec)},
        {"ETD-ABM4 PEC x5/4", etd_pec_dense(x, 5, 4, 1.0 / rate)},
        {"ETD-ABM4 PEC x3/2", etd_pec_dense(x, 3, 2, 1.0 / rate)},
        {"ETD-ABM4 PEC x11/4", etd_pec_dense(x, 11, 4, 1.0 / rate)},
    };
    for (const auto& [name, stepper] : methods) {
      if (!method_only.empty() && name.find(method_only) == std::string::npos) continue;
      const Result r = run(c, model, stepper, duration, rate);
      if (r.diverged) {
        std::printf("| %s | %s | - | diverged | | | |\n", c.name.c_str(), name.c_str());
        continue;
      }
      std::printf("| %s | %s | %.3g | %+.2f %% | %+.3f | %.2f | %.2f |\n", c.name.c_str(), name.c_str(),
                  r.evals_per_sample, 100.0 * (r.a_rms / ref.a_rms - 1.0), r.level_db - ref.level_db,
                  band_error_db(r.ax, ref.ax, rate), r.realtime_factor);
      std::fflush(stdout);
    }
  }
  return 0;
}
