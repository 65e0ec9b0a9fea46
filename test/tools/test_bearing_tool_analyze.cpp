// bearing_tool analyze on a CSV written by bearing_tool simulate --csv: the indicators
// must be those of the core library on the same signal (computed here in-process from
// the same simulation), and the command must reject bad input with exit code 2.
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

#include "../core/bearing_6205_yaml.hpp"
#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/condition_indicators.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/simulation_run.hpp"
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

// 6205-like, inner ring rotating, a 1 mm x 30 um outer race spall (as test_envelope_faults).
const std::string kBearing = bearing_sim::test::kBearing6205Yaml +
                             "imperfections: {seed: 3, roughness_rms_um: 0.02}\n"
                             "defects: [{surface: outer_race, position_deg: 0, width_mm: 1.0, depth_um: 30}]\n";

using bearing_sim::test::RunResult;

class AnalyzeTool : public bearing_sim::test::ToolScratchTest {
 protected:
  void SetUp() override {
    ToolScratchTest::SetUp();
    bearing_ = write("b.yaml", kBearing);
  }

  std::string bearing_;
};

TEST_F(AnalyzeTool, SameIndicatorsAsTheLibrary) {
  const std::string csv = dir_ + "/run.csv";
  const RunResult sim = run("simulate --bearing '" + bearing_ +
                            "' --force 1000,0,200 --inner-rpm 1800 --rate 40000 --duration 1 --csv '" + csv + "'");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const RunResult r =
      run("analyze --csv '" + csv + "' --bearing '" + bearing_ + "' --inner-rpm 1800 --window-s 0.8 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out);

  // The library on the same run, in-process (the dynamics are deterministic).
  const bearing_sim::BearingModel model(bearing_sim::bearing_config_from_string(kBearing));
  bearing_sim::SimulationRequest req;
  req.load << 1000.0, 0.0, 200.0, 0.0, 0.0;
  req.ring_speed_rad_s = 1800.0 * 2.0 * kPi / 60.0;
  req.duration_s = 1.0;
  req.sample_rate_hz = 40000.0;
  std::vector<double> ax;
  bearing_sim::run_simulation(model, req,
                              [&ax](const bearing_sim::DynamicSample& s) { ax.push_back(s.acceleration[0]); });
  bearing_sim::AnalysisOptions o;
  o.window_s = 0.8;
  const bearing_sim::ConditionIndicators c =
      bearing_sim::analyze_vibration(ax, 40000.0, bearing_sim::bearing_frequencies(model, req.ring_speed_rad_s), o);

  // The CSV holds 11 significant digits and the rate comes from its time column
  // (%.12g): agreement to 1e-6 relative is far tighter than any physical effect.
  const auto near = [](double tool, double lib) { EXPECT_NEAR(tool, lib, 1e-6 * std::abs(lib) + 1e-12); };
  EXPECT_NEAR(j["sample_rate_hz"].get<double>(), 40000.0, 1e-4);
  EXPECT_EQ(j["samples"].get<std::size_t>(), c.samples);
  near(j["rms_m_s2"], c.acceleration.rms);
  near(j["peak_m_s2"], c.acceleration.peak);
  near(j["crest_factor"], c.acceleration.crest_factor);
  near(j["kurtosis"], c.acceleration.kurtosis);
  near(j["L_dB"], c.level_db);
  near(j["velocity_rms_mm_s"], c.velocity_rms_mm_s);
  EXPECT_EQ(j["zone"], bearing_sim::velocity_zone_name(c.zone));
  EXPECT_EQ(j["envelope_band_source"], "kurtogram");
  near(j["envelope_band_hz"][0], c.envelope_low_hz);
  near(j["envelope_band_hz"][1], c.envelope_high_hz);
  EXPECT_NEAR(j["envelope_band_kurtosis"].get<double>(), c.envelope_band_kurtosis, 1e-4);
  ASSERT_EQ(j["faults"].size(), c.faults.size());
  for (std::size_t k = 0; k < c.faults.size(); ++k) {
    const json& p = j["faults"][k]["envelope_peak"];
    near(p["frequency_hz"], c.faults[k].envelope_peak.frequency_hz);
    near(p["amplitude_m_s2"], c.faults[k].envelope_peak.amplitude);
    EXPECT_NEAR(p["snr_db"].get<double>(), c.faults[k].envelope_peak.snr_db, 1e-4);
    EXPECT_EQ(j["faults"][k]["suspected"].get<bool>(), c.faults[k].suspected);
    // The evidence behind the decision.
    const bearing_sim::FaultIndicator& f = c.faults[k];
    EXPECT_EQ(j["faults"][k]["harmonics_found"].get<int>(), f.harmonics_found);
    EXPECT_EQ(j["faults"][k]["sidebands_found"].get<int>(), f.sidebands_found);
    EXPECT_EQ(j["faults"][k]["sidebands_required"].get<bool>(), f.sidebands_required);
    EXPECT_EQ(j["faults"][k]["resolvable"].get<bool>(), f.resolvable);
    EXPECT_EQ(j["faults"][k]["impulsiveness_required"].get<bool>(), f.impulsiveness_required);
    EXPECT_EQ(j["faults"][k]["impulsive"].get<bool>(), f.impulsive);
    EXPECT_EQ(j["faults"][k]["note"].get<std::string>(), f.note);
    ASSERT_EQ(j["faults"][k]["harmonics"].size(), f.harmonics.size());
    for (std::size_t n = 0; n < f.harmonics.size(); ++n) {
      const json& h = j["faults"][k]["harmonics"][n];
      EXPECT_EQ(h["order"].get<int>(), f.harmonics[n].order);
      EXPECT_EQ(h["found"].get<bool>(), f.harmonics[n].found);
      EXPECT_NEAR(h["peak"]["snr_db"].get<double>(), f.harmonics[n].peak.snr_db, 1e-4);
    }
    ASSERT_EQ(j["faults"][k]["sidebands"].size(), f.sidebands.size());
  }
  // The outer race spall's BPFO series: fundamental and 2nd harmonic found (the inner ring
  // turns, the outer stands: no sidebands required).
  EXPECT_GE(j["faults"][0]["harmonics_found"].get<int>(), 2);
  EXPECT_FALSE(j["faults"][0]["sidebands_required"].get<bool>());
  EXPECT_EQ(j["level"], bearing_sim::health_level_name(c.diagnosis.level));
  EXPECT_EQ(j["reason"], c.diagnosis.reason);
  // And physically: the outer race spall is what the tool reports.
  EXPECT_TRUE(j["faults"][0]["suspected"].get<bool>());
  EXPECT_NE(j["reason"].get<std::string>().find("outer race defect suspected"), std::string::npos);

  // The human table carries the same diagnosis line.
  const RunResult t = run("analyze --csv '" + csv + "' --bearing '" + bearing_ + "' --inner-rpm 1800 --window-s 0.8");
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_NE(t.out.find("Diagnosis: " + std::string(bearing_sim::health_level_name(c.diagnosis.level))),
            std::string::npos)
      << t.out;
}

TEST_F(AnalyzeTool, BadInput) {
  const std::string csv = dir_ + "/small.csv";
  {
    std::ofstream f(csv);
    f << "time_s,accel\n";
    for (int i = 0; i < 200; ++i) f << i * 1e-4 << "," << std::sin(0.3 * i) << "\n";
  }
  // No speed: the fault frequencies are unknown.
  RunResult r = run("analyze --csv '" + csv + "' --bearing '" + bearing_ + "' --column accel");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--inner-rpm"), std::string::npos) << r.err;
  // A column that is not there is named with the available ones.
  r = run("analyze --csv '" + csv + "' --bearing '" + bearing_ + "' --inner-rpm 1800 --column ay_m_s2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("columns: time_s, accel"), std::string::npos) << r.err;
  // A file that is not there.
  r = run("analyze --csv '" + dir_ + "/missing.csv' --bearing '" + bearing_ + "' --inner-rpm 1800");
  EXPECT_EQ(r.exit_code, 2);
  // A malformed number names the line.
  {
    std::ofstream f(csv, std::ios::app);
    f << "0.02,abc\n";
  }
  r = run("analyze --csv '" + csv + "' --bearing '" + bearing_ + "' --inner-rpm 1800 --column accel");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("line 202"), std::string::npos) << r.err;
}

}  // namespace
