// bearing_tool refuses an output its disk cannot hold (src/tools/output_space.hpp), from the
// size it estimates before the run (output_size.hpp). The estimates against the files the
// built tool writes on short runs: a text file lies between the narrowest and the widest its
// number formats print (the estimate is the widest), an NPY file is exact, a bag below its
// estimate by at most the estimate's allowances. The refusal's rule against its closed form, with
// the free space given; the files a rerun replaces, whose space comes back; and a generate
// run no disk could hold, refused for space before anything is written.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <string>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/runtime/scenario_simulation.hpp"
#include "dataset_files.hpp"
#include "output_size.hpp"
#include "output_space.hpp"
#include "tool_common.hpp"
#include "tool_runner.hpp"
#include "tool_test_files.hpp"

using namespace bearing_sim;
using bearing_sim::test::read_text;
using bearing_sim::test::RunResult;
using bearing_sim::test::ToolScratchTest;

namespace {

namespace fs = std::filesystem;

using bearing_sim::test::source_file;

double file_bytes(const std::string& path) { return static_cast<double>(fs::file_size(path)); }

// The InputError's text of check_output_space, "" if it accepts.
std::string refusal(const std::string& what, double needed, const std::string& dir, double available) {
  try {
    tool::check_output_space(what, needed, dir, available);
  } catch (const tool::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(OutputSpace, ByteSizesInDecimalUnits) {
  EXPECT_EQ(tool::byte_size_text(0.0), "0 bytes");
  EXPECT_EQ(tool::byte_size_text(999.0), "999 bytes");
  EXPECT_EQ(tool::byte_size_text(1000.0), "1 kB");
  EXPECT_EQ(tool::byte_size_text(830e3), "830 kB");
  EXPECT_EQ(tool::byte_size_text(12.4e9), "12.4 GB");
  EXPECT_EQ(tool::byte_size_text(76e9), "76 GB");
  EXPECT_EQ(tool::byte_size_text(2.5e15), "2.5 PB");
}

TEST(OutputSpace, AnOutputFitsWithFivePercentAndOneHundredMegabytesToSpare) {
  // Needed 12.4 GB: with 5 % it is 13.02 GB, leaving 100 MB free takes 13.12 GB.
  const double needed = 12.4e9, limit = needed * 1.05 + 100e6;
  EXPECT_EQ(refusal("--csv '/data/a.csv'", needed, "/data", limit), "");
  EXPECT_EQ(refusal("--csv '/data/a.csv'", needed, "/data", 1e15), "");
  const std::string text = refusal("--csv '/data/a.csv'", needed, "/data", limit - 1e3);
  EXPECT_NE(text.find("--csv '/data/a.csv': 12.4 GB needed (estimate), 13.1 GB free on /data"), std::string::npos)
      << text;
  EXPECT_NE(text.find("(the output and 5 % more must leave 100 MB free)"), std::string::npos) << text;
  EXPECT_NE(refusal("--csv '/data/a.csv'", needed, "/data", 3.1e9).find("12.4 GB needed (estimate), 3.1 GB free"),
            std::string::npos);
  // A small file on a disk with less than the 100 MB that every run leaves.
  EXPECT_NE(refusal("--out '/d'", 2e3, "/d", 99e6).find("2 kB needed (estimate), 99 MB free on /d"), std::string::npos);
  EXPECT_EQ(refusal("--out '/d'", 2e3, "/d", 101e6), "");
}

TEST(OutputSpace, FilesOnOneDiskAreAddedUp) {
  // Two outputs, each fitting alone, together more than the free space of their directory.
  const std::string dir = fs::temp_directory_path().string();
  const double available = static_cast<double>(fs::space(dir).available);
  const double each = 0.6 * (available - 100e6) / 1.05;
  ASSERT_GT(each, 0.0) << dir << " has less than 100 MB free";
  EXPECT_NO_THROW(tool::check_output_space({{"--csv 'a'", dir + "/bearing_sim_a.csv", each}}));
  try {
    tool::check_output_space(
        {{"--csv 'a'", dir + "/bearing_sim_a.csv", each}, {"--sensor-csv 'b'", dir + "/bearing_sim_b.csv", each}});
    ADD_FAILURE() << "not refused";
  } catch (const tool::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--csv 'a', --sensor-csv 'b': "), std::string::npos) << e.what();
  }
}

class OutputSize : public ToolScratchTest {};

TEST_F(OutputSize, SimulateCsvBetweenItsNarrowestAndItsEstimate) {
  const std::string csv = dir_ + "/run.csv";
  const double rows = 4000.0;  // 0.2 s at 20 kHz
  const RunResult r = run("simulate --bearing '" + source_file("config/bearings/deep_groove_6205.yaml") +
                          "' --force 2000,0,100 --inner-rpm 1800 --duration 0.2 --rate 20000 --csv '" + csv + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string header = read_text(csv).substr(0, read_text(csv).find('\n') + 1);
  const double estimate = tool::time_series_csv_bytes(rows, 10, static_cast<double>(header.size()));
  // Narrowest: a time of 1 character ("0"), numbers without a sign (16 characters and a comma).
  const double narrowest = static_cast<double>(header.size()) + rows * (1.0 + 10.0 * 17.0 + 1.0);
  const double bytes = file_bytes(csv);
  EXPECT_LE(bytes, estimate);
  EXPECT_GE(bytes, narrowest);
  std::printf("simulate --csv: %.0f bytes, estimate %.0f (%.1f %% above)\n", bytes, estimate,
              100.0 * (estimate / bytes - 1.0));
}

TEST_F(OutputSize, GenerateFilesAgainstTheirEstimates) {
  // The CT gantry (many balls) at 20 kHz with the housing sensor at 10 kHz for 1.05 s: a
  // spall from 0.55 s, two phases.
  const std::string scenario = write(
      "size_test.yaml", "name: size_test\nduration_s: 1.05\nsample_rate_hz: 20000\nseed: 3\nbearing_file: " +
                            source_file("config/bearings/ct_gantry_lyc.yaml") +
                            "\nsensor_file: " + source_file("config/sensors/ct_gantry_housing_accelerometer.yaml") +
                            "\nphases: [{name: settle, start_s: 0}, {name: spalled, start_s: 0.55}]\n"
                            "speed: {initial_speed_rpm: 150}\n"
                            "load: {initial: {force_N: [6800, 0, 0], moment_Nm: [0, 2100]}}\n"
                            "defects:\n  - {at_s: 0.55, surface: outer_race, position_deg: 0, width_mm: 0.3, "
                            "depth_um: 5}\n");
  const RunResult r = run("generate '" + scenario + "' --out '" + dir_ + "/out' --format bag,npy,csv --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const runtime::GenerateSettings settings;  // generate's defaults
  const runtime::ScenarioSimulation simulation(Scenario::load(scenario), scenario, settings);
  const runtime::DatasetInfo& info = simulation.info();
  const BearingConfig bearing = load_bearing_config(simulation.scenario().bearing_file());
  const int balls = bearing.rows * bearing.balls_per_row;
  const double ideal = static_cast<double>(info.ideal_samples), measured = static_cast<double>(info.measured_samples);
  ASSERT_LT(measured, ideal);  // the sensor decimates: both channels' estimates are exercised apart
  const std::string stem = dir_ + "/out/size_test";

  // NPY: header and float32 rows, exact.
  EXPECT_EQ(file_bytes(stem + "_vibration.npy"), tool::npy_float_bytes(measured, 3));
  EXPECT_EQ(file_bytes(stem + "_vibration_ideal.npy"), tool::npy_float_bytes(ideal, 3));

  // CSV: no wider than the estimate; no narrower than 1-character numbers and the time's
  // 1 + 1 + 9 characters (the sample index has at least 1 digit).
  for (const auto& [suffix, rows] : {std::pair<std::string, double>{"_vibration.csv", measured},
                                     std::pair<std::string, double>{"_vibration_ideal.csv", ideal}}) {
    const double bytes = file_bytes(stem + suffix);
    const double estimate = tool::dataset_csv_bytes(rows, info.duration_s);
    const double narrowest = std::strlen("sample,time_s,accel_x,accel_y,accel_z\n") + rows * (1 + 1 + 11 + 3 * 2 + 1);
    EXPECT_LE(bytes, estimate) << suffix;
    EXPECT_GE(bytes, narrowest) << suffix;
    std::printf("generate %s: %.0f bytes, estimate %.0f (%.1f %% above)\n", suffix.c_str(), bytes, estimate,
                100.0 * (estimate / bytes - 1.0));
  }
  // The sidecars: an allowance per label, never below the file.
  const double sidecar = tool::dataset_sidecar_bytes(info, simulation.scenario());
  EXPECT_LE(file_bytes(stem + ".json"), sidecar);
  EXPECT_LE(file_bytes(stem + "_csv.json"), sidecar);

  // The bag: messages at their serialized size with the format's records, and allowances
  // (output_size.hpp), by which the file may come in below the estimate: each health report's
  // texts (~0.4 kB written), each chunk's records, each connection record's field names (7
  // topics, each record twice), and the spall in every label (here from 0.55 s on; a
  // DefectState is under 128 bytes).
  const double bag = file_bytes(stem + ".bag");
  const double bag_estimate = tool::dataset_bag_bytes(info, settings, simulation.scenario(), balls);
  const double reports = std::floor(info.duration_s * settings.health_rate_hz) + 1.0;
  const double labels = std::floor(info.duration_s * info.label_rate_hz) + 1.0;
  const double chunks = std::ceil(bag_estimate / (768.0 * 1024.0));
  const double allowances = reports * tool::kHealthTextBytes + chunks * tool::kBagChunkAllowanceBytes +
                            7 * 2 * tool::kBagConnectionAllowanceBytes + labels * 128.0;
  EXPECT_LE(bag, bag_estimate);
  EXPECT_GE(bag, bag_estimate - allowances);
  std::printf("generate .bag: %.0f bytes, estimate %.0f (%.1f %% above)\n", bag, bag_estimate,
              100.0 * (bag_estimate / bag - 1.0));
  // All of it, as generate checks it.
  const double total = tool::dataset_output_bytes(info, settings, simulation.scenario(), balls, {"bag", "npy", "csv"});
  double written = 0.0;
  for (const auto& f : fs::directory_iterator(dir_ + "/out")) written += file_bytes(f.path().string());
  EXPECT_LE(written, total);
  // The files a second run into the same --out replaces (whose space its check counts as free)
  // are exactly the files this run wrote.
  std::set<std::string> named, found;
  for (const char* format : {"bag", "npy", "csv"})
    for (const std::string& file : tool::dataset_files(stem, format)) named.insert(file);
  for (const auto& f : fs::directory_iterator(dir_ + "/out")) found.insert(f.path().string());
  EXPECT_EQ(named, found);
}

TEST_F(OutputSize, AReplacedFileFreesTheSpaceItTakes) {
  // 1 MiB of random bytes (no filesystem compresses them): its blocks hold at least its size and,
  // with a filesystem's block rounding and preallocation, less than twice it.
  const std::string path = dir_ + "/replaced.bin";
  {
    std::ofstream out(path, std::ios::binary);
    std::mt19937_64 bits(7);
    for (int i = 0; i < (1 << 20) / 8; ++i) {
      const std::uint64_t word = bits();
      out.write(reinterpret_cast<const char*>(&word), sizeof word);
    }
  }
  ASSERT_EQ(fs::file_size(path), 1u << 20);
  const double bytes = tool::allocated_bytes({path});
  EXPECT_GE(bytes, 1 << 20);
  EXPECT_LT(bytes, 2 << 20);
  // A missing file and a directory free nothing; files add up.
  EXPECT_EQ(tool::allocated_bytes({dir_ + "/missing.bin", dir_}), 0.0);
  EXPECT_EQ(tool::allocated_bytes({path, path, dir_ + "/missing.bin"}), 2.0 * bytes);
}

TEST_F(OutputSize, AGenerateRunNoDiskHoldsIsRefusedBeforeAnythingIsWritten) {
  // 1e6 s at 1 MHz with --allow-long-run: 1e12 samples, over 60 TB as a bag alone. --out lies
  // under a regular file: the space is that of the scratch directory, and were the size check
  // missing, generate could not create --out and would stop there (exit 2) with nothing
  // written, so this test cannot fill a disk.
  const std::string scenario =
      write("huge.yaml", "name: huge\nduration_s: 1.0e6\nsample_rate_hz: 1.0e6\nseed: 1\nbearing_file: " +
                             source_file("config/bearings/deep_groove_6205.yaml") +
                             "\nspeed: {initial_speed_rpm: 1800}\nload: {initial: {force_N: [2000, 0, 100]}}\n");
  const std::string out = write("not_a_directory", "") + "/out";
  const runtime::GenerateSettings settings;
  const runtime::ScenarioSimulation simulation(Scenario::load(scenario), scenario, settings);
  const BearingConfig bearing = load_bearing_config(simulation.scenario().bearing_file());
  const double estimate = tool::dataset_output_bytes(simulation.info(), settings, simulation.scenario(),
                                                     bearing.rows * bearing.balls_per_row, {"bag"});
  if (static_cast<double>(fs::space(dir_).available) > estimate)
    GTEST_SKIP() << dir_ << " has more than " << tool::byte_size_text(estimate) << " free";
  const RunResult r = run("generate '" + scenario + "' --out '" + out + "' --format bag --allow-long-run --quiet");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--out '" + out + "': " + tool::byte_size_text(estimate) + " needed (estimate), "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(" free on " + dir_ + " "), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("cannot create"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}
