// Bearing file validation (docs/bearing_file.md): every kind of bad file is a ConfigError
// naming the source and the key; the shipped files load.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/errors.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {
const char* kBearingSource = "unit_test_bearing.yaml";

// A valid single-row file as (key, value) lines; overrides replace or add, "" removes.
std::string yaml(const std::map<std::string, std::string>& overrides = {}) {
  std::vector<std::pair<std::string, std::string>> lines = {
      {"name", "test bearing"},
      {"balls_per_row", "9"},
      {"ball_diameter_mm", "7.94"},
      {"pitch_diameter_mm", "39.04"},
      {"inner_groove_curvature", "0.52"},
      {"outer_groove_curvature", "0.52"},
      {"contact_angle_deg", "15"},
      {"rotating_mass_kg", "0.5"},
      {"material", "{youngs_modulus_GPa: 208, poisson_ratio: 0.3}"},
      {"damping", "{contact_damping_Ns_per_m: 10}"}};
  std::string out;
  std::map<std::string, std::string> rest = overrides;
  for (auto& [k, v] : lines) {
    auto it = rest.find(k);
    if (it != rest.end()) {
      if (!it->second.empty()) out += k + ": " + it->second + "\n";
      rest.erase(it);
    } else {
      out += k + ": " + v + "\n";
    }
  }
  for (auto& [k, v] : rest)
    if (!v.empty()) out += k + ": " + v + "\n";
  return out;
}

// Expects a ConfigError whose message names the source and every one of `words`.
void expect_bearing_error(const std::string& text, const std::vector<std::string>& words) {
  SCOPED_TRACE(text);
  try {
    bearing_config_from_string(text, kBearingSource);
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(kBearingSource), std::string::npos) << msg;
    for (const auto& w : words) EXPECT_NE(msg.find(w), std::string::npos) << "'" << w << "' not in: " << msg;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
  }
}
}  // namespace

TEST(ConfigErrors, BaseFileIsValid) {
  const BearingConfig c = bearing_config_from_string(yaml(), kBearingSource);
  EXPECT_EQ(c.balls_per_row, 9);
  EXPECT_NEAR(c.ball_diameter_m, 7.94e-3, 1e-15);
  EXPECT_NEAR(c.contact_angle_rad, 15.0 * kPi / 180.0, 1e-15);
  EXPECT_NEAR(c.material.youngs_modulus_Pa, 208e9, 1.0);
  EXPECT_EQ(c.rows, 1);  // default
  EXPECT_EQ(c.clearance_m, 0.0);
}

TEST(ConfigErrors, MissingRequiredKey) {
  for (const char* k :
       {"balls_per_row", "ball_diameter_mm", "pitch_diameter_mm", "inner_groove_curvature", "outer_groove_curvature"})
    expect_bearing_error(yaml({{k, ""}}), {k});
  // Two rows need a row spacing.
  expect_bearing_error(yaml({{"rows", "2"}}), {"row_spacing_mm"});
}

TEST(ConfigErrors, UnknownKey) {
  expect_bearing_error(yaml({{"ball_diameter", "7.94"}}), {"ball_diameter"});
  expect_bearing_error(yaml({{"material", "{youngs_modulus: 208}"}}), {"material", "youngs_modulus"});
  expect_bearing_error(yaml({{"damping", "{contact_damping: 10}"}}), {"damping", "contact_damping"});
}

TEST(ConfigErrors, WrongType) {
  expect_bearing_error(yaml({{"ball_diameter_mm", "seven"}}), {"ball_diameter_mm"});
  expect_bearing_error(yaml({{"balls_per_row", "9.5"}}), {"balls_per_row"});
  expect_bearing_error(yaml({{"rows", "two"}}), {"rows"});
  expect_bearing_error(yaml({{"pitch_diameter_mm", "[39.04]"}}), {"pitch_diameter_mm"});
  expect_bearing_error(yaml({{"material", "208"}}), {"material"});
  expect_bearing_error(yaml({{"material", "{poisson_ratio: abc}"}}), {"poisson_ratio"});
  expect_bearing_error(yaml({{"damping", "{contact_damping_Ns_per_m: lots}"}}), {"contact_damping_Ns_per_m"});
  expect_bearing_error(yaml({{"rotating_ring", "both"}}), {"rotating_ring"});
  expect_bearing_error(yaml({{"arrangement", "tandem"}}), {"arrangement"});
}

TEST(ConfigErrors, OutOfRange) {
  expect_bearing_error(yaml({{"ball_diameter_mm", "0"}}), {"ball_diameter_mm"});
  expect_bearing_error(yaml({{"ball_diameter_mm", "-7.94"}}), {"ball_diameter_mm"});
  expect_bearing_error(yaml({{"pitch_diameter_mm", "0"}}), {"pitch_diameter_mm"});
  expect_bearing_error(yaml({{"pitch_diameter_mm", "-39"}}), {"pitch_diameter_mm"});
  expect_bearing_error(yaml({{"balls_per_row", "0"}}), {"balls_per_row"});
  expect_bearing_error(yaml({{"balls_per_row", "-9"}}), {"balls_per_row"});
  expect_bearing_error(yaml({{"inner_groove_curvature", "0.5"}}), {"inner_groove_curvature"});
  expect_bearing_error(yaml({{"inner_groove_curvature", "0.45"}}), {"inner_groove_curvature"});
  expect_bearing_error(yaml({{"outer_groove_curvature", "0.5"}}), {"outer_groove_curvature"});
  expect_bearing_error(yaml({{"outer_groove_curvature", "-1"}}), {"outer_groove_curvature"});
  expect_bearing_error(yaml({{"contact_angle_deg", "-1"}}), {"contact_angle_deg"});
  expect_bearing_error(yaml({{"contact_angle_deg", "60"}}), {"contact_angle_deg"});
  expect_bearing_error(yaml({{"contact_angle_deg", "75"}}), {"contact_angle_deg"});
  expect_bearing_error(yaml({{"rows", "3"}}), {"rows"});
  expect_bearing_error(yaml({{"rows", "0"}}), {"rows"});
  expect_bearing_error(yaml({{"rows", "2"}, {"row_spacing_mm", "0"}}), {"row_spacing_mm"});
  expect_bearing_error(yaml({{"rows", "2"}, {"row_spacing_mm", "-5"}}), {"row_spacing_mm"});
  expect_bearing_error(yaml({{"material", "{poisson_ratio: 0.5}"}}), {"poisson_ratio"});
  expect_bearing_error(yaml({{"material", "{poisson_ratio: -0.1}"}}), {"poisson_ratio"});
  expect_bearing_error(yaml({{"material", "{youngs_modulus_GPa: 0}"}}), {"youngs_modulus_GPa"});
  expect_bearing_error(yaml({{"material", "{density_kg_m3: -1}"}}), {"density_kg_m3"});
  expect_bearing_error(yaml({{"damping", "{contact_damping_Ns_per_m: -1}"}}), {"contact_damping_Ns_per_m"});
  expect_bearing_error(yaml({{"rotating_mass_kg", "0"}}), {"rotating_mass_kg"});
  expect_bearing_error(yaml({{"rotating_mass_kg", "-1"}}), {"rotating_mass_kg"});
  expect_bearing_error(yaml({{"tilt_inertia_kg_m2", "-1"}}), {"tilt_inertia_kg_m2"});
  // A row phase beyond a turn (1e308 lost every digit of the azimuth; 1e20 put all balls at one).
  expect_bearing_error(yaml({{"rows", "2"}, {"row_spacing_mm", "10"}, {"row_phase_deg", "1e308"}}), {"row_phase_deg"});
  expect_bearing_error(yaml({{"rows", "2"}, {"row_spacing_mm", "10"}, {"row_phase_deg", "-361"}}), {"row_phase_deg"});
  EXPECT_NO_THROW(bearing_config_from_string(yaml({{"rows", "2"}, {"row_spacing_mm", "10"}, {"row_phase_deg", "-360"}}),
                                             kBearingSource));
  // Balls that do not fit on the pitch circle: 40 x 7.94 mm > pi x 39.04 mm.
  expect_bearing_error(yaml({{"balls_per_row", "40"}}), {"balls_per_row"});
  // Limits are open/closed as documented: 0 deg and just under 60 deg are accepted.
  EXPECT_NO_THROW(bearing_config_from_string(yaml({{"contact_angle_deg", "0"}}), kBearingSource));
  EXPECT_NO_THROW(bearing_config_from_string(yaml({{"contact_angle_deg", "59.9"}}), kBearingSource));
  EXPECT_NO_THROW(bearing_config_from_string(yaml({{"inner_groove_curvature", "0.5001"}}), kBearingSource));
}

TEST(ConfigErrors, NonFinite) {
  for (const char* v : {".nan", ".NaN", ".inf", "-.inf"}) {
    expect_bearing_error(yaml({{"ball_diameter_mm", v}}), {"ball_diameter_mm"});
    expect_bearing_error(yaml({{"clearance_um", v}}), {"clearance_um"});
    expect_bearing_error(yaml({{"material", std::string("{youngs_modulus_GPa: ") + v + "}"}}), {"youngs_modulus_GPa"});
    expect_bearing_error(yaml({{"damping", std::string("{contact_damping_Ns_per_m: ") + v + "}"}}),
                         {"contact_damping_Ns_per_m"});
  }
}

TEST(ConfigErrors, MalformedYamlAndMissingFile) {
  expect_bearing_error("balls_per_row: [9\nball_diameter_mm: 7.94\n", {});
  expect_bearing_error("balls_per_row: 9\n  ball_diameter_mm: : 7.94\n", {});
  expect_bearing_error("- just\n- a list\n", {});
  expect_bearing_error("", {});
  const std::string missing = std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings/no_such_bearing.yaml";
  try {
    load_bearing_config(missing);
    ADD_FAILURE() << "no ConfigError for a missing file";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_bearing.yaml"), std::string::npos) << e.what();
  }
}

TEST(ConfigErrors, ErrorFromAFileNamesTheFile) {
  const std::string path = ::testing::TempDir() + "bad_bearing_test.yaml";
  {
    FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    const std::string text = yaml({{"ball_diameter_mm", "-1"}});
    std::fwrite(text.data(), 1, text.size(), f);
    std::fclose(f);
  }
  try {
    load_bearing_config(path);
    ADD_FAILURE() << "no ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("ball_diameter_mm"), std::string::npos) << e.what();
  }
  std::remove(path.c_str());
}

TEST(ConfigErrors, ShippedFilesLoad) {
  const BearingConfig ct = load_bearing_config(bearing_file("ct_gantry_lyc.yaml"));
  EXPECT_EQ(ct.rows, 2);
  EXPECT_EQ(ct.balls_per_row, 207);
  EXPECT_NEAR(ct.ball_diameter_m, 12e-3, 1e-15);
  EXPECT_NEAR(ct.pitch_diameter_m, 1.111, 1e-12);
  EXPECT_NEAR(ct.row_spacing_m, 0.040, 1e-15);
  EXPECT_NEAR(ct.contact_angle_rad, 35.0 * kPi / 180.0, 1e-15);
  EXPECT_NEAR(ct.rotating_mass_kg, 46.3, 1e-12);
  EXPECT_NEAR(ct.tilt_inertia_kg_m2, 7.9, 1e-12);
  EXPECT_EQ(ct.rotating_ring, RotatingRing::Outer);
  EXPECT_EQ(ct.arrangement, Arrangement::BackToBack);
  const BearingConfig ins = load_bearing_config(bearing_file("ins_618_22_db.yaml"));
  EXPECT_EQ(ins.rows, 2);
  EXPECT_EQ(ins.balls_per_row, 10);
  EXPECT_NEAR(ins.inner_groove_curvature, 0.528, 1e-15);
  // Tilt inertia not given: derived from the envelope, m (3 (Ro^2 + Ri^2) + w^2) / 12 over
  // the outer ring's side of the pitch circle (Ro = 17 mm, Ri = 14 mm, w = 14 mm).
  EXPECT_FALSE(ins.tilt_inertia_given);
  EXPECT_NEAR(ins.tilt_inertia_kg_m2, 0.1 * (3.0 * (0.017 * 0.017 + 0.014 * 0.014) + 0.014 * 0.014) / 12.0, 1e-12);
}

// /dev/zero used to be read until memory ran out; a directory or a > 1 MiB file is refused too.
TEST(ConfigErrors, NonRegularOrHugeFilesAreRefusedNamingTheFile) {
  for (const std::string path : {"/dev/zero", "/tmp"}) {
    try {
      bearing_sim::load_bearing_config(path);
      ADD_FAILURE() << path << " accepted";
    } catch (const bearing_sim::ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
  const std::string big = ::testing::TempDir() + "bearing_sim_big.yaml";
  {
    std::FILE* f = std::fopen(big.c_str(), "w");
    ASSERT_NE(f, nullptr);
    const std::string line(1023, '#');
    for (int i = 0; i < 1100; ++i) std::fprintf(f, "%s\n", line.c_str());
    std::fclose(f);
  }
  try {
    bearing_sim::load_bearing_config(big);
    ADD_FAILURE() << "1.1 MiB file accepted";
  } catch (const bearing_sim::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("1 MiB"), std::string::npos) << e.what();
  }
  std::remove(big.c_str());
}

// An imperfections file (config/imperfections/) is read as the same sections of a bearing
// file: the shipped one holds four waviness components and one inner-race spall, and gives
// the spec a bearing file with its text appended gives.
TEST(ConfigErrors, AnImperfectionsFileReadsAsTheSameSectionsOfABearingFile) {
  const std::string file = config_path("imperfections/ct_gantry_waviness_and_spall.yaml");
  const ImperfectionSpec alone = load_imperfections(file, 1);
  ASSERT_EQ(alone.waviness.size(), 4u);
  EXPECT_EQ(alone.waviness[0].surface, Surface::InnerRace);
  EXPECT_EQ(alone.waviness[0].order, 206);
  EXPECT_EQ(alone.waviness[2].surface, Surface::OuterRace);
  EXPECT_EQ(alone.waviness[2].order, 8);
  EXPECT_NEAR(alone.waviness[2].amplitude_m, 0.5e-6, 1e-18);
  EXPECT_EQ(alone.waviness[3].surface, Surface::Ball);
  ASSERT_EQ(alone.spalls.size(), 1u);
  EXPECT_EQ(alone.spalls[0].surface, Surface::InnerRace);
  EXPECT_NEAR(alone.spalls[0].position_rad, kPi, 1e-15);
  EXPECT_NEAR(alone.spalls[0].width_m, 2e-3, 1e-18);
  EXPECT_NEAR(alone.spalls[0].depth_m, 20e-6, 1e-18);
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  const ImperfectionSpec in_bearing = bearing_config_from_string(yaml() + text.str(), kBearingSource).imperfections;
  ASSERT_EQ(in_bearing.waviness.size(), alone.waviness.size());
  for (std::size_t i = 0; i < alone.waviness.size(); ++i) {
    EXPECT_EQ(in_bearing.waviness[i].order, alone.waviness[i].order);
    EXPECT_EQ(in_bearing.waviness[i].amplitude_m, alone.waviness[i].amplitude_m);
  }
  ASSERT_EQ(in_bearing.spalls.size(), 1u);
  EXPECT_EQ(in_bearing.spalls[0].width_m, alone.spalls[0].width_m);
  EXPECT_EQ(in_bearing.spalls[0].row, alone.spalls[0].row);
}

// The balls' spin slip is given in degrees (docs/bearing_file.md): the spec holds radians,
// and without the keys no slip, counted opposite a load along x.
TEST(ConfigErrors, TheBallSpinSlipIsReadInDegrees) {
  const ImperfectionSpec given = imperfections_from_string(
      "imperfections: {ball_spin_slip_deg: 9, ball_spin_slip_azimuth_deg: -90}\n", kBearingSource, 1);
  EXPECT_NEAR(given.ball_spin_slip_rad, kPi / 20.0, 1e-15);
  EXPECT_NEAR(given.ball_spin_slip_azimuth_rad, -kPi / 2.0, 1e-15);
  EXPECT_FALSE(given.empty());
  const ImperfectionSpec absent = imperfections_from_string("imperfections: {}\n", kBearingSource, 1);
  EXPECT_EQ(absent.ball_spin_slip_rad, 0.0);
  EXPECT_NEAR(absent.ball_spin_slip_azimuth_rad, kPi, 1e-15);
}

// A ball spall's mean latitude is given in degrees; without the key the spall is on the track.
TEST(ConfigErrors, TheBallSpallLatitudeIsReadInDegrees) {
  const ImperfectionSpec given =
      imperfections_from_string("imperfections: {ball_spall_latitude_deg: 30}\n", kBearingSource, 1);
  EXPECT_NEAR(given.ball_spall_latitude_rad, kPi / 6.0, 1e-15);
  EXPECT_EQ(imperfections_from_string("imperfections: {}\n", kBearingSource, 1).ball_spall_latitude_rad, 0.0);
}

// Its keys are checked as a bearing file's, and a key of neither section is refused by name.
TEST(ConfigErrors, AnImperfectionsTextWithABadKeyIsRefusedNamingIt) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"imperfections: {}\ndefect: []\n", {"key 'defect'", "unknown key"}},
      {"defects: [{surface: outer_race, width_mm: 0, depth_um: 5}]\n", {"key 'defects[0].width_mm'", "must be > 0"}},
      {"imperfections: {roughness_row: 1}\n", {"key 'imperfections.roughness_row'", "one row"}},
      {"imperfections: {ball_spin_slip_deg: -1}\n", {"key 'imperfections.ball_spin_slip_deg'", "[0, 180] deg"}},
      {"imperfections: {ball_spin_slip_deg: 181}\n", {"key 'imperfections.ball_spin_slip_deg'", "[0, 180] deg"}},
      {"imperfections: {ball_spin_slip_deg: .nan}\n", {"key 'imperfections.ball_spin_slip_deg'", "finite"}},
      {"imperfections: {ball_spin_slip_deg: ten}\n", {"key 'imperfections.ball_spin_slip_deg'", "a number"}},
      {"imperfections: {ball_spall_latitude_deg: -1}\n",
       {"key 'imperfections.ball_spall_latitude_deg'", "[0, 90] deg"}},
      {"imperfections: {ball_spall_latitude_deg: 91}\n",
       {"key 'imperfections.ball_spall_latitude_deg'", "[0, 90] deg"}},
      {"imperfections: {ball_spin_slip_azimuth_deg: 400}\n",
       {"key 'imperfections.ball_spin_slip_azimuth_deg'", "[-360, 360] deg"}},
      {"- a list\n", {"expected a YAML mapping"}}};
  for (const auto& [text, words] : cases) {
    SCOPED_TRACE(text);
    try {
      imperfections_from_string(text, kBearingSource, 1);
      ADD_FAILURE() << "no ConfigError";
    } catch (const ConfigError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(kBearingSource), std::string::npos) << msg;
      for (const auto& w : words) EXPECT_NE(msg.find(w), std::string::npos) << "'" << w << "' not in: " << msg;
    }
  }
}
