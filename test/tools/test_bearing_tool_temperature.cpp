// bearing_tool --ring-temperature-difference-K (docs/model.md section 3.7): static moves the
// ring as a cold bearing with the operating clearance does; NaN, inf, words and values that
// leave the model's clearance range exit 2 naming the option, for static, simulate, generate.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bearing_sim/core/constants.hpp"
#include "tool_runner.hpp"
#include "tool_test_files.hpp"

namespace {

using bearing_sim::kPi;
using bearing_sim::test::contains;
using bearing_sim::test::kConfigDir;
using bearing_sim::test::kCtBearingYaml;
using bearing_sim::test::kCtScanYaml;

using bearing_sim::test::RunResult;


// A 6205-like deep groove bearing (a0 = 0, dm = 39.04 mm) with the given clearance.
std::string bearing_6205(double clearance_um) {
  return "name: 6205-like\nballs_per_row: 9\nball_diameter_mm: 7.94\npitch_diameter_mm: 39.04\n"
         "inner_groove_curvature: 0.52\nouter_groove_curvature: 0.52\nrotating_ring: inner\n"
         "rotating_mass_kg: 0.5\ndamping: {contact_damping_Ns_per_m: 100}\nclearance_um: " +
         std::to_string(clearance_um) + "\n";
}

class ToolTemperatureTest : public bearing_sim::test::ToolScratchTest {
 protected:
  nlohmann::json static_json(const std::string& args) {
    const RunResult r = run("static --json " + args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  }
  void expect_refused(const std::string& args, const std::vector<std::string>& words) {
    SCOPED_TRACE(args);
    const RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    for (const auto& w : words) EXPECT_NE(r.err.find(w), std::string::npos) << "'" << w << "' not in: " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
};

}  // namespace

TEST_F(ToolTemperatureTest, StaticAtATemperatureDifferenceIsTheColdBearingWithItsClearance) {
  const std::string warm = write("b10.yaml", bearing_6205(10.0));
  const nlohmann::json hot = static_json("--bearing '" + warm + "' --force 300,0,0 --ring-temperature-difference-K 20");
  // -alpha dT dm / 2 = -11.5e-6 * 20 * 19.52 mm = -4.4896 um
  const double g_um = hot["bearing"]["operating_clearance_um"].get<double>();
  EXPECT_NEAR(g_um, 10.0 - 11.5e-6 * 20.0 * 19.52e3, 1e-9);
  EXPECT_EQ(hot["bearing"]["ring_temperature_difference_K"].get<double>(), 20.0);
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", g_um);
  std::string eq_text = bearing_6205(0.0);
  eq_text.replace(eq_text.find("clearance_um: "), std::string::npos, std::string("clearance_um: ") + text + "\n");
  const nlohmann::json eq = static_json("--bearing '" + write("b_equivalent.yaml", eq_text) + "' --force 300,0,0");
  EXPECT_NEAR(hot["displacement"][0].get<double>(), eq["displacement"][0].get<double>(), 1e-13);
  // The closed clearance moves the ring less than the cold bearing does.
  const nlohmann::json cold10 = static_json("--bearing '" + warm + "' --force 300,0,0");
  EXPECT_LT(hot["displacement"][0].get<double>(), cold10["displacement"][0].get<double>() - 4.4e-6);
}

TEST_F(ToolTemperatureTest, BadValuesExit2NamingTheOption) {
  for (const std::string v : {"nan", "inf", "-inf", "warm"}) {
    expect_refused("static --bearing '" + kCtBearingYaml + "' --ring-temperature-difference-K " + v,
                   {"--ring-temperature-difference-K"});
    expect_refused("simulate --bearing '" + kCtBearingYaml +
                       "' --force 6800,0,0 --moment 0,2100 --outer-rpm 180 "
                       "--duration 0.01 --ring-temperature-difference-K " +
                       v,
                   {"--ring-temperature-difference-K"});
    expect_refused("generate '" + kCtScanYaml + "' --out '" + dir_ + "/out' --quiet --ring-temperature-difference-K " + v,
                   {"--ring-temperature-difference-K"});
  }
  // 120 K on the CT bearing's 1111 mm pitch circle: 630 um of interference, beyond 5 % of d.
  expect_refused("static --bearing '" + kCtBearingYaml + "' --force 6800,0,0 --ring-temperature-difference-K 120",
                 {"--ring-temperature-difference-K", "interference", "5 % of the ball diameter"});
  expect_refused("simulate --bearing '" + kCtBearingYaml +
                     "' --force 6800,0,0 --moment 0,2100 --outer-rpm 180 "
                     "--duration 0.01 --ring-temperature-difference-K 200",
                 {"--ring-temperature-difference-K", "150 K"});
  expect_refused("generate '" + kCtScanYaml + "' --out '" + dir_ + "/out' --quiet --ring-temperature-difference-K 120",
                 {"ring temperature difference 120 K", "interference"});
}
