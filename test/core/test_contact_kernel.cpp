// The SIMD contact kernel (Google Highway, one variant per SIMD target, picked at run time)
// must give the plain scalar loop's forces, for every target compiled in that this CPU can
// run: same formulas and correctly rounded square roots and divisions; only fused
// multiply-adds and the order of the sums differ. The same for the Adams step's small
// matrix-vector products against Eigen's.
#include <gtest/gtest.h>

#include <hwy/targets.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

#include "../../src/core/contact_kernel.hpp"
#include "../../src/core/harmonic_sums.hpp"
#include "../../src/core/small_products.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/simd_info.hpp"
#include "simd_targets.hpp"
#include "test_support.hpp"

namespace bearing_sim {
namespace {

void expect_kernels_agree(const BearingModel& model, const Vector5& load) {
  const Vector5 q0 = solve_static(model, load).displacement;
  std::mt19937_64 rng(42);
  std::normal_distribution<double> n(0.0, 1.0);
  const double scale = load.head<3>().norm() + load.tail<2>().norm() / model.pitch_radius_m();
  for (int trial = 0; trial < 200; ++trial) {
    Vector5 q = q0, v;
    for (int i = 0; i < 5; ++i) {
      q[i] += 0.2 * std::abs(q0[i]) * n(rng);  // around the load zone, balls entering and leaving
      v[i] = 1e-3 * n(rng) * (i < 3 ? 1.0 : 1.0 / model.pitch_radius_m());
    }
    const RollingPhase phase{0.1 * trial};
    const Vector5 fast = model.contact_force(q, v, phase, model.balls(), BearingModel::ContactKernel::Fastest);
    const Vector5 scalar = model.contact_force(q, v, phase, model.balls(), BearingModel::ContactKernel::Scalar);
    Vector5 scaled = fast - scalar;
    scaled.tail<2>() /= model.pitch_radius_m();
    // Rounding of a few hundred ball forces summed in a different order: 1e-12 of the load.
    EXPECT_LT(scaled.norm(), 1e-12 * scale) << "trial " << trial;
  }
}

TEST(ContactKernel, SimdAndScalarLoopsAgreeForTheCtBearing) {
  const BearingModel model(test::ct_bearing());
  test::for_each_simd_target([&] { expect_kernels_agree(model, test::ct_load()); });
}

TEST(ContactKernel, SimdAndScalarLoopsAgreeForAPreloadedInnerRingBearing) {
  BearingConfig c =
      test::single_row(13, 9.0, 46.0, 25.0, 0.52, 0.53, -3.0,
                       "rotating_ring: inner\nrotating_mass_kg: 1\ndamping: {contact_damping_Ns_per_m: 300}\n");
  const BearingModel model(c);
  test::for_each_simd_target([&] { expect_kernels_agree(model, test::load5(800.0, -300.0, 1500.0, 5.0, -3.0)); });
}

// Random ball sets straight into the kernel (balls of two rows mixed), with the edge cases
// placed on purpose: balls just touching and just leaving (deflection +-1e-12 m), inside a
// spall (offset -1 mm, and under a race spall's window of either row), damping pulling a
// touching ball's load negative, and set sizes that are not multiples of any vector width.
TEST(ContactKernel, SimdAndScalarKernelsAgreeOnRandomBallsWithEdgeCases) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double kn = 1.1e10, cn = 400.0;  // N/m^1.5, N s/m
  const double A = 3.2e-4, g0 = 1e-5, rho = 0.05, a0 = 0.3;
  int pulled_negative = 0;
  test::for_each_simd_target([&] {
    for (int n : {1, 3, 7, 8, 207}) {
      for (int trial = 0; trial < 50; ++trial) {
        std::vector<double> cb(n), sb(n), gz(n), nz(n), off(n);
        double q[5], qd[5];
        for (int i = 0; i < 5; ++i) {
          q[i] = (i < 3 ? 2e-5 : 1e-4) * u(rng);
          qd[i] = (i < 3 ? 1e-3 : 1e-2) * u(rng);
        }
        const double cage = 3.0 * u(rng), sg = trial % 2 ? 1.0 : -1.0;
        const double row_z = 0.01 * u(rng);
        for (int b = 0; b < n; ++b) {
          const double phi = 6.283185307179586 * b / n + 0.01 * u(rng);
          cb[b] = std::cos(phi);
          sb[b] = std::sin(phi);
          const bool row0 = (b / 2) % 2 == 0;  // rows interleaved in runs of two
          gz[b] = row0 ? row_z : -row_z;
          nz[b] = (row0 ? 1.0 : -1.0) * std::sin(a0);
        }
        // Two race spalls, one per row, each centred within 0.02 rad of a ball of its row
        // (so that its ball, and for the wider ones a neighbour, is in it), 0.01-0.6 rad wide.
        std::vector<Imperfections::SpallWindow> windows;
        for (int k = 0; k < 2; ++k) {
          const int b = (2 * k + 4 * (trial % 3)) % n;
          const double width = 0.01 + 0.59 * std::abs(u(rng));
          const double centre = cage + std::atan2(sb[b], cb[b]) + 0.02 * u(rng);
          // Every other trial: sharp edges with a rim 0.1-0.4 of the width wide, the first
          // spall a round pit (the ball riding the ring rim's crest over it).
          const bool sharp = trial % 2 == 1;
          const double rim = sharp ? width * (0.1 + 0.3 * std::abs(u(rng))) : 0.0;
          const double rim_height = sharp ? 3e-6 * std::abs(u(rng)) : 0.0;
          windows.push_back({std::cos(centre), std::sin(centre), std::sin(0.5 * width + rim), 3.141592653589793 / width,
                             2e-5 * std::abs(u(rng)), sharp,
                             /*geometric_depth=*/sharp ? 4e-5 * std::abs(u(rng)) : 0.0,
                             /*half_width=*/0.5 * width, rim_height,
                             /*rim_pi_over_width=*/sharp ? 3.141592653589793 / rim : 0.0, k, k == 0 ? row_z : -row_z,
                             /*ring_drop=*/sharp && k == 0 ? 4e-5 * std::abs(u(rng)) : 0.0,
                             /*ring_crest=*/0.5 * width + 0.5 * rim});
        }
        const detail::ContactKernelInput in{std::cos(cage),
                                            std::sin(cage),
                                            rho,
                                            std::cos(a0),
                                            A,
                                            g0,
                                            sg,
                                            kn,
                                            cn,
                                            q,
                                            qd,
                                            cb.data(),
                                            sb.data(),
                                            gz.data(),
                                            nz.data(),
                                            off.data(),
                                            n,
                                            windows.data(),
                                            static_cast<int>(windows.size())};
        // Place each ball's deflection: the bare one (no offset) from a one-ball scalar
        // run's geometry, |v| - A - g0.
        for (int b = 0; b < n; ++b) {
          const double cphi = in.cos_cage * cb[b] - in.sin_cage * sb[b];
          const double sphi = in.sin_cage * cb[b] + in.cos_cage * sb[b];
          const double vx = A * in.cos_a0 * cphi - sg * (q[0] + q[4] * gz[b]);
          const double vy = A * in.cos_a0 * sphi - sg * (q[1] - q[3] * gz[b]);
          const double vz = A * nz[b] - sg * (q[2] + q[3] * rho * sphi - q[4] * rho * cphi);
          const double bare = std::sqrt(vx * vx + vy * vy + vz * vz) - A - g0;
          switch (b % 5) {
            case 0:
              off[b] = 1e-12 - bare;
              break;  // just touching
            case 1:
              off[b] = -1e-12 - bare;
              break;  // just leaving
            case 2:
              off[b] = -1e-3;
              break;  // inside a spall
            case 3:
              off[b] = 1e-9 - bare;
              break;  // light contact: damping may pull its load negative
            default:
              off[b] = 2e-5 * u(rng);
              break;  // random
          }
          if (b % 5 == 3) {
            const detail::ContactKernelInput one{in.cos_cage, in.sin_cage, rho, in.cos_a0, A,      g0,     sg,
                                                 kn,          cn,          q,   qd,        &cb[b], &sb[b], &gz[b],
                                                 &nz[b],      &off[b],     1,   nullptr,   0};
            const detail::ContactSums s = detail::contact_sums_scalar(one);
            if (s.x == 0.0 && s.y == 0.0 && s.z == 0.0) ++pulled_negative;
          }
        }
        const detail::ContactSums ref = detail::contact_sums_scalar(in);
        const detail::ContactSums simd = detail::contact_sums_simd(in);
        // Load scale: n balls at the largest deflection here (~3e-5 m) and rate (~0.1 m/s),
        // in N. Each ball's term has a relative rounding error of a few 1e-16 (sqrt and div
        // are correctly rounded in both; only FMA contraction and grouping differ), but
        // delta = |v| - A - g0 + offset cancels: |v| ~ A ~ 3e-4 m rounds to ~1e-20 m,
        // ~1e-15 of a 1e-5 m deflection; and n <= 207 terms summed in another order add
        // ~n 1e-16 of the sum. 1e-12 of the scale bounds both with a wide margin while
        // still catching any wrong term (a ball missing or kept is >= 1e-6 of the scale).
        const double scale = n * (kn * std::pow(3e-5, 1.5) + cn * 0.1);
        const double tol = 1e-12 * scale;
        const double lever = 0.01;  // m: the z-weighted sums are forces times |z| <= 0.01 m
        EXPECT_NEAR(simd.x, ref.x, tol) << "n " << n << " trial " << trial;
        EXPECT_NEAR(simd.y, ref.y, tol) << "n " << n << " trial " << trial;
        EXPECT_NEAR(simd.z, ref.z, tol) << "n " << n << " trial " << trial;
        EXPECT_NEAR(simd.z_cos, ref.z_cos, tol) << "n " << n << " trial " << trial;
        EXPECT_NEAR(simd.z_sin, ref.z_sin, tol) << "n " << n << " trial " << trial;
        EXPECT_NEAR(simd.x_z, ref.x_z, tol * lever) << "n " << n << " trial " << trial;
        EXPECT_NEAR(simd.y_z, ref.y_z, tol * lever) << "n " << n << " trial " << trial;
      }
    }
  });
  // The damping case must really occur, or the test would not cover it.
  EXPECT_GT(pulled_negative, 0);
}

// The race spalls' windows in the kernel against the offsets' dips (Imperfections::add_offsets,
// the path of the stiffness and of every bearing with waviness): the same force at zero
// velocity, with balls entering, inside and leaving an outer-race spall (fixed ring) and an
// inner-race spall (rotating ring) of the 6205, and on one row of a double-row bearing.
// Only the rounding of the ball's angle from the window's centre differs (asin of a sine
// against a difference of angles: ~1e-16 rad, ~1e-16 of the depth), 1e-9 of the load.
void expect_windows_match_dips(const BearingModel& model, const Vector5& load, double width_rad) {
  const Vector5 q = solve_static(model, load).displacement;
  const double scale = load.head<3>().norm() + load.tail<2>().norm() / model.pitch_radius_m();
  const double pitch = 6.283185307179586 / model.balls_per_row();
  int changed = 0;
  Vector5 previous = Vector5::Zero();
  for (int k = 0; k <= 40; ++k) {
    // The cage from a ball half a width before the spall's centre to half a width past it.
    const RollingPhase phase{(k / 40.0 - 0.5) * (width_rad + 0.1 * pitch), 0.37, 0.0, 0.0, 0.0};
    const Vector5 kernel =
        model.contact_force(q, Vector5::Zero(), phase, model.balls(), BearingModel::ContactKernel::Scalar);
    const Vector5 fastest = model.contact_force(q, Vector5::Zero(), phase, model.balls());
    const Vector5 dips = model.contact_force_and_stiffness(q, phase, nullptr, nullptr);
    for (const Vector5& f : {kernel, fastest}) {
      Vector5 d = f - dips;
      d.tail<2>() /= model.pitch_radius_m();
      EXPECT_LT(d.norm(), 1e-9 * scale) << "cage at " << phase.cage << " rad";
    }
    if (k > 0 && (dips - previous).norm() > 1e-6 * scale) ++changed;
    previous = dips;
  }
  EXPECT_GT(changed, 3) << "no ball went through the spall";
}

TEST(ContactKernel, RaceSpallWindowsGiveTheOffsetsDips) {
  test::for_each_simd_target([&] {
    // Rounded and sharp edges (docs/model.md 9.6).
    for (const Surface surface : {Surface::OuterRace, Surface::InnerRace})
      for (const char* edges :
           {"", "imperfections: {spall_edges: sharp}\n",
            "imperfections: {spall_edges: sharp, spall_rim_height_um: 3, spall_rim_width_um: 400}\n",
            "imperfections: {spall_edges: sharp, spall_pits: round, spall_rim_height_um: 3, "
            "spall_rim_width_um: 400}\n"}) {
        BearingModel model = test::bearing_6205(edges);
        // Centred on ball 0's azimuth at cage angle 0 in the race's frame (the inner ring at 0.37 rad).
        Spall spall{surface, surface == Surface::InnerRace ? -0.37 : 0.0, 0, 1.5e-3, 20e-6};
        model.add_spall(spall);
        expect_windows_match_dips(model, test::load5(1000.0, 0.0, 0.0, 0.0, 0.0), 1.5e-3 / 0.02);
      }
    // The CT bearing: row 0's ball nearest 180 deg, in the load zone of its 6800 N.
    BearingModel ct(test::ct_bearing());
    const int ball = ct.balls_per_row() / 2;
    ct.add_spall(Spall{Surface::InnerRace, ct.base_azimuth_rad(ball) - 0.37, 0, 2e-3, 20e-6});
    expect_windows_match_dips(ct, test::ct_load(), 2e-3 / 0.55);
  });
}

// The windows of spalls on a standing ring are made once with the spalls (BearingModel keeps
// them): they must follow every change of the spalls. On the 6205 (the outer ring stands),
// ball 0 at the centre of the load zone: a spall under it lowers the force, clearing it
// gives back the spall-free force bit for bit, and a growing spall (its windows made anew
// at each time) deepens with time; each as the offsets' dips give it (1e-9 of the load).
TEST(ContactKernel, StandingSpallWindowsFollowTheSpalls) {
  BearingModel model = test::bearing_6205();
  const Vector5 load = test::load5(1000.0, 0.0, 0.0, 0.0, 0.0);
  const Vector5 q = solve_static(model, load).displacement;
  const double scale = load.norm();
  const auto force = [&](double time_s) {
    const RollingPhase phase{0.0, 0.37, 0.0, 0.0, time_s};
    const Vector5 f = model.contact_force(q, Vector5::Zero(), phase, model.balls());
    EXPECT_LT((f - model.contact_force_and_stiffness(q, phase, nullptr, nullptr)).norm(), 1e-9 * scale);
    return f;
  };
  const Vector5 clean = force(0.0);
  model.add_spall(Spall{Surface::OuterRace, 0.0, 0, 1.5e-3, 20e-6});
  const Vector5 spalled = force(0.0);
  EXPECT_GT((clean - spalled).norm(), 1e-3 * scale) << "the spall under ball 0 was not seen";
  EXPECT_EQ(force(1.0), spalled) << "a spall that does not grow gave another force later";
  model.clear_spalls();
  EXPECT_EQ(force(0.0), clean);
  Spall growing{Surface::OuterRace, 0.0, 0, 0.5e-3, 2e-6};
  growing.depth_growth_m_per_s = 10e-6;
  model.add_spall(growing);
  const Vector5 young = force(0.0), grown = force(1.0);
  EXPECT_GT((young - grown).norm(), 1e-3 * scale) << "the growing spall's windows did not follow time";
}

// The waviness sums against the scalar loop: random phases and amplitudes of 0.01-1 um, 1-9
// harmonics, ball counts that are not multiples of any vector width. Each offset is a sum of
// at most 18 terms of <= 1e-6 m: FMAs and the order give rounding of ~1e-15 of that.
TEST(ContactKernel, HarmonicSumsAgreeWithTheScalarLoop) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  test::for_each_simd_target([&] {
    for (int harmonics : {1, 4, 9})
      for (int n : {1, 3, 7, 9, 207, 317}) {
        std::vector<double> c(2 * harmonics), terms(2 * static_cast<std::size_t>(harmonics) * n), base(n);
        double bound = 0.0;
        for (int h = 0; h < harmonics; ++h) {
          const double amplitude = 1e-8 + 1e-6 * std::abs(u(rng)), shift = 3.0 * u(rng);
          c[2 * h] = amplitude * std::cos(shift);
          c[2 * h + 1] = amplitude * std::sin(shift);
          bound += amplitude;
          for (int b = 0; b < n; ++b) {
            const double angle = 40.0 * u(rng);
            terms[2 * h * n + b] = std::cos(angle);
            terms[(2 * h + 1) * n + b] = std::sin(angle);
          }
        }
        for (double& x : base) x = 1e-6 * u(rng);  // the constant offsets the sums add to
        // In place (out = base) and into a separate array (the constant offsets left as they are).
        std::vector<double> simd = base, scalar = base, separate(n, std::nan(""));
        detail::add_harmonic_sums(c.data(), harmonics, terms.data(), n, simd.data(), simd.data());
        detail::add_harmonic_sums(c.data(), harmonics, terms.data(), n, base.data(), separate.data());
        detail::add_harmonic_sums_scalar(c.data(), harmonics, terms.data(), n, scalar.data(), scalar.data());
        for (int b = 0; b < n; ++b) {
          ASSERT_NEAR(simd[b], scalar[b], 1e-14 * (bound + 1e-6))
              << harmonics << " harmonics, ball " << b << " of " << n;
          ASSERT_EQ(separate[b], simd[b]) << harmonics << " harmonics, ball " << b << " of " << n;
        }
        // A wrong term (a harmonic or a ball missed) would be >= 1e-8 m off somewhere.
      }
  });
}

// The per-call waviness coefficients a (cos, sin)(angle) against std::cos and std::sin:
// Highway's vector functions are within 3 ulp over +-39000 rad (hwy/contrib/math), so
// 8 ulp of the amplitude is a bound with margin; angles of a race harmonic of order up to
// ~5000 (|angle| <= 2 pi order), one beyond the vector range (std::cos for its lanes), and
// counts that are not multiples of any vector width.
TEST(ContactKernel, HarmonicCoefficientsAgreeWithStdCosAndSin) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  test::for_each_simd_target([&] {
    for (int harmonics : {1, 3, 4, 5, 9, 17}) {
      std::vector<double> amplitude(harmonics), angle(harmonics), c(2 * harmonics);
      for (int h = 0; h < harmonics; ++h) {
        amplitude[h] = 1e-8 + 1e-6 * std::abs(u(rng));
        angle[h] = (h == 2 ? 1e6 : 30000.0) * u(rng);
      }
      detail::harmonic_coefficients(amplitude.data(), angle.data(), harmonics, c.data());
      for (int h = 0; h < harmonics; ++h) {
        const double tol = 8.0 * std::numeric_limits<double>::epsilon() * amplitude[h];
        EXPECT_NEAR(c[2 * h], amplitude[h] * std::cos(angle[h]), tol) << "harmonic " << h << " of " << harmonics;
        EXPECT_NEAR(c[2 * h + 1], amplitude[h] * std::sin(angle[h]), tol) << "harmonic " << h << " of " << harmonics;
      }
    }
  });
}

// Every size the Adams step uses, with and without the added vector, against Eigen's
// product: rounding only (FMAs and the order of the sums), 1e-15 of the terms' magnitude.
template <int Rows, int Cols>
void expect_products_agree() {
  const Eigen::Matrix<double, Rows, Cols> m = Eigen::Matrix<double, Rows, Cols>::Random();
  const Eigen::Matrix<double, Cols, 1> x = Eigen::Matrix<double, Cols, 1>::Random() * 1e3;
  const Eigen::Matrix<double, Rows, 1> base = Eigen::Matrix<double, Rows, 1>::Random() * 1e3;
  Eigen::Matrix<double, Rows, 1> product, sum;
  detail::multiply_add<Rows, Cols>(m.data(), x.data(), nullptr, product.data());
  detail::multiply_add<Rows, Cols>(m.data(), x.data(), base.data(), sum.data());
  const double tol = 1e-15 * Cols * (m.cwiseAbs() * x.cwiseAbs()).maxCoeff();
  EXPECT_LT((product - m * x).cwiseAbs().maxCoeff(), tol) << Rows << "x" << Cols;
  EXPECT_LT((sum - (base + m * x)).cwiseAbs().maxCoeff(), tol + 1e-15 * base.cwiseAbs().maxCoeff())
      << Rows << "x" << Cols;
}

TEST(ContactKernel, SmallProductsAgreeWithEigen) {
  std::srand(3);  // Eigen's Random()
  test::for_each_simd_target([&] {
    for (int trial = 0; trial < 20; ++trial) {
      expect_products_agree<15, 30>();
      expect_products_agree<10, 5>();
      expect_products_agree<5, 10>();
    }
  });
}

TEST(ContactKernel, ReportsTheCpuAndSimdTarget) {
  std::cout << "CPU: " << cpu_model_name() << ", SIMD target: " << simd_target_name() << "\n";
  EXPECT_FALSE(simd_target_name().empty());
  EXPECT_FALSE(cpu_model_name().empty());
  // The name as /proc/cpuinfo gives it first, then its family and model where it has them.
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line) && line.rfind("model name", 0) != 0) {
  }
  if (line.empty()) return;  // no "model name" (e.g. an Arm kernel): "unknown" is right
  const std::string name = line.substr(line.find_first_not_of(" \t", line.find(':') + 1));
  EXPECT_EQ(cpu_model_name().rfind(name, 0), 0u) << cpu_model_name();
}

// bench_simulate --simd_target=AVX2: an AVX2-only CPU's kernel on an AVX-512 machine.
TEST(ContactKernel, LimitsTheSimdTarget) {
  EXPECT_FALSE(limit_simd_target("no such target"));
  const std::int64_t supported = hwy::SupportedTargets();
  for (const std::int64_t target : detail::contact_kernel_compiled_targets()) {
    if ((target & supported) == 0) continue;
    EXPECT_TRUE(limit_simd_target(hwy::TargetName(target)));
    EXPECT_EQ(simd_target_name(), hwy::TargetName(target));
    hwy::DisableTargets(0);  // every target again, for the other tests
  }
}

}  // namespace
}  // namespace bearing_sim
