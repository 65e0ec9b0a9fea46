// bearing_sim_node as fast as possible (real_time false): every sample once, /clock driving
// a use_sim_time consumer, outputs stamped on simulated time. How much faster than wall time
// it runs is the machine's business (bench/, scripts/measure_node.py), not a test's.
#include "bearing_sim/core/quasi_static.hpp"
#include "node_test_support.hpp"

using namespace node_test;

namespace {
constexpr double kRate = 10000.0;
}

TEST(FastMode, EverySampleOnceOnSimulatedTimeAndPublishesClock) {
  Recorder& rec = recorder();
  ASSERT_TRUE(rec.wait_for_sample(0, 60.0)) << "no vibration samples";
  const std::uint64_t index0 = rec.next_index();
  const ros::WallTime t0 = ros::WallTime::now();
  // 3 s of simulated time, however long that takes on this machine.
  ASSERT_TRUE(rec.wait_for_sample(index0 + static_cast<std::uint64_t>(3.0 * kRate), 180.0));
  // How fast depends on the CPU and its load: printed for the record, not asserted.
  const double speed = static_cast<double>(rec.next_index() - index0) / kRate / (ros::WallTime::now() - t0).toSec();
  std::cout << "simulated seconds per wall second: " << speed << std::endl;
  EXPECT_EQ(rec.gaps(), 0u);
  EXPECT_EQ(rec.repeats(), 0u);
  EXPECT_EQ(rec.non_finite(), 0u);

  // This node has use_sim_time: its clock is the simulation's /clock, published after each
  // chunk with the time of the chunk's last sample, so it always reads a chunk end, and it
  // advances while the simulation runs (how far in a wall second depends on the machine).
  // roscpp connects /clock on its own, possibly after the samples' topic: wait for it.
  ASSERT_TRUE(ros::Time::isSimTime());
  const auto chunks = rec.chunks();
  const std::uint64_t chunk = chunks.back().size;
  ASSERT_GT(chunk, 0u);
  ASSERT_TRUE(rec.wait_for([] { return !ros::Time::now().isZero(); }, 60.0)) << "no /clock received";
  const ros::Time clock0 = ros::Time::now();
  const auto samples_at = [](const ros::Time& t) {
    return static_cast<std::uint64_t>(std::llround(t.toSec() * kRate));
  };
  EXPECT_EQ((samples_at(clock0) + 1) % chunk, 0u) << "clock " << clock0 << " is not a chunk end";
  ASSERT_TRUE(rec.wait_for([&] { return ros::Time::now() > clock0; }, 60.0)) << "/clock stopped at " << clock0;
  const ros::Time clock1 = ros::Time::now();
  EXPECT_EQ((samples_at(clock1) + 1) % chunk, 0u) << "clock " << clock1 << " is not a chunk end";
  // Stamps are simulated time itself: sample n at n / rate.
  EXPECT_NEAR(chunks.back().stamp.toSec(), static_cast<double>(chunks.back().first_sample) / kRate, 1e-6);

  // Lower-rate outputs follow simulated time: vibration_level every 0.1 s of it. roscpp
  // connects each topic on its own schedule, and in fast mode seconds of simulated time can
  // pass before the levels' connection is up: wait for 21 of them.
  ASSERT_TRUE(rec.wait_for_levels(21, 60.0)) << "only " << rec.levels().size() << " vibration levels";
  const auto levels = rec.levels();
  for (std::size_t i = levels.size() - 20; i < levels.size(); ++i)
    EXPECT_NEAR((levels[i].header.stamp - levels[i - 1].header.stamp).toSec(), 0.1, 1e-6);

  // Same physics as in real time: the mean displacement at the static solution (0.5 %,
  // as in test_node_steady_state).
  const bearing_sim::StaticSolution s = bearing_sim::solve_static(ct_model(), ct_load());
  const std::uint64_t end = rec.next_index();
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(rec.mean_displacement(c, end - 10000, end), s.displacement[c], 0.005 * s.displacement.head<3>().norm());
}

NODE_TEST_MAIN("test_node_fast_mode")
