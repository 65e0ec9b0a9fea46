// bearing_sim_node in real time (ct_gantry.launch): the real-time contract as behaviour,
// not speed. Every sample exactly once, in order, finite; every chunk stamped with its first
// sample's time on one time base; no chunk published before its time, so the stream never
// runs ahead of the wall clock. How far behind a chunk arrives depends on the machine and
// its load: lag, overruns and CPU are printed for the record but not asserted (they belong to
// scripts/soak_node.py and docs/performance.md).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "node_pid.hpp"
#include "node_test_support.hpp"

using namespace node_test;

namespace {
constexpr double kRate = 10000.0;
constexpr double kRunS = 20.0;
// A chunk stamp is the start stamp plus first_sample / rate: ros::Time keeps nanoseconds,
// so 1 us covers its rounding over any run length.
constexpr double kStampToleranceS = 1e-6;
// Stamps are on the ROS wall clock and arrival is read from the same clock: "no earlier
// than its time" holds to the clock's resolution; 1 ms covers the stamp rounding and the
// system clock's own slewing during the run.
constexpr double kClockToleranceS = 0.001;

// utime + stime of a process, s; NaN when its /proc entry cannot be read (the process gone:
// the figure is printed for the record, not asserted).
double cpu_seconds(int pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  std::getline(f, line);
  const std::size_t comm_end = line.rfind(')');
  if (comm_end == std::string::npos || comm_end + 2 > line.size()) return std::nan("");
  std::istringstream rest(line.substr(comm_end + 2));  // after "pid (comm) "
  std::string field;
  double utime = 0, stime = 0;
  for (int i = 3; i <= 15 && rest >> field; ++i) {
    if (i == 14) utime = std::stod(field);
    if (i == 15) stime = std::stod(field);
  }
  return (utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}
}  // namespace

TEST(RealTime, EverySampleOnceAndOnTheWallClock) {
  Recorder& rec = recorder();
  ASSERT_TRUE(rec.wait_for_sample(0, 60.0)) << "no vibration samples";
  // As a nodelet the simulation runs in the manager (its node name is the loader's process).
  const int manager_pid = node_pid("/bearing/bearing_nodelet_manager");
  const int pid = manager_pid > 0 ? manager_pid : node_pid("/bearing/bearing_sim_node");
  const std::uint64_t index0 = rec.next_index();
  const ros::WallTime t0 = ros::WallTime::now();
  const double cpu0 = pid > 0 ? cpu_seconds(pid) : 0.0;
  ros::WallDuration(kRunS).sleep();
  const std::uint64_t index1 = rec.next_index();
  const double wall_s = (ros::WallTime::now() - t0).toSec();
  const double cpu_s = pid > 0 ? cpu_seconds(pid) - cpu0 : 0.0;

  // Every sample exactly once, in order.
  EXPECT_EQ(rec.gaps(), 0u);
  EXPECT_EQ(rec.repeats(), 0u);
  EXPECT_EQ(rec.non_finite(), 0u);
  // The stream made progress, and never ran ahead of the wall clock: a node computing as
  // fast as it can would deliver several times more than the elapsed time allows (the
  // bound adds one second for the lead, a chunk and the clock's resolution).
  EXPECT_GT(index1, index0);
  EXPECT_LE(static_cast<double>(index1 - index0), (wall_s + 1.0) * kRate);

  // Each chunk stamped on one time base (stamp = start + first_sample / rate) and published
  // no earlier than its last sample's time.
  const auto chunks = rec.chunks();
  ASSERT_GT(chunks.size(), 10u);
  const ChunkArrival& first = chunks.front();
  std::size_t early = 0, misstamped = 0;
  double worst_early_s = 0.0;
  for (const auto& c : chunks) {
    const double expected_offset_s = static_cast<double>(c.first_sample - first.first_sample) / kRate;
    if (std::abs((c.stamp - first.stamp).toSec() - expected_offset_s) > kStampToleranceS) ++misstamped;
    const double delay_s = c.received.toSec() - c.stamp.toSec() - static_cast<double>(c.size - 1) / kRate;
    if (delay_s < -kClockToleranceS) ++early, worst_early_s = std::min(worst_early_s, delay_s);
  }
  EXPECT_EQ(misstamped, 0u) << "chunk stamps not start + first_sample / rate";
  EXPECT_EQ(early, 0u) << "chunks published before their time, worst " << worst_early_s * 1e3 << " ms early";

  // The node's own account is there and says how it is scheduled (figures for the record).
  ASSERT_TRUE(rec.wait_for_new_diagnostics(1, 30.0));
  diagnostic_msgs::DiagnosticStatus rt;
  ASSERT_TRUE(rec.diagnostic("Real time", &rt));
  EXPECT_FALSE(Recorder::value(rt, "overruns").empty());
  std::cout << "node lag p50/p99/max (ms): " << Recorder::value(rt, "lag p50 (ms)") << " / "
            << Recorder::value(rt, "lag p99 (ms)") << " / " << Recorder::value(rt, "lag max (ms)") << ", overruns "
            << Recorder::value(rt, "overruns") << "; CPU of "
            << (manager_pid > 0 ? "the nodelet manager" : "bearing_sim_node") << ": " << 100.0 * cpu_s / wall_s
            << " % of one core" << std::endl;
}

NODE_TEST_MAIN("test_node_realtime")
