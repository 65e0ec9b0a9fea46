// Damping given as the modal ratio of the radial mode (docs/model.md section 7.3): the c_n
// solved from a ratio gives that ratio back in the eigenvalues of the damped ring, the
// conversion is linear, and the bearing file takes exactly one of the two forms.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>

#include <Eigen/Eigenvalues>

#include "bearing_6205_yaml.hpp"
#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/modal_damping.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {

// Damping ratio -Re(lambda)/|lambda| of the eigenvalue of the damped linearised ring,
// y' = [0 I; -M^-1 K, -M^-1 C] y, whose damped frequency is nearest the mode's omega.
double eigenvalue_damping_ratio(const BearingModel& model, const Vector5& load, double omega) {
  const StaticSolution s = solve_static(model, load);
  Matrix5 c;
  model.contact_force_and_stiffness(s.displacement, RollingPhase{}, nullptr, &c);
  const Matrix5 inv_m = model.mass_matrix().inverse();
  Eigen::Matrix<double, 10, 10> a = Eigen::Matrix<double, 10, 10>::Zero();
  a.topRightCorner<5, 5>().setIdentity();
  a.bottomLeftCorner<5, 5>() = -(inv_m * s.stiffness);
  a.bottomRightCorner<5, 5>() = -(inv_m * c);
  const Eigen::EigenSolver<Eigen::Matrix<double, 10, 10>> eigen(a, false);
  std::complex<double> best(0.0, 0.0);
  for (int i = 0; i < 10; ++i) {
    const std::complex<double> l = eigen.eigenvalues()[i];
    if (l.imag() > 0.0 && std::abs(std::abs(l) - omega) < std::abs(std::abs(best) - omega)) best = l;
  }
  return -best.real() / std::abs(best);
}

BearingModel with_damping(const BearingModel& model, double c) {
  BearingConfig config = model.config();
  config.contact_damping_Ns_per_m = c;
  return BearingModel(config);
}

struct Case {
  const char* name;
  BearingModel model;
  Vector5 load;
};

std::vector<Case> cases() {
  return {{"CT gantry, operating load", BearingModel(ct_bearing()), ct_load()},
          {"6205, 500 N radial", BearingModel(bearing_config_from_string(kBearing6205Yaml)), load5(500, 0, 0, 0, 0)},
          {"INS pair, 50 N radial and 20 N axial",
           BearingModel(load_bearing_config(bearing_file("ins_618_22_db.yaml"))), load5(50, 0, 20, 0, 0)}};
}

}  // namespace

// The conversion is first-order (modal) perturbation theory: the damped eigenvalue's real part
// is -c phi^T G phi / 2 to first order in c. C is not proportional to K or M, so it couples the
// radial mode to the others at second order, ~ zeta^2 times the modal coupling over the
// relative frequency gap: 2e-6 of zeta measured on these cases. 1e-4 of zeta bounds that with
// margin, while a wrong mode, a factor 2 or a missing mass normalisation is off by far more.
TEST(ModalDamping, RatioComesBackFromTheDampedEigenvalues) {
  for (const Case& k : cases()) {
    SCOPED_TRACE(k.name);
    const double zeta = 0.02;
    const double c = contact_damping_for_ratio(k.model, k.load, zeta);
    ASSERT_GT(c, 0.0);
    const BearingModel damped = with_damping(k.model, c);
    const RadialMode mode = radial_mode(damped, k.load);
    EXPECT_GT(mode.radial_share, 0.5) << "the chosen mode is mostly radial";
    EXPECT_NEAR(eigenvalue_damping_ratio(damped, k.load, mode.omega_rad_s), zeta, 1e-4 * zeta);
    EXPECT_NEAR(radial_mode_damping_ratio(damped, k.load), zeta, 1e-12);
  }
}

TEST(ModalDamping, ConversionIsLinearInTheRatio) {
  for (const Case& k : cases()) {
    SCOPED_TRACE(k.name);
    const double c1 = contact_damping_for_ratio(k.model, k.load, 0.02);
    const double c2 = contact_damping_for_ratio(k.model, k.load, 0.04);
    EXPECT_NEAR(c2, 2.0 * c1, 1e-12 * c2);
    EXPECT_EQ(contact_damping_for_ratio(k.model, k.load, 0.0), 0.0);
    // and independent of the damping the model already has (G is the contacts' geometry)
    EXPECT_NEAR(contact_damping_for_ratio(with_damping(k.model, 5.0 * c1), k.load, 0.02), c1, 1e-12 * c1);
  }
}

// The shipped per-contact values sit in the 1-5 % that lubricated steel contacts show.
TEST(ModalDamping, ShippedFilesGiveAFewPercentOfCritical) {
  for (const Case& k : cases()) {
    SCOPED_TRACE(k.name);
    const double zeta = radial_mode_damping_ratio(k.model, k.load);
    EXPECT_GT(zeta, 0.002);
    EXPECT_LT(zeta, 0.1);
    std::printf("%s: c_n = %g N*s/m, radial mode %.1f Hz, zeta = %.4f\n", k.name,
                k.model.config().contact_damping_Ns_per_m, radial_mode(k.model, k.load).omega_rad_s / (2 * kPi), zeta);
  }
}

TEST(ModalDamping, BearingFileResolvesTheRatioAtItsReferenceLoad) {
  const std::string base = kBearing6205Yaml.substr(0, kBearing6205Yaml.find("damping:"));
  const BearingConfig config = bearing_config_from_string(
      base + "damping: {modal_damping_ratio: 0.03, reference_force_N: [500, 0, 0]}\n", "ratio.yaml");
  EXPECT_EQ(config.modal_damping_ratio, 0.03);
  const BearingModel model(config);
  EXPECT_NEAR(config.contact_damping_Ns_per_m, contact_damping_for_ratio(model, load5(500, 0, 0, 0, 0), 0.03),
              1e-9 * config.contact_damping_Ns_per_m);
  EXPECT_NEAR(radial_mode_damping_ratio(model, load5(500, 0, 0, 0, 0)), 0.03, 1e-12);
}

namespace {
void expect_damping_error(const std::string& yaml, std::vector<std::string> words) {
  words.push_back("damping_test.yaml");
  test::expect_config_error([&] { bearing_config_from_string(yaml, "damping_test.yaml"); }, words, yaml);
}
}  // namespace

TEST(ModalDamping, BadDampingBlocksAreNamed) {
  const std::string base = kBearing6205Yaml.substr(0, kBearing6205Yaml.find("damping:"));
  expect_damping_error(base + "damping: {contact_damping_Ns_per_m: 100, modal_damping_ratio: 0.02}\n",
                      {"damping.contact_damping_Ns_per_m", "damping.modal_damping_ratio", "exactly one"});
  expect_damping_error(base + "damping: {}\n", {"exactly one"});
  expect_damping_error(base + "damping: {modal_damping_ratio: 0.5, reference_force_N: [500, 0, 0]}\n",
                      {"damping.modal_damping_ratio", "[0, 0.3]"});
  expect_damping_error(base + "damping: {modal_damping_ratio: 0.02, reference_force_N: [500, 0]}\n",
                      {"damping.reference_force_N", "3 numbers"});
  // The 6205 has no preload: at zero load no ball touches and there is no radial mode.
  expect_damping_error(base + "clearance_um: 5\ndamping: {modal_damping_ratio: 0.02}\n",
                      {"damping.modal_damping_ratio", "reference_force_N", "no radial mode"});
  expect_damping_error(base + "damping: {contact_damping_Ns_per_m: 100, reference_force_N: [1, 0, 0]}\n",
                      {"damping.reference_force_N"});
}
