// bearing_tool driven as a careless user would: files that are no files, keys written twice,
// option values CLI parsing mangles, CSV time going backwards, bearing values that stall the
// integrator and runs of years. Every one exits 2 naming the argument or the file, before any
// work starts, and prints no result.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bearing_sim/core/constants.hpp"
#include "tool_runner.hpp"
#include "tool_test_files.hpp"

namespace {

using bearing_sim::kPi;
using bearing_sim::test::contains;
using bearing_sim::test::kConfigDir;
using bearing_sim::test::kCtBearingYaml;
using bearing_sim::test::kCtScanYaml;

using bearing_sim::test::read_text;
using bearing_sim::test::RunResult;



class ToolInputTest : public bearing_sim::test::ToolScratchTest {
 protected:
  // The CT bearing file with one line replaced (the key must be in it).
  std::string ct_with(const std::string& key, const std::string& value) {
    const std::string text =
        std::regex_replace(read_text(kCtBearingYaml), std::regex("(^|\n)( *)" + key + ":[^\n]*"), "$1$2" + key + ": " + value);
    EXPECT_NE(text, read_text(kCtBearingYaml)) << key;
    return write("ct_" + key + ".yaml", text);
  }

  // Exit 2, each word in stderr, nothing on stdout.
  void expect_refused(const std::string& args, const std::vector<std::string>& words) {
    SCOPED_TRACE(args);
    const RunResult r = run(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    for (const auto& w : words) EXPECT_TRUE(contains(r.err, w)) << "'" << w << "' not in: " << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
};

TEST_F(ToolInputTest, FilesThatAreNoRegularFilesAreRefusedNamingThem) {
  // /dev/zero used to be read until memory ran out; a directory gave "empty file" or
  // "basic_filebuf::underflow" with exit 1.
  for (const std::string& path :
       {std::string("/dev/zero"), std::string("/dev/urandom"), dir_, dir_ + "/missing.yaml"}) {
    expect_refused("static --bearing '" + path + "'", {path});
    expect_refused("frequencies --bearing '" + path + "' --outer-rpm 10", {path});
    expect_refused("sweep --definition '" + path + "' --csv '" + dir_ + "/out.csv'", {path});
    expect_refused("generate '" + path + "' --out '" + dir_ + "/out' --quiet", {path});
    expect_refused("analyze --csv '" + path + "' --bearing '" + kCtBearingYaml + "' --outer-rpm 180", {"--csv", path});
  }
}

TEST_F(ToolInputTest, AKeyWrittenTwiceIsRefusedNamingFileKeyAndLines) {
  std::string text = read_text(kCtBearingYaml);
  text.insert(0, "balls_per_row: 10\n");  // a stale line above the real one (now line 2 + its old number)
  const std::string path = write("twice.yaml", text);
  const RunResult r = run("static --bearing '" + path + "' --force 6800,0,0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, path)) << r.err;
  EXPECT_TRUE(contains(r.err, "'balls_per_row'")) << r.err;
  EXPECT_TRUE(std::regex_search(r.err, std::regex("lines 1 and [0-9]+"))) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST_F(ToolInputTest, EmptyVectorFieldsNameTheOptionNotTheNextArgument) {
  const std::string b = " --bearing '" + kCtBearingYaml + "'";
  for (const std::string value : {",,", ",", "1,,3", "''"}) {
    SCOPED_TRACE(value);
    const RunResult r = run("static" + b + " --force " + value + " --json");
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_TRUE(contains(r.err, "--force")) << r.err;
    EXPECT_FALSE(contains(r.err, "'--json'")) << r.err;
    EXPECT_TRUE(r.out.empty());
  }
  // A number too small for a double is a number (0 here), not an error of the parser (exit 1).
  EXPECT_EQ(run("static" + b + " --force 6800,1e-400,0 --json").exit_code, 0);
  // Out of range: the option, the value and the rule, not 300 digits of the largest double.
  expect_refused("simulate" + b + " --outer-rpm 180 --duration 0", {"--duration", "'0' must be > 0"});
  // The comma-separated form still works: 6800 N radial on the CT bearing is carried.
  EXPECT_EQ(run("static" + b + " --force 6800,0,0 --moment 0,2100 --json").exit_code, 0);
}

TEST_F(ToolInputTest, ACsvWhoseTimeGoesBackwardsIsRefusedNamingTheLine) {
  std::string csv = "time_s,ax_m_s2\n";
  for (int i = 0; i < 100; ++i) csv += std::to_string(i * 1e-4) + "," + std::to_string(i % 7) + "\n";
  csv += "0.005,1\n";  // line 102: back in time
  const std::string path = write("backwards.csv", csv);
  expect_refused("analyze --csv '" + path + "' --bearing '" + kCtBearingYaml + "' --outer-rpm 180",
                 {path, "line 102", "time_s", "does not increase"});
}

// 20 kHz of a 50 Hz sine with its times written as `decimals` fixed decimals; the samples of
// [hole_from_s, hole_to_s) left out.
std::string sine_csv(double seconds, int decimals, double hole_from_s = 0.0, double hole_to_s = 0.0,
                     double rate_hz = 20000.0) {
  std::string csv = "time_s,ax_m_s2\n";
  char row[96];
  for (long i = 0; i < std::lround(seconds * rate_hz); ++i) {
    const double t = i / rate_hz;
    if (t >= hole_from_s && t < hole_to_s) continue;
    std::snprintf(row, sizeof row, "%.*f,%.6f\n", decimals, t, std::sin(2.0 * 3.141592653589793 * 50.0 * t));
    csv += row;
  }
  return csv;
}

TEST_F(ToolInputTest, ACsvWithAHoleInItsTimeIsRefusedNamingTheLineAndTheGap) {
  // 2 s at 20 kHz with 0.5 s missing from t = 1 s: the rate came out as 29999/2 = 14999.5 Hz.
  const std::string holed = write("hole.csv", sine_csv(2.0, 9, 1.0, 1.5));
  const std::string analyze = " --bearing '" + kCtBearingYaml + "' --outer-rpm 180";
  // Line 20002 holds t = 1.5 s (line 1 is the header, line 20001 the sample at 0.99995 s).
  expect_refused("analyze --csv '" + holed + "'" + analyze,
                 {holed, "line 20002", "time_s", "0.50005 s after the previous sample (line 20001)",
                  "median step is 5e-05 s (20000 Hz)", "within 25 %", "--rate"});
  // --rate: the samples are taken as consecutive at that rate and the time column is not read.
  RunResult r = run("analyze --csv '" + holed + "'" + analyze + " --rate 20000 --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "\"sample_rate_hz\": 20000")) << r.out;
  // Uniform steps pass, also with times printed to a microsecond at 200 kHz (5 us +- 1 us).
  EXPECT_EQ(run("analyze --csv '" + write("whole.csv", sine_csv(2.0, 9)) + "'" + analyze).exit_code, 0);
  const RunResult coarse =
      run("analyze --csv '" + write("coarse.csv", sine_csv(0.1, 6, 0.0, 0.0, 200000.0)) + "'" + analyze + " --json");
  EXPECT_EQ(coarse.exit_code, 0) << coarse.err;
  // One sample missing is a step of twice the others: refused.
  expect_refused("analyze --csv '" + write("one.csv", sine_csv(0.1, 9, 0.05, 0.05004)) + "'" + analyze,
                 {"line 1002", "0.0001 s after the previous sample"});
}

TEST_F(ToolInputTest, ACsvWithAColumnNamedTwiceIsRefusedNamingIt) {
  std::string csv = "time_s,ax_m_s2,ay_m_s2,ax_m_s2\n";
  for (int i = 0; i < 1000; ++i) csv += std::to_string(i * 1e-4) + ",1,2," + std::to_string(i % 7) + "\n";
  const std::string path = write("twice.csv", csv);
  // The last 'ax_m_s2' silently won; now refused, whichever column is asked for.
  for (const std::string column : {"ax_m_s2", "ay_m_s2"})
    expect_refused("analyze --csv '" + path + "' --bearing '" + kCtBearingYaml + "' --outer-rpm 180 --column " + column,
                   {path, "column 'ax_m_s2' appears twice", "columns 2 and 4"});
}

TEST_F(ToolInputTest, AnalysisThresholdsOutsideTheirRangesAreRefused) {
  const std::string csv = write("ok.csv", sine_csv(0.5, 9));
  const std::string analyze = "analyze --csv '" + csv + "' --bearing '" + kCtBearingYaml + "' --outer-rpm 180";
  expect_refused(analyze + " --snr-db -1e300", {"--snr-db -1e+300", "from 0 to 60 dB"});
  expect_refused(analyze + " --snr-db 61", {"--snr-db 61", "from 0 to 60 dB"});
  expect_refused(analyze + " --kurtosis-warn -5", {"--kurtosis-warn -5", "0 (off) or from 3", "1000"});
  expect_refused(analyze + " --kurtosis-warn 2", {"--kurtosis-warn 2", "0 (off) or from 3"});
  // The ends of the ranges and the switch-off are accepted.
  for (const std::string good : {" --snr-db 0", " --snr-db 60", " --kurtosis-warn 0", " --kurtosis-warn 3"})
    EXPECT_EQ(run(analyze + good).exit_code, 0) << good;
}

TEST_F(ToolInputTest, ABearingValueThatStallsTheIntegratorIsRefusedNamingTheKeyAndTheMode) {
  // A tilt inertia a million times too small: the tilt mode rises a thousandfold, far above any
  // bearing's (the run would need tens of thousands of steps per sample).
  expect_refused("simulate --bearing '" + ct_with("tilt_inertia_kg_m2", "7.9e-06") +
                     "' --force 6800,0,0 --moment 0,2100 --outer-rpm 180 --duration 0.01",
                 {"tilt mode at", "MHz", "tilt_inertia_kg_m2", "implausibly small", "ct_tilt_inertia_kg_m2.yaml"});
  // Contact damping of 1e10 N*s/m: overdamped contacts, c/m ~ 1e11 1/s.
  expect_refused("simulate --bearing '" + ct_with("contact_damping_Ns_per_m", "1e10") +
                     "' --force 6800,0,0 --moment 0,2100 --outer-rpm 180 --duration 0.01",
                 {"overdamped", "contact_damping_Ns_per_m", "implausibly large"});
  // A dynamic sweep over such a bearing: refused before any case runs, naming the case.
  const std::string sweep =
      write("stall_sweep.yaml", "name: stall\nbearing: " + ct_with("contact_damping_Ns_per_m", "1e10") +
                                    "\noperating_point: {force_N: [6800, 0, 0], speed_rpm: 180, "
                                    "duration_s: 0.01}\nparameter: clearance_um\nvalues: [0, 1]\n");
  expect_refused("sweep --definition '" + sweep + "' --csv '" + dir_ + "/stall.csv' --quiet",
                 {sweep, "case 1 (clearance_um = 0", "overdamped", "contact_damping_Ns_per_m"});
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/stall.csv")) << "nothing may be written for a refused sweep";
  // The shipped file runs.
  EXPECT_EQ(run("simulate --bearing '" + kCtBearingYaml + "' --force 6800,0,0 --moment 0,2100 --outer-rpm 180 --duration 0.01")
                .exit_code,
            0);
}

TEST_F(ToolInputTest, RunsOfYearsNeedTheConfirmationFlagAndNothingStarts) {
  // 1e9 samples of the CT bearing (414 balls) at 10 kHz with 200 integration steps each: weeks
  // here (about 1 ms per sample), and still days on a machine 50 times faster.
  expect_refused("simulate --bearing '" + kCtBearingYaml + "' --force 6800,0,0 --outer-rpm 180 --duration 1e5 --substeps 200",
                 {"simulate", "--allow-long-run", "measured on this machine"});
  // 1e11 samples (the longest duration a scenario may have): years at any speed.
  const std::string out = dir_ + "/never";
  expect_refused("generate '" + kCtScanYaml + "' --out '" + out + "' --duration-s 1e7 --quiet",
                 {"generate", "--allow-long-run"});
  EXPECT_FALSE(std::filesystem::exists(out)) << "nothing may be written for a refused run";
  // The flexible ring: 1e9 samples of 1000 steps each, about 70 days here (AMD EPYC, AVX-512),
  // so still far above the hour on a machine 50 times faster. (At its automatic few steps per
  // sample the same run is an hour here and under it on a faster machine, which then started
  // the run.) Its probe runs on a copy before the CSV opens.
  const std::string flexible = kConfigDir + "/bearings/ct_gantry_flexible.yaml";
  const std::string csv = dir_ + "/flexible.csv";
  expect_refused("simulate --bearing '" + flexible + "' --force 6800,0,0 --moment 0,2100 --outer-rpm 180" +
                     " --duration 1e5 --substeps 1000 --csv '" + csv + "'",
                 {"simulate", "--allow-long-run", "measured on this machine"});
  EXPECT_FALSE(std::filesystem::exists(csv)) << "nothing may be written for a refused run";
}

TEST_F(ToolInputTest, ARateSampleCountOrStepCountBeyondAnyRunIsRefusedNamingTheOptions) {
  const std::string sim = "simulate --bearing '" + kCtBearingYaml + "' --force 6800,0,0 --outer-rpm 180";
  // 1 GHz: a second of run is 1e9 samples (the node and a scenario stop at 1 MHz too).
  expect_refused(sim + " --rate 1e9", {"--rate", "1e9", "1000000"});
  // 1e10 samples at the default 10 kHz: beyond the 1e9 a run holds.
  expect_refused(sim + " --duration 1e6", {"--duration", "--rate", "1e+10 samples", "at most 1e9"});
  expect_refused(sim + " --duration 1e-4", {"--duration", "--rate", "at least 4"});
  // 1e9 steps per sample, even of a short run (the node stops at 1000 too).
  expect_refused(sim + " --duration 0.01 --substeps 1000000000", {"--substeps", "1000"});
}

TEST_F(ToolInputTest, ASpeedNoBearingReachesIsRefusedNamingItAndTheLimit) {
  // 1e300 rpm and a sweep to 1e12 rpm ran and printed numbers; the CT bearing's pitch circle
  // (1111 mm) at 500 m/s is 900 rad/s, 8595 rpm.
  const std::string b = " --bearing '" + kCtBearingYaml + "'";
  expect_refused("simulate" + b + " --force 6800,0,0 --outer-rpm 1e300 --duration 0.01",
                 {"ring speed", "(1e+300 rpm) is beyond +-900.1 rad/s (8595 rpm)", "500 m/s"});
  expect_refused("frequencies" + b + " --outer-rpm -1e12", {"outer ring speed", "(-1e+12 rpm)"});
  const std::string sweep = write("fast_sweep.yaml", "name: fast\nbearing: " + kCtBearingYaml +
                                                         "\noperating_point: {force_N: [6800, 0, 0], duration_s: 0.01}"
                                                         "\nparameter: speed_rpm\nvalues: [180, 1e12]\n");
  expect_refused("sweep --definition '" + sweep + "' --csv '" + dir_ + "/fast.csv' --quiet",
                 {"speed_rpm 1e+12", "8595 rpm"});
  EXPECT_EQ(run("frequencies" + b + " --outer-rpm 8500").exit_code, 0);
}

TEST_F(ToolInputTest, ABodyOrBearingPlaceBeyondAnyMachineIsRefusedNamingWhatWasGiven) {
  // A body of 5e-324 kg made every K/m overflow; 1e-300 kg was refused naming a mass of
  // 5e-324 kg never given, and so were bearings 1e300 mm from the centre of mass.
  const std::string modes = "modes --bearing '" + kCtBearingYaml + "' --force 6800,0,0";
  expect_refused(modes + " --mass-kg 1e-300 --inertia-kg-m2 1,1,1", {"--mass-kg 1e-300", "from 0.001 to 1e+07 kg"});
  expect_refused(modes + " --mass-kg 5e-324 --inertia-kg-m2 1,1,1", {"--mass-kg 4.94066e-324", "0.001"});
  expect_refused(modes + " --mass-kg 1e9 --inertia-kg-m2 1,1,1", {"--mass-kg 1e+09", "1e+07 kg"});
  expect_refused(modes + " --mass-kg 100 --inertia-kg-m2 1,1e-300,1", {"--inertia-kg-m2 1e-300", "1e-09"});
  expect_refused(modes + " --mass-kg 100 --inertia-kg-m2 1,1,1 --bearing-positions-mm 1e300,-1e300",
                 {"--bearing-positions-mm 1e+300", "+-100000 mm"});
  EXPECT_FALSE(contains(run(modes + " --mass-kg 100 --inertia-kg-m2 1,1,1 --bearing-positions-mm 1e300").err, "kg"));
  // The limits themselves are machines.
  EXPECT_EQ(
      run(modes + " --mass-kg 0.001 --inertia-kg-m2 1e-9,1e-9,1e-9 --bearing-positions-mm -100000,100000").exit_code,
      0);
}

}  // namespace
