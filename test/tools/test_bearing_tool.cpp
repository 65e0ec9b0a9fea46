// Runs the built bearing_tool binary (BEARING_TOOL_PATH) and checks its exit codes,
// messages and JSON against the core library and against published values.
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/core/flexible_bearing.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/simd_info.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "bearing_sim/core/constants.hpp"
#include "tool_runner.hpp"
#include "tool_test_files.hpp"

namespace {

using bearing_sim::kPi;
using bearing_sim::test::contains;
using bearing_sim::test::kConfigDir;
using bearing_sim::test::kCtBearingYaml;
using bearing_sim::test::kCtScanYaml;

using nlohmann::json;

using bearing_sim::test::read_text;
using bearing_sim::test::RunResult;

// A scratch directory for YAML and CSV files, removed at exit of the test.
class ToolTest : public bearing_sim::test::ToolScratchTest {
 protected:
  json run_json(const std::string& args) {
    const RunResult r = run(args + " --json");
    EXPECT_EQ(r.exit_code, 0) << args << "\n" << r.err;
    try {
      return json::parse(r.out);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not JSON: " << e.what() << "\n" << r.out;
      return json::object();
    }
  }
};

const std::string kIns = std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings/ins_618_22_db.yaml";

// 6205 deep-groove ball bearing (the usual fault-frequency example); no mass given.
const char* const k6205 =
    "name: 6205\n"
    "balls_per_row: 9\n"
    "ball_diameter_mm: 7.94\n"
    "pitch_diameter_mm: 39.04\n"
    "contact_angle_deg: 0\n"
    "inner_groove_curvature: 0.52\n"
    "outer_groove_curvature: 0.52\n";

// Single-row angular contact bearing (7205-like, 40 deg): carries axial load one way only.
const char* const kSingleRowAngular =
    "name: single row angular contact\n"
    "balls_per_row: 12\n"
    "ball_diameter_mm: 7.94\n"
    "pitch_diameter_mm: 38.5\n"
    "contact_angle_deg: 40\n"
    "inner_groove_curvature: 0.52\n"
    "outer_groove_curvature: 0.52\n";


// ---------------------------------------------------------------------------
// --help
// ---------------------------------------------------------------------------

TEST_F(ToolTest, HelpOnEverySubcommandExitsZeroAndListsItsOptions) {
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"static", {"--bearing", "--force", "--moment", "--cage-angle-deg", "--json"}},
      {"frequencies", {"--bearing", "--outer-rpm", "--inner-rpm", "--json"}},
      {"simulate",
       {"--bearing", "--force", "--moment", "--outer-rpm", "--inner-rpm", "--duration", "--rate", "--csv", "--substeps",
        "--json"}},
  };
  for (const auto& [command, options] : cases) {
    const RunResult r = run(command + " --help");
    EXPECT_EQ(r.exit_code, 0) << command;
    for (const auto& o : options) EXPECT_TRUE(contains(r.out, o)) << command << " --help lacks " << o << "\n" << r.out;
  }
  const RunResult top = run("--help");
  EXPECT_EQ(top.exit_code, 0);
  for (const char* c : {"static", "frequencies", "simulate"}) EXPECT_TRUE(contains(top.out, c)) << top.out;
}

TEST_F(ToolTest, NoSubcommandOrUnknownOptionIsBadInput) {
  EXPECT_EQ(run("").exit_code, 2);
  EXPECT_EQ(run("static --bearing '" + kCtBearingYaml + "' --no-such-option 1").exit_code, 2);
  const RunResult missing = run("static --force 1,0,0");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_TRUE(contains(missing.err, "--bearing")) << missing.err;
}

// ---------------------------------------------------------------------------
// Bad bearing files: exit 2, the message names the file and the key
// ---------------------------------------------------------------------------

TEST_F(ToolTest, UnknownKeyInBearingFileNamesFileAndKey) {
  const std::string path = write("unknown.yaml", std::string(k6205) + "ball_colour_mm: 3\n");
  const RunResult r = run("static --bearing '" + path + "' --force 100,0,0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, path)) << r.err;
  EXPECT_TRUE(contains(r.err, "ball_colour_mm")) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST_F(ToolTest, LoadWhoseMagnitudeOverflowsIsRefusedNotPrintedAsNaN) {
  // Finite components, but |F| overflows: before, static exited 0 printing NaN.
  const std::string path = write("b6205.yaml", std::string(k6205));
  const RunResult r = run("static --bearing '" + path + "' --force 1e300,1e300,0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "load")) << r.err;
  EXPECT_FALSE(contains(r.out, "nan")) << r.out;
}

TEST_F(ToolTest, MissingRequiredKeyNamesFileAndKey) {
  const std::string path = write("missing.yaml",
                                 "balls_per_row: 9\npitch_diameter_mm: 39.04\n"
                                 "inner_groove_curvature: 0.52\nouter_groove_curvature: 0.52\n");
  for (const char* command : {"static", "frequencies --inner-rpm 100", "simulate --outer-rpm 10"}) {
    const RunResult r = run(std::string(command) + " --bearing '" + path + "'");
    EXPECT_EQ(r.exit_code, 2) << command;
    EXPECT_TRUE(contains(r.err, path)) << r.err;
    EXPECT_TRUE(contains(r.err, "ball_diameter_mm")) << r.err;
  }
}

TEST_F(ToolTest, WrongTypeInBearingFileNamesFileAndKey) {
  std::string text = k6205;
  text.replace(text.find("balls_per_row: 9"), 16, "balls_per_row: nine");
  const std::string path = write("wrong_type.yaml", text);
  const RunResult r = run("frequencies --bearing '" + path + "' --inner-rpm 1800");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, path)) << r.err;
  EXPECT_TRUE(contains(r.err, "balls_per_row")) << r.err;
}

TEST_F(ToolTest, MissingBearingFileIsBadInputNamingIt) {
  const std::string path = dir_ + "/does_not_exist.yaml";
  const RunResult r = run("static --bearing '" + path + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, path)) << r.err;
}

// ---------------------------------------------------------------------------
// Bad numbers: exit 2 naming the option
// ---------------------------------------------------------------------------

TEST_F(ToolTest, BadVectorsAndNumbersNameTheOption) {
  const std::string b = " --bearing '" + kCtBearingYaml + "'";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"static" + b + " --force 1,2", "--force"},      // too few
      {"static" + b + " --force 1,2,3,4", "--force"},  // too many
      {"static" + b + " --force 1,nan,3", "--force"},  // NaN
      {"static" + b + " --force 1,inf,3", "--force"},  // infinite
      {"static" + b + " --force 1,abc,3", "--force"},  // not a number
      {"static" + b + " --moment 1", "--moment"},
      {"static" + b + " --moment 1,nan", "--moment"},
      {"static" + b + " --cage-angle-deg nan", "--cage-angle-deg"},
      {"frequencies" + b + " --outer-rpm nan", "--outer-rpm"},
      {"simulate" + b + " --outer-rpm 10 --duration -1", "--duration"},
      {"simulate" + b + " --outer-rpm 10 --duration nan", "--duration"},
      {"simulate" + b + " --outer-rpm 10 --rate 0", "--rate"},
      {"simulate" + b + " --outer-rpm 10 --substeps -3", "--substeps"},
  };
  for (const auto& [args, option] : cases) {
    const RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_TRUE(contains(r.err, option)) << args << "\n" << r.err;
  }
  // The NaN message says why.
  EXPECT_TRUE(contains(run("static" + b + " --force 1,nan,3").err, "finite"));
}

// ---------------------------------------------------------------------------
// Loads the bearing cannot carry
// ---------------------------------------------------------------------------

TEST_F(ToolTest, HugeAxialLoadOnSmallBearingIsNotCarried) {
  const RunResult r = run("static --bearing '" + kIns + "' --force 0,0,1e6");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "cannot carry")) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST_F(ToolTest, AxialLoadAgainstSingleRowAngularContactIsNotCarried) {
  const std::string path = write("single_row.yaml", kSingleRowAngular);
  // Force on the moving outer ring along +z lifts it off the contact lines
  // (normal (cos a0 cos phi, cos a0 sin phi, +sin a0) from inner to outer).
  const RunResult against = run("static --bearing '" + path + "' --force 0,0,100");
  EXPECT_EQ(against.exit_code, 2);
  EXPECT_TRUE(contains(against.err, "cannot carry")) << against.err;
  // The same force the other way is carried: the failure above is about direction.
  const json with = run_json("static --bearing '" + path + "' --force 0,0,-100");
  ASSERT_TRUE(with.contains("displacement"));
  EXPECT_LT(with["displacement"][2].get<double>(), 0.0);
  // The dynamic run refuses it too, with the same exit code.
  const std::string massive = write("single_row_mass.yaml", std::string(kSingleRowAngular) + "rotating_mass_kg: 0.2\n");
  const RunResult sim = run("simulate --bearing '" + massive + "' --force 0,0,100 --outer-rpm 100 --duration 0.01");
  EXPECT_EQ(sim.exit_code, 2);
  EXPECT_TRUE(contains(sim.err, "cannot carry")) << sim.err;
}

// ---------------------------------------------------------------------------
// static
// ---------------------------------------------------------------------------

TEST_F(ToolTest, StaticMatchesCoreSolverAndBallLoadsBalanceTheForce) {
  const bearing_sim::BearingModel model(bearing_sim::load_bearing_config(kCtBearingYaml));
  struct Case {
    std::string force, moment;
    bearing_sim::Vector5 load;
  };
  std::vector<Case> cases(2);
  cases[0] = {"6800,0,0", "0,2100", {}};
  cases[0].load << 6800, 0, 0, 0, 2100;
  cases[1] = {"3000,-2000,1500", "-300,800", {}};
  cases[1].load << 3000, -2000, 1500, -300, 800;
  for (const auto& c : cases) {
    const json j = run_json("static --bearing '" + kCtBearingYaml + "' --force " + c.force + " --moment " + c.moment);
    ASSERT_TRUE(j.contains("displacement") && j.contains("balls")) << j.dump();
    const bearing_sim::StaticSolution core = bearing_sim::solve_static(model, c.load);

    // Same solver, same inputs: equal up to the JSON round trip (exact for doubles).
    const double scale = core.displacement.norm();
    ASSERT_EQ(j["displacement"].size(), 5u);
    for (int i = 0; i < 5; ++i)
      EXPECT_NEAR(j["displacement"][i].get<double>(), core.displacement[i], 1e-9 * scale) << "dof " << i;
    for (int r = 0; r < 5; ++r)
      for (int k = 0; k < 5; ++k)
        EXPECT_NEAR(j["stiffness"][r][k].get<double>(), core.stiffness(r, k), 1e-9 * core.stiffness.norm());
    EXPECT_EQ(j["bushing_matrix"].size(), 6u);
    EXPECT_EQ(j["bushing_matrix"][5][5].get<double>(), 0.0);
    EXPECT_NEAR(j["max_ball_load_N"].get<double>(), core.max_ball_load_N, 1e-9 * core.max_ball_load_N);

    // Equilibrium from the ball list alone: the contact forces Q e on the moving ring
    // balance the applied force. With the reported normals: to the solver's tolerance
    // (1e-6 relative). From azimuth phi and contact angle a alone (docs/model.md section 5.2): the
    // contact line v = A e0 - s u has the radial-axial part at angle a and a tangential part
    // v_t = -s u.t (t = (-sin phi, cos phi, 0)) of length |v| = A + g0 + delta; leaving v_t
    // out is 0.44 % off for the CT case (|u| / A = 6.6 um / 1.3 mm). Taking v_t from the
    // translation (x, y) only neglects the tilt's share theta * z (about 0.3 um against 6.6 um,
    // a few % of that 0.44 %): within 0.1 % of |F|.
    const double A = model.groove_centre_distance_m(), s = model.moving_sign(), g0 = model.config().clearance_m;
    const double ux = j["displacement"][0], uy = j["displacement"][1];
    ASSERT_EQ(j["balls"].size(), static_cast<std::size_t>(model.ball_count()));
    double fx = 0, fy = 0, fz = 0, fx_angles = 0, fy_angles = 0, max_load = 0;
    for (const auto& b : j["balls"]) {
      const double q = b["load_N"], phi = b["azimuth_deg"].get<double>() * kPi / 180.0,
                   a = b["contact_angle_deg"].get<double>() * kPi / 180.0;
      fx += q * b["normal"][0].get<double>();
      fy += q * b["normal"][1].get<double>();
      fz += q * b["normal"][2].get<double>();
      const double e_t = -s * (-ux * std::sin(phi) + uy * std::cos(phi)) / (A + g0 + b["deflection_m"].get<double>());
      const double e_r = std::cos(a) * std::sqrt(1.0 - e_t * e_t);
      fx_angles += q * (e_r * std::cos(phi) - e_t * std::sin(phi));
      fy_angles += q * (e_r * std::sin(phi) + e_t * std::cos(phi));
      max_load = std::max(max_load, q);
      EXPECT_GE(q, 0.0);
      EXPECT_TRUE(b.contains("row") && b.contains("deflection_m") && b.contains("pressure_Pa"));
    }
    const double f_norm = c.load.head<3>().norm();
    EXPECT_NEAR(fx, -c.load[0], 1e-6 * f_norm);
    EXPECT_NEAR(fy, -c.load[1], 1e-6 * f_norm);
    EXPECT_NEAR(fz, -c.load[2], 1e-6 * f_norm);
    EXPECT_NEAR(fx_angles, -c.load[0], 1e-3 * f_norm);
    EXPECT_NEAR(fy_angles, -c.load[1], 1e-3 * f_norm);
    EXPECT_DOUBLE_EQ(max_load, j["max_ball_load_N"].get<double>());
  }
}

TEST_F(ToolTest, StaticCtCaseHasThePublishedMagnitudes) {
  // The example: x about 6.6 um, theta_y about 1.47e-5 rad, max ball load about 171 N.
  const json j = run_json("static --bearing '" + kCtBearingYaml + "' --force 6800,0,0 --moment 0,2100");
  EXPECT_NEAR(j["displacement"][0].get<double>(), 6.6e-6, 0.1e-6);
  EXPECT_NEAR(j["displacement"][4].get<double>(), 1.47e-5, 0.01e-5);
  EXPECT_NEAR(j["max_ball_load_N"].get<double>(), 171.0, 1.0);
  EXPECT_TRUE(j["warnings"].empty());
  EXPECT_LT(j["residual_N"].get<double>(), 1e-6);
}

TEST_F(ToolTest, StaticTableShowsTheJsonValuesInDisplayUnits) {
  const std::string args = "static --bearing '" + kCtBearingYaml + "' --force 6800,0,0 --moment 0,2100";
  const RunResult r = run(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = run_json(args);
  char x_um[32], load[32];
  std::snprintf(x_um, sizeof x_um, "%.4f", j["displacement"][0].get<double>() * 1e6);
  std::snprintf(load, sizeof load, "%.2f N", j["max_ball_load_N"].get<double>());
  EXPECT_TRUE(contains(r.out, x_um)) << x_um << "\n" << r.out;
  EXPECT_TRUE(contains(r.out, load)) << load;
  for (const char* s : {"N/um", "N*m/urad", "MPa", "Loaded balls", "contact angle deg"})
    EXPECT_TRUE(contains(r.out, s)) << s;
}

TEST_F(ToolTest, PressureWarningExactlyAboveThePermissibleLimit) {
  // INS 618/22 pair (3 mm balls): about 3000 MPa at 1 kN radial, over 5000 MPa at 6 kN.
  for (const char* force : {"1000,0,0", "6000,0,0"}) {
    const RunResult r = run("static --json --bearing '" + kIns + "' --force " + force);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json j = json::parse(r.out);
    const bool above = j["max_contact_pressure_Pa"].get<double>() > bearing_sim::kPermissibleContactPressurePa;
    EXPECT_EQ(!j["warnings"].empty(), above) << force;
    EXPECT_EQ(contains(r.err, "warning"), above) << force << r.err;
    EXPECT_EQ(above, std::string(force) == "6000,0,0");
  }
}

// ---------------------------------------------------------------------------
// frequencies
// ---------------------------------------------------------------------------

TEST_F(ToolTest, FrequenciesOf6205MatchPublishedOrders) {
  const std::string path = write("6205.yaml", k6205);
  // Inner ring at 1800 rpm (30 Hz), outer fixed; the file's default rotating ring is the
  // outer one: frequencies takes both speeds regardless.
  const json j = run_json("frequencies --bearing '" + path + "' --inner-rpm 1800 --outer-rpm 0");
  const double fr = 30.0;
  // Published multiples of shaft speed for the 6205 (e.g. SKF calculator, CWRU data set).
  EXPECT_NEAR(j["ball_pass_outer_race_hz"].get<double>() / fr, 3.5848, 1e-3 * 3.5848);
  EXPECT_NEAR(j["ball_pass_inner_race_hz"].get<double>() / fr, 5.4152, 1e-3 * 5.4152);
  EXPECT_NEAR(j["cage_hz"].get<double>() / fr, 0.39828, 1e-3 * 0.39828);
  // dm/(2d) (1 - gamma^2) = 2.3567 for these dimensions (the tabulated BSF is twice this).
  EXPECT_NEAR(j["ball_spin_hz"].get<double>() / fr, 2.3567, 1e-3 * 2.3567);
  EXPECT_NEAR(j["relative_ring_hz"].get<double>(), fr, 1e-9);
  // Balls pass the fixed outer ring's load zone: Z f_c.
  EXPECT_NEAR(j["varying_compliance_hz"].get<double>(), 9 * j["cage_hz"].get<double>(), 1e-9);

  // The outer ring turning instead: ball pass on the outer race becomes Z (1 + gamma)/2 f_r.
  const json o = run_json("frequencies --bearing '" + path + "' --outer-rpm 1800");
  const double gamma = 7.94 / 39.04;
  EXPECT_NEAR(o["ball_pass_outer_race_hz"].get<double>(), 9 * (1 - gamma) / 2 * fr, 1e-9 * fr);
  EXPECT_NEAR(o["ball_pass_inner_race_hz"].get<double>(), 9 * (1 + gamma) / 2 * fr, 1e-9 * fr);
}

// ---------------------------------------------------------------------------
// simulate
// ---------------------------------------------------------------------------

std::vector<std::vector<double>> parse_csv(const std::string& path, std::string* header) {
  std::ifstream in(path);
  std::vector<std::vector<double>> rows;
  std::getline(in, *header);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

// --simd-target pins the kernels' target (a dataset byte-identical across machines): the
// narrowest target this CPU runs gives the best one's result to rounding. The smooth CT
// bearing's vibration (8.5e-5 m/s^2 on 46 kg: 4 mN) is what is left of 6800 N force sums,
// whose rounding in another order (~1e-12 N per evaluation) moves a_rms by ~1e-8 of itself
// (seen: 1.5e-8); 1e-6 is a wide margin, while a kernel that differed would be percent off.
// A name this CPU cannot run is refused naming it and the targets it can.
TEST_F(ToolTest, SimdTargetPinsTheKernelsAndOneThisCpuCannotRunIsRefused) {
  const std::string targets = bearing_sim::runnable_simd_targets();
  const std::size_t comma = targets.rfind(", ");
  const std::string narrowest = comma == std::string::npos ? targets : targets.substr(comma + 2);
  const std::string args =
      "simulate --bearing '" + kCtBearingYaml + "' --force 6800,0,0 --moment 0,2100 --outer-rpm 180 --duration 0.05";
  const json best = run_json(args);
  const json pinned = run_json("--simd-target " + narrowest + " " + args);
  EXPECT_EQ(best["simd_target"], bearing_sim::simd_target_name());
  EXPECT_EQ(pinned["simd_target"], narrowest);
  const double a = best["a_rms_x"].get<double>();
  ASSERT_GT(a, 0.0);
  EXPECT_NEAR(pinned["a_rms_x"].get<double>(), a, 1e-6 * a);
  const RunResult bad = run("--simd-target NO_SUCH_TARGET " + args);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(contains(bad.err, "--simd-target NO_SUCH_TARGET")) << bad.err;
  EXPECT_TRUE(contains(bad.err, narrowest)) << bad.err;
}

TEST_F(ToolTest, SimulateCsvHasOneRowPerSampleAndMeanIsTheStaticDisplacement) {
  const double duration = 0.1, rate = 7000.0;  // 700 samples
  const std::size_t expected_rows = 700;
  const std::string csv = dir_ + "/run.csv";
  const json j = run_json("simulate --bearing '" + kCtBearingYaml + "' --force 6800,0,0 --moment 0,2100 --outer-rpm 180 " +
                          "--duration 0.1 --rate 7000 --csv '" + csv + "'");
  ASSERT_TRUE(j.contains("mean_displacement")) << j.dump();

  std::string header;
  const auto rows = parse_csv(csv, &header);
  EXPECT_EQ(header, "time_s,x_m,y_m,z_m,theta_x_rad,theta_y_rad,ax_m_s2,ay_m_s2,az_m_s2,alpha_x_rad_s2,alpha_y_rad_s2");
  ASSERT_EQ(rows.size(), expected_rows);
  EXPECT_EQ(j["samples"].get<std::size_t>(), expected_rows);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), 11u) << "row " << i;
    if (i > 0) {
      EXPECT_NEAR(rows[i][0] - rows[i - 1][0], 1.0 / rate, 1e-9) << "row " << i;
    }
  }
  EXPECT_NEAR(rows.back()[0] - rows.front()[0], (expected_rows - 1) / rate, 1e-9);
  EXPECT_LE(rows.back()[0], duration + 1e-9);

  // The CSV holds the samples the summary was computed from: its second-half mean of x
  // equals the summary (to the 11 significant digits printed).
  double mean_x = 0;
  for (std::size_t i = expected_rows / 2; i < expected_rows; ++i) mean_x += rows[i][1];
  mean_x /= static_cast<double>(expected_rows - expected_rows / 2);
  EXPECT_NEAR(mean_x, j["mean_displacement"][0].get<double>(), 1e-9 * std::abs(mean_x));

  // A smooth bearing started at its static equilibrium stays there on average: the mean
  // displacement equals the core's static solution within 0.5 % (of each non-zero
  // component; the zero ones within 0.5 % of the displacement's size).
  const bearing_sim::BearingModel model(bearing_sim::load_bearing_config(kCtBearingYaml));
  bearing_sim::Vector5 load;
  load << 6800, 0, 0, 0, 2100;
  const auto eq = bearing_sim::solve_static(model, load);
  const double trans = eq.displacement.head<3>().norm(), tilt = eq.displacement.tail<2>().norm();
  for (int i = 0; i < 5; ++i) {
    const double tol = 5e-3 * std::max(std::abs(eq.displacement[i]), 1e-3 * (i < 3 ? trans : tilt));
    EXPECT_NEAR(j["mean_displacement"][i].get<double>(), eq.displacement[i], tol) << "dof " << i;
  }

  // L is a_rms_x in dB re 9.81e-3 m/s^2; a smooth 207-ball bearing is near -40 dB (docs/model.md section 11.2).
  const double a_rms = j["a_rms_x"];
  EXPECT_GT(a_rms, 0.0);
  EXPECT_NEAR(j["L_dB"].get<double>(), 20 * std::log10(a_rms / 9.81e-3), 1e-9);
  EXPECT_GT(j["L_dB"].get<double>(), -60.0);
  EXPECT_LT(j["L_dB"].get<double>(), -20.0);
  EXPECT_GE(j["substeps"].get<double>(), 1.0);  // steps per sample, a multiple of 1/4 for the Adams methods
  EXPECT_NEAR(j["internal_step_s"].get<double>(), 1.0 / (rate * j["substeps"].get<double>()), 1e-15);
  EXPECT_GT(j["realtime_factor"].get<double>(), 0.0);
}

// --sensor: the healthy CT bearing's ring vibrates far below the housing accelerometer's noise
// floor, so its output on x is the sensor noise through the anti-alias filter. Noise of
// one-sided density D through an order-n Butterworth low-pass at f_c has the RMS
// D sqrt(f_c (pi / 2n) / sin(pi / 2n)) (its equivalent noise bandwidth): 9.33e-4 m/s^2 for the
// shipped file. The ring's own x acceleration (a_rms_x, ~8e-5 m/s^2) adds in quadrature
// (+0.4 %), and the RMS of 0.5 s of noise 4 kHz wide scatters by about 1/sqrt(2 B T) = 1.1 %:
// 5 % holds both. Gaussian noise has kurtosis 3 (its estimate from 5000 correlated samples
// scatters by ~0.1).
TEST_F(ToolTest, SimulateThroughASensorGivesItsNoiseFloorAndWritesItsSamples) {
  const std::string sensor_file =
      std::string(BEARING_SIM_SOURCE_DIR) + "/config/sensors/ct_gantry_housing_accelerometer.yaml";
  const std::string csv = dir_ + "/sensor.csv";
  const json j = run_json("simulate --bearing '" + kCtBearingYaml + "' --force 6800,0,0 --moment 0,2100 --outer-rpm 180 " +
                          "--duration 1 --sensor '" + sensor_file + "' --sensor-csv '" + csv + "'");
  ASSERT_TRUE(j["sensor"].is_object()) << j.dump();
  const bearing_sim::AccelerometerConfig config = bearing_sim::load_accelerometer_config(sensor_file);
  const double pi = 3.141592653589793, n = config.anti_alias_order;
  const double bandwidth =
      config.anti_alias_cutoff_fraction * config.output_rate_hz * (pi / (2 * n)) / std::sin(pi / (2 * n));
  const double noise_rms = config.noise_density_m_s2_per_sqrt_hz * std::sqrt(bandwidth);
  EXPECT_NEAR(j["sensor"]["rms"][0].get<double>(), noise_rms, 0.05 * noise_rms);
  EXPECT_NEAR(j["sensor"]["kurtosis"][0].get<double>(), 3.0, 0.3);
  EXPECT_EQ(j["sensor"]["unit"], "m_s2");
  EXPECT_EQ(j["sensor"]["clipped_samples"].get<int>(), 0);

  // One CSV row per sensor sample (same rate as the run here); the second half's RMS of x
  // recomputed from the file equals the summary's (to the 11 digits written).
  std::string header;
  const auto rows = parse_csv(csv, &header);
  EXPECT_EQ(header, "time_s,x_m_s2,y_m_s2,z_m_s2");
  ASSERT_EQ(rows.size(), 10000u);
  EXPECT_EQ(j["sensor"]["samples"].get<std::size_t>(), rows.size());
  double mean = 0, ss = 0;
  const std::size_t half = rows.size() / 2;
  for (std::size_t i = half; i < rows.size(); ++i) mean += rows[i][1];
  mean /= static_cast<double>(rows.size() - half);
  for (std::size_t i = half; i < rows.size(); ++i) ss += (rows[i][1] - mean) * (rows[i][1] - mean);
  const double rms = std::sqrt(ss / static_cast<double>(rows.size() - half));
  EXPECT_NEAR(rms, j["sensor"]["rms"][0].get<double>(), 1e-8 * rms);

  // Without --sensor the JSON says so (null), and --sensor-csv alone is refused.
  const json ideal =
      run_json("simulate --bearing '" + kCtBearingYaml + "' --force 6800,0,0 --moment 0,2100 --outer-rpm 180 --duration 0.01");
  EXPECT_TRUE(ideal["sensor"].is_null());
  const RunResult alone =
      run("simulate --bearing '" + kCtBearingYaml + "' --outer-rpm 10 --duration 0.01 --sensor-csv '" + csv + "'");
  EXPECT_EQ(alone.exit_code, 2);
  EXPECT_NE(alone.err.find("--sensor"), std::string::npos) << alone.err;
  // A sensor that cannot run at the run's rate (its 10 kHz output does not divide 7 kHz).
  const RunResult rate =
      run("simulate --bearing '" + kCtBearingYaml + "' --outer-rpm 10 --duration 0.01 --rate 7000 --sensor '" + sensor_file + "'");
  EXPECT_EQ(rate.exit_code, 2);
  EXPECT_NE(rate.err.find("--sensor"), std::string::npos) << rate.err;
}

TEST_F(ToolTest, SimulateExplicitSubstepsAreUsed) {
  const json j = run_json("simulate --bearing '" + kCtBearingYaml +
                          "' --force 6800,0,0 --outer-rpm 180 --duration 0.01 "
                          "--rate 10000 --substeps 3");
  EXPECT_EQ(j["substeps"].get<int>(), 3);
  EXPECT_NEAR(j["internal_step_s"].get<double>(), 1.0 / 30000.0, 1e-15);
  EXPECT_EQ(j["samples"].get<int>(), 100);
}

TEST_F(ToolTest, SimulateRefusesASpeedOnTheFixedRing) {
  // CT file: the outer ring turns, the inner one is fixed.
  const RunResult r = run("simulate --bearing '" + kCtBearingYaml +
                          "' --force 6800,0,0 --outer-rpm 180 --inner-rpm 10 "
                          "--duration 0.01");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--inner-rpm")) << r.err;
  EXPECT_TRUE(contains(r.err, "fixed")) << r.err;

  // A file with the inner ring turning: then the outer one must be still.
  std::string text = read_text(kIns);
  text.replace(text.find("rotating_ring: outer"), 20, "rotating_ring: inner");
  const std::string path = write("inner.yaml", text);
  const RunResult o = run("simulate --bearing '" + path + "' --force 100,0,0 --outer-rpm 5 --duration 0.01");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_TRUE(contains(o.err, "--outer-rpm")) << o.err;
  // ... and its own speed is accepted.
  EXPECT_EQ(run("simulate --json --bearing '" + path +
                "' --force 100,0,0 --inner-rpm 600 --duration 0.002 "
                "--rate 10000")
                .exit_code,
            0);
  // frequencies takes both speeds.
  EXPECT_EQ(run("frequencies --bearing '" + kCtBearingYaml + "' --outer-rpm 180 --inner-rpm 10").exit_code, 0);
}

TEST_F(ToolTest, SimulateWithoutMassIsBadInputNamingTheKey) {
  const std::string path = write("6205.yaml", k6205);
  const RunResult r = run("simulate --bearing '" + path + "' --force 1000,0,0 --outer-rpm 100 --duration 0.01");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "rotating_mass_kg")) << r.err;
}

TEST_F(ToolTest, SimulateUnwritableCsvIsBadInput) {
  const RunResult r = run("simulate --bearing '" + kCtBearingYaml + "' --force 6800,0,0 --outer-rpm 180 --duration 0.01 --csv '" +
                          dir_ + "/no/such/dir/run.csv'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--csv")) << r.err;
}

// A flexible ring (docs/model.md section 18): static reports the core's flexible equilibrium
// beside the rigid ring's peak; simulate writes the modal coordinates.
const std::string kCtFlexible = std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings/ct_gantry_flexible.yaml";

TEST_F(ToolTest, StaticWithAFlexibleRingIsTheCoresFlexibleEquilibrium) {
  const json j = run_json("static --bearing '" + kCtFlexible + "' --force 6800,0,0 --moment 0,2100");
  const bearing_sim::BearingModel model(bearing_sim::load_bearing_config(kCtFlexible));
  const bearing_sim::Vector5 load = (bearing_sim::Vector5() << 6800, 0, 0, 0, 2100).finished();
  const bearing_sim::FlexibleStaticSolution core =
      bearing_sim::solve_flexible_static(bearing_sim::FlexibleBearing(model), load);
  const double rigid_peak = bearing_sim::solve_static(model, load).max_ball_load_N;
  ASSERT_TRUE(j["flexible_ring"].is_object()) << j.dump();
  // The same computation: equal to the printed digits (JSON doubles round-trip).
  EXPECT_NEAR(j["max_ball_load_N"].get<double>(), core.rigid_coordinates.max_ball_load_N, 1e-9);
  EXPECT_NEAR(j["flexible_ring"]["rigid_ring_max_ball_load_N"].get<double>(), rigid_peak, 1e-9);
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(j["displacement"][i].get<double>(), core.coordinates[i], 1e-15) << i;
  // Ten modes, n = 2..6 in and out of plane; the first is the free ring's n = 2 (Hoppe, 84.7 Hz).
  ASSERT_EQ(j["flexible_ring"]["modes"].size(), 10u);
  EXPECT_EQ(j["flexible_ring"]["modes"][0]["direction"], "in_plane");
  EXPECT_NEAR(j["flexible_ring"]["modes"][0]["frequency_hz"].get<double>(), 84.7, 0.05);
  EXPECT_EQ(j["flexible_ring"]["natural_frequencies_hz"].size(), 25u);
  // A rigid ring's file has none.
  EXPECT_TRUE(run_json("static --bearing '" + kCtBearingYaml + "' --force 6800,0,0")["flexible_ring"].is_null());
}

TEST_F(ToolTest, SimulateWithAFlexibleRingWritesTheModalCoordinates) {
  const std::string csv = dir_ + "/flexible.csv";
  const json j = run_json("simulate --bearing '" + kCtFlexible + "' --force 6800,0,0 --moment 0,2100 " +
                          "--outer-rpm 180 --duration 0.01 --rate 5000 --csv '" + csv + "'");
  EXPECT_EQ(j["integrator"], "adams_pec");  // the default, as for a rigid ring
  EXPECT_EQ(j["samples"].get<int>(), 50);
  ASSERT_EQ(j["flexible_ring"].size(), 10u);
  std::string header;
  const auto rows = parse_csv(csv, &header);
  ASSERT_EQ(rows.size(), 50u);
  EXPECT_NE(header.find(",ring_in_plane_n2_cos_m,ring_in_plane_n2_sin_m,"), std::string::npos) << header;
  EXPECT_NE(header.find(",ring_out_of_plane_n6_sin_m"), std::string::npos) << header;
  ASSERT_EQ(rows[0].size(), 11u + 20u);
  // The first sample (0.2 ms in) still holds the static shape: the n = 2 in-plane amplitude,
  // which turns through the ring at 2 x 3 Hz, within 1 %.
  const double a = rows[0][11], b = rows[0][12];
  const double static_amplitude = j["flexible_ring"][0]["static_amplitude_m"].get<double>();
  EXPECT_NEAR(std::hypot(a, b), static_amplitude, 0.01 * static_amplitude);
  // RK4, the reference, on request; other integrators are refused, naming the option.
  EXPECT_EQ(run_json("simulate --bearing '" + kCtFlexible + "' --force 6800,0,0 --outer-rpm 180 --duration 0.01 " +
                     "--integrator rk4")["integrator"],
            "rk4");
  const RunResult r = run("simulate --bearing '" + kCtFlexible +
                          "' --force 6800,0,0 --outer-rpm 180 --duration 0.01 "
                          "--integrator etdrk4");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--integrator"), std::string::npos) << r.err;
}

}  // namespace
