// The public datasets' scenarios (config/scenarios) run at the operating conditions the
// datasets publish: speed of the shaft, radial load and sample rate.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::test;

namespace {

struct Condition {
  std::string file;
  double rpm;
  double radial_load_N;   // along x
  double sample_rate_hz;  // of the record: the sensor's output rate where a sensor file is given
};

constexpr double kNewtonsPerPoundForce = 4.4482216152605;

// CWRU Bearing Data Center (0-3 hp: 1797, 1772, 1750, 1730 rpm; 12 kHz records; no radial
// load published: the scenarios' assumed 49 N rotor weight). IMS: 2000 rpm, 6000 lbf,
// 20 kHz (Qiu et al. 2006). XJTU-SY condition 1: 2100 rpm, 12 kN, 25.6 kHz. PRONOSTIA
// condition 1: 1800 rpm, 4000 N, 25.6 kHz (Nectoux et al. 2012). Paderborn N15_M07_F10:
// 1500 rpm, 1000 N, 64 kHz (Lessmeier et al. 2016).
const std::vector<Condition> kConditions = {
    {"cwru_drive_end_0hp.yaml", 1797.0, 49.0, 12000.0},
    {"cwru_drive_end_1hp.yaml", 1772.0, 49.0, 12000.0},
    {"cwru_drive_end_2hp.yaml", 1750.0, 49.0, 12000.0},
    {"cwru_drive_end_3hp.yaml", 1730.0, 49.0, 12000.0},
    {"cwru_fan_end_0hp.yaml", 1797.0, 49.0, 12000.0},
    {"ims_run_to_failure.yaml", 2000.0, 6000.0 * kNewtonsPerPoundForce, 20000.0},
    {"xjtu_sy_condition1_run_to_failure.yaml", 2100.0, 12000.0, 25600.0},
    {"pronostia_condition1_run_to_failure.yaml", 1800.0, 4000.0, 25600.0},
    {"paderborn_n15_m07_f10.yaml", 1500.0, 1000.0, 64000.0},
};

}  // namespace

TEST(DatasetConditions, ScenariosHoldTheDatasetsSpeedLoadAndRate) {
  for (const Condition& c : kConditions) {
    SCOPED_TRACE(c.file);
    const Scenario sc = Scenario::load(config_path("scenarios/" + c.file));
    const double w = c.rpm * 2.0 * test::kPi / 60.0;
    for (double t : {0.0, 0.5 * sc.duration_s(), sc.duration_s()}) {
      const ScenarioInputs in = sc.inputs_at(t);
      EXPECT_NEAR(in.ring_speed_rad_s, w, 1e-12 * w);
      // The file gives the load in whole newtons (6000 lbf = 26689.3 N written 26689 N).
      EXPECT_NEAR(in.load[0], c.radial_load_N, 0.5);
      EXPECT_EQ(in.load.tail<4>().norm(), 0.0);
    }
    // Recorded at the dataset's rate; dynamics run faster (impacts must not alias) decimate to
    // it through the sensor's anti-alias filter, by a whole factor.
    if (sc.sensor_file().empty()) {
      EXPECT_EQ(sc.sample_rate_hz(), c.sample_rate_hz);
    } else {
      EXPECT_EQ(load_accelerometer_config(sc.sensor_file()).output_rate_hz, c.sample_rate_hz);
      const double factor = sc.sample_rate_hz() / c.sample_rate_hz;
      EXPECT_GE(factor, 1.0);
      EXPECT_EQ(factor, std::round(factor));
    }
  }
}
