// The flexible ring's exponential Adams integrator (docs/model.md 18.4): exact on a linear
// system at any step, converging on a forced one, its load-frame contact force the ring-frame
// force rotated, its SIMD kernel the scalar loop's on every target, and the CT ring's response
// that of converged RK4.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>
#include <utility>
#include <vector>

#include <unsupported/Eigen/MatrixFunctions>

#include "../../src/core/phi_functions.hpp"
#include "../../src/core/small_products.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/flexible_adams.hpp"
#include "bearing_sim/core/flexible_dynamics.hpp"
#include "simd_targets.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

using test::kPi;

// x'' = -w^2 x - 2 zeta w x' + f cos(W t): displacement at t from rest at 0, closed form.
double forced_oscillator(double w, double zeta, double f, double big_w, double t) {
  const std::complex<double> amplitude = f / std::complex<double>(w * w - big_w * big_w, 2.0 * zeta * w * big_w);
  const auto particular = [&](double s) {
    return std::real(amplitude * std::exp(std::complex<double>(0.0, big_w * s)));
  };
  const auto particular_rate = [&](double s) {
    return std::real(std::complex<double>(0.0, big_w) * amplitude * std::exp(std::complex<double>(0.0, big_w * s)));
  };
  const double wd = w * std::sqrt(1.0 - zeta * zeta);
  const double a = -particular(0.0), b = (-particular_rate(0.0) + zeta * w * a) / wd;
  return particular(t) + std::exp(-zeta * w * t) * (a * std::cos(wd * t) + b * std::sin(wd * t));
}

TEST(FlexibleAdams, LinearSystemIsExactAtStepsBeyondItsFastestPeriod) {
  // Two oscillators, 100 and 10,000 rad/s, 2 % damped, stepped at w h = 3 for the fast one
  // (RK4 is unstable beyond 2.8): the remainder is zero, so the matrix exponential is all.
  const double w1 = 100.0, w2 = 1e4, zeta = 0.02, h = 3.0 / w2;
  const FlexibleAdams::Acceleration accel = [&](const Eigen::VectorXd& z, const Eigen::VectorXd& v, double) {
    Eigen::VectorXd a(2);
    a << -w1 * w1 * z[0] - 2.0 * zeta * w1 * v[0], -w2 * w2 * z[1] - 2.0 * zeta * w2 * v[1];
    return a;
  };
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(2), z0 = Eigen::Vector2d(1e-3, 2e-6);
  FlexibleAdams adams(accel, zero, Eigen::VectorXd::Constant(2, 1e-9), Eigen::VectorXd::Constant(2, 1e-6), z0, zero, h,
                      0.0);
  EXPECT_NEAR(adams.highest_rate_rad_s(), w2, 1e-6 * w2);
  const int steps = 200;
  for (int i = 0; i < steps; ++i) adams.step(accel);
  const double t = steps * h;
  for (int k = 0; k < 2; ++k) {
    const double w = k ? w2 : w1, wd = w * std::sqrt(1.0 - zeta * zeta);
    const double exact = z0[k] * std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t));
    // Difference Jacobian of a linear function: exact to rounding (1e-16 / 1e-9 relative).
    EXPECT_NEAR(adams.position()[k], exact, 1e-7 * std::abs(z0[k])) << "oscillator " << k;
  }
}

TEST(FlexibleAdams, ForcedOscillatorConvergesAtThirdOrderOrBetter) {
  // The forcing is the remainder, extrapolated by the Adams polynomials: halving the step
  // must cut the error by 2^3 at least (4th-order steps after a start of lower order).
  const double w = 2.0 * kPi * 300.0, zeta = 0.05, f = 1.0, big_w = 2.0 * kPi * 50.0, end_s = 0.1;
  const FlexibleAdams::Acceleration accel = [&](const Eigen::VectorXd& z, const Eigen::VectorXd& v, double t) {
    return Eigen::VectorXd::Constant(1, -w * w * z[0] - 2.0 * zeta * w * v[0] + f * std::cos(big_w * t));
  };
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(1);
  const double exact = forced_oscillator(w, zeta, f, big_w, end_s);
  std::vector<double> errors;
  for (const double h : {1e-3, 5e-4, 2.5e-4}) {
    FlexibleAdams adams(accel, zero, Eigen::VectorXd::Constant(1, 1e-9), Eigen::VectorXd::Constant(1, 1e-6), zero, zero,
                        h, 0.0);
    const int steps = static_cast<int>(std::lround(end_s / h));
    for (int i = 0; i < steps; ++i) adams.step(accel);
    errors.push_back(std::abs(adams.position()[0] - exact));
  }
  EXPECT_LT(errors[2], 1e-4 * std::abs(exact));
  EXPECT_GT(errors[0] / errors[1], 8.0);
  EXPECT_GT(errors[1] / errors[2], 8.0);
}

TEST(FlexibleAdams, ItsMatrixProductsAreEigensOnEveryTarget) {
  // out = base + m x at the step's sizes (50 x 50, 50 x 100) and at sizes below and between
  // the vectors' lanes: fused multiply-adds and the order of the sums differ, 1e-14 relative.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  test::for_each_simd_target([&] {
    for (const auto& [rows, cols] : {std::pair{50, 50}, {50, 100}, {25, 50}, {37, 9}, {3, 5}, {13, 7}, {9, 1}}) {
      const Eigen::MatrixXd m = Eigen::MatrixXd::NullaryExpr(rows, cols, [&] { return noise(rng); });
      const Eigen::VectorXd x = Eigen::VectorXd::NullaryExpr(cols, [&] { return noise(rng); });
      const Eigen::VectorXd base = Eigen::VectorXd::NullaryExpr(rows, [&] { return noise(rng); });
      Eigen::VectorXd out(rows), plain(rows);
      detail::multiply_add(rows, cols, m.data(), x.data(), base.data(), out.data());
      detail::multiply_add(rows, cols, m.data(), x.data(), nullptr, plain.data());
      const Eigen::VectorXd expected = base + m * x;
      const double scale = std::sqrt(static_cast<double>(cols)) * 10.0;
      for (int i = 0; i < rows; ++i) {
        EXPECT_NEAR(out[i], expected[i], 1e-14 * scale) << rows << "x" << cols << " row " << i;
        EXPECT_NEAR(plain[i], expected[i] - base[i], 1e-14 * scale) << rows << "x" << cols << " row " << i;
      }
    }
  });
}

// The CT bearing with its flexible outer ring, near its equilibrium under the operating load.
struct CtRing {
  FlexibleBearing bearing{BearingModel(load_bearing_config(test::bearing_file("ct_gantry_flexible.yaml")))};
  FlexibleStaticSolution equilibrium = solve_flexible_static(bearing, test::ct_load());
};

// phi_k(z) = (e^z - sum_{j<k} z^j / j!) / z^k, closed form (no cancellation for |z| >= 1).
std::complex<double> phi_closed_form(int k, std::complex<double> z) {
  std::complex<double> sum = std::exp(z), term = 1.0;
  for (int j = 0; j < k; ++j) {
    sum -= term;
    term *= z / static_cast<double>(j + 1);
  }
  return sum / std::pow(z, k);
}

TEST(PhiFunctions, RotationBlocksGiveTheClosedFormOfTheirEigenvalues) {
  // [a -b; b a] acts as z = a + i b: its phi_k is [Re -Im; Im Re] of phi_k(z). Rates from a
  // slow damped mode to |z| = 40 (the scaling's 7 doublings).
  const std::vector<std::complex<double>> zs = {{-0.02, 1.0}, {-0.3, 3.0}, {-1.0, 12.0}, {-2.0, 40.0}, {-5.0, 0.5}};
  const int m = 2 * static_cast<int>(zs.size());
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
  for (std::size_t i = 0; i < zs.size(); ++i)
    a.block<2, 2>(2 * i, 2 * i) << zs[i].real(), -zs[i].imag(), zs[i].imag(), zs[i].real();
  const detail::PhiFunctions f = detail::phi_functions(a, m);
  for (int k = 0; k <= 4; ++k) {
    const Eigen::MatrixXd& got = k == 0 ? f.exp : f.phi[k - 1];
    for (std::size_t i = 0; i < zs.size(); ++i) {
      const std::complex<double> want = phi_closed_form(k, zs[i]);
      // Each doubling adds a few roundings of the size of phi_k: 1e-13 of it with margin.
      const double tolerance = 1e-12 * std::max(1.0, std::abs(want));
      EXPECT_NEAR(got(2 * i, 2 * i), want.real(), tolerance) << "phi_" << k << " at z = " << zs[i];
      EXPECT_NEAR(got(2 * i + 1, 2 * i), want.imag(), tolerance) << "phi_" << k << " at z = " << zs[i];
    }
  }
}

TEST(PhiFunctions, AreTheBlockRowOfTheAugmentedExponential) {
  // A non-normal matrix of norm 8: e^A and the right halves of phi_1..4 are the first block
  // row of exp([A I 0 0 0; 0 0 I 0 0; ...; 0]) (Eigen's Pade scaling and squaring, 5 times the size).
  const int m = 30, half = m / 2;
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd a(m, m);
  for (int i = 0; i < m * m; ++i) a.data()[i] = normal(random);
  a *= 8.0 / a.cwiseAbs().colwise().sum().maxCoeff();
  a.diagonal().array() -= 2.0;  // decaying, as a damped structure
  Eigen::MatrixXd big = Eigen::MatrixXd::Zero(5 * m, 5 * m);
  big.topLeftCorner(m, m) = a;
  for (int k = 0; k < 4; ++k) big.block(m * k, m * (k + 1), m, m).setIdentity();
  const Eigen::MatrixXd e = big.exp();
  const detail::PhiFunctions f = detail::phi_functions(a, half);
  // Both are accurate to rounding times the scaling's doublings: 1e-12 of the largest entry.
  EXPECT_LE((f.exp - e.topLeftCorner(m, m)).cwiseAbs().maxCoeff(), 1e-12 * e.topLeftCorner(m, m).cwiseAbs().maxCoeff());
  for (int k = 1; k <= 4; ++k) {
    const Eigen::MatrixXd want = e.block(0, m * k, m, m).rightCols(half);
    EXPECT_LE((f.phi[k - 1] - want).cwiseAbs().maxCoeff(), 1e-12 * want.cwiseAbs().maxCoeff()) << "phi_" << k;
  }
}

TEST(FlexibleBearing, LoadFrameForceIsTheRingFrameForceRotated) {
  // b = R(n psi) a per pair: the kernel with the shapes at the balls' azimuths must give the
  // ring-frame loop's force (shapes at phi - psi), its modal pairs rotated by R(n psi).
  const CtRing ct;
  const int n = ct.bearing.size();
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  RollingPhase phase;
  phase.cage = 0.3;
  phase.outer_ring = 0.7;
  const double psi = ct.bearing.ring_angle_rad(phase);
  Eigen::VectorXd x = ct.equilibrium.coordinates, x_dot(n);
  for (int i = 0; i < n; ++i) {
    x[i] += 2e-7 * noise(rng) * (i == 3 || i == 4 ? 1.0 / 0.6 : 1.0);
    x_dot[i] = 1e-4 * noise(rng);
  }
  Eigen::VectorXd z = x, rates = x_dot;
  const auto& modes = ct.bearing.modes();
  const auto rotate = [&](Eigen::VectorXd* v, std::size_t i) {
    const int j = 5 + 2 * static_cast<int>(i);
    const double c = std::cos(modes[i].order * psi), s = std::sin(modes[i].order * psi);
    const double a0 = (*v)[j], a1 = (*v)[j + 1];
    (*v)[j] = c * a0 - s * a1;
    (*v)[j + 1] = s * a0 + c * a1;
  };
  for (std::size_t i = 0; i < modes.size(); ++i) {
    rotate(&z, i);
    rotate(&rates, i);
  }
  Eigen::VectorXd expected = ct.bearing.contact_force(x, x_dot, phase);
  for (std::size_t i = 0; i < modes.size(); ++i) rotate(&expected, i);
  const Eigen::VectorXd got = ct.bearing.contact_force_load_frame(z, rates, phase, false);
  const double scale = expected.lpNorm<Eigen::Infinity>();
  ASSERT_GT(scale, 1000.0);  // the 6800 N load is carried
  // Sums over 414 balls in a different order of rotations: rounding, 1e-10 of the largest.
  for (int i = 0; i < n; ++i) EXPECT_NEAR(got[i], expected[i], 1e-10 * scale) << "coordinate " << i;
}

// The CT bearing's second row turned by half a degree: its balls no longer share the first
// row's azimuths, so the SIMD kernel takes the ring's displacement at every ball.
FlexibleBearing ct_ring_rows_out_of_phase() {
  BearingConfig c = load_bearing_config(test::bearing_file("ct_gantry_flexible.yaml"));
  c.row_phase_rad = 0.5 * kPi / 180.0;
  return FlexibleBearing(BearingModel(c));
}

TEST(FlexibleBearing, SimdKernelGivesTheScalarLoopsForceOnEveryTarget) {
  const CtRing ct;
  const FlexibleBearing out_of_phase = ct_ring_rows_out_of_phase();
  const int n = ct.bearing.size();
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  test::for_each_simd_target([&] {
    for (const FlexibleBearing* bearing : {&ct.bearing, &out_of_phase}) {
      for (int trial = 0; trial < 20; ++trial) {
        RollingPhase phase;
        phase.cage = noise(rng);
        phase.outer_ring = noise(rng);
        Eigen::VectorXd z = ct.equilibrium.coordinates, rates(n);
        for (int i = 0; i < n; ++i) {
          z[i] += 5e-7 * noise(rng) * (i == 3 || i == 4 ? 1.0 / 0.6 : 1.0);
          rates[i] = 1e-3 * noise(rng);
        }
        const Eigen::VectorXd scalar = bearing->contact_force_load_frame(z, rates, phase, false);
        const Eigen::VectorXd simd = bearing->contact_force_load_frame(z, rates, phase, true);
        // Same formulas; fused multiply-adds and the order of the sums differ.
        const double scale = scalar.lpNorm<Eigen::Infinity>();
        ASSERT_GT(scale, 1000.0);  // the balls carry the 6800 N load
        for (int i = 0; i < n; ++i)
          EXPECT_NEAR(simd[i], scalar[i], 1e-11 * scale)
              << "coordinate " << i << (bearing == &ct.bearing ? ", rows in phase" : ", rows out of phase");
      }
    }
  });
}

struct RunStatistics {
  double a_rms_x = 0.0, a_rms_y = 0.0;
  std::vector<double> mode_rms_m;  // per mode, of its (cos, sin) pair about the mean
};

RunStatistics run(IntegrationMethod method, double duration_s) {
  const double rate_hz = 10000.0;
  const BearingModel model(load_bearing_config(test::bearing_file("ct_gantry_flexible.yaml")));
  FlexibleDynamics dyn(FlexibleBearing(model), test::ct_load(), test::kCtSpeedRadS, rate_hz, 0, method);
  const int n = dyn.bearing().size(), samples = static_cast<int>(duration_s * rate_hz);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(n + 2), sq = Eigen::VectorXd::Zero(n + 2);
  int count = 0;
  for (int i = 0; i < samples; ++i) {
    const FlexibleSample& s = dyn.step();
    if (i < samples / 2) continue;
    Eigen::VectorXd v(n + 2);
    v << s.accelerations.head<2>(), s.coordinates;
    sum += v;
    sq += v.cwiseAbs2();
    ++count;
  }
  const Eigen::VectorXd var = (sq / count - (sum / count).cwiseAbs2()).cwiseMax(0.0);
  RunStatistics r;
  r.a_rms_x = std::sqrt(var[0]);
  r.a_rms_y = std::sqrt(var[1]);
  for (int i = 0; i < (n - 5) / 2; ++i) r.mode_rms_m.push_back(std::sqrt(var[7 + 2 * i] + var[8 + 2 * i]));
  return r;
}

TEST(FlexibleDynamics, AdamsStepGivesTheCtRingsResponseOfConvergedRk4) {
  // The measure: a_rms within 1 % (L within 0.1 dB) of converged RK4 (|omega| h <=
  // 0.5; at 4 times its steps a_rms moves by 0.04 %), and every ring mode's RMS in the ring's
  // frame within 1 %. Adams: one step per 10 kHz sample, |lambda| h about 1.5.
  const RunStatistics adams = run(IntegrationMethod::ExponentialAdamsPec, 0.3);
  const RunStatistics rk4 = run(IntegrationMethod::Rk4, 0.3);
  ASSERT_GT(rk4.a_rms_x, 1e-5);
  EXPECT_NEAR(adams.a_rms_x, rk4.a_rms_x, 0.01 * rk4.a_rms_x);
  EXPECT_NEAR(adams.a_rms_y, rk4.a_rms_y, 0.01 * rk4.a_rms_y);
  EXPECT_NEAR(20.0 * std::log10(adams.a_rms_x / rk4.a_rms_x), 0.0, 0.1);
  for (std::size_t i = 0; i < rk4.mode_rms_m.size(); ++i) {
    if (rk4.mode_rms_m[i] > 1e-3 * rk4.mode_rms_m[0]) {  // modes the load drives (in plane)
      EXPECT_NEAR(adams.mode_rms_m[i], rk4.mode_rms_m[i], 0.01 * rk4.mode_rms_m[i]) << "mode " << i;
    }
  }
}

TEST(FlexibleDynamics, OtherIntegratorsAreRefusedNamingTheChoices) {
  const CtRing ct;
  try {
    FlexibleDynamics dyn(ct.bearing, test::ct_load(), test::kCtSpeedRadS, 10000.0, 0,
                         IntegrationMethod::ExponentialRk4);
    FAIL() << "etdrk4 accepted for a flexible ring";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("adams_pec or rk4"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace bearing_sim
