// ROS-free units of bearing_sim_node: pacer, chunk assembler, input validation, the
// divergence-safe sample source, the sample-rate divider and the timing statistics.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <optional>
#include <regex>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/runtime/chunk_assembler.hpp"
#include "bearing_sim/runtime/input_validator.hpp"
#include "bearing_sim/runtime/realtime_pacer.hpp"
#include "bearing_sim/runtime/sample_divider.hpp"
#include "bearing_sim/runtime/sample_pipeline.hpp"
#include "bearing_sim/runtime/sample_source.hpp"
#include "bearing_sim/runtime/timing_stats.hpp"

#include "test_support.hpp"

using namespace bearing_sim;
using namespace bearing_sim::runtime;

namespace {

using bearing_sim::test::ct_load;  // the CT gantry's load (test_support)

DynamicSample sample_with(double v) {
  DynamicSample s;
  s.acceleration.setConstant(v);
  s.displacement.setConstant(v);
  return s;
}
}  // namespace

TEST(RealtimePacer, DeadlinesAreAbsoluteFromTheSampleIndex) {
  const auto start = RealtimePacer::Clock::time_point(std::chrono::seconds(1000));
  const RealtimePacer pacer(10000.0, start);
  // 600,000 samples at 10 kHz are exactly 60 s after the start: no accumulated rounding.
  EXPECT_EQ(pacer.due_time(600000) - start, std::chrono::seconds(60));
  EXPECT_EQ(pacer.due_time(1) - start, std::chrono::microseconds(100));
  EXPECT_NEAR(pacer.lateness_s(100, start + std::chrono::milliseconds(12)), 0.002, 1e-12);
  // A non-integer period (3 kHz) still lands on the exact ns after many samples.
  const RealtimePacer odd(3000.0, start);
  EXPECT_EQ(odd.due_time(3000 * 3600) - start, std::chrono::hours(1));
}

TEST(RealtimePacer, SleepsUntilTheDeadlineAndStopsOnRequest) {
  const auto start = RealtimePacer::Clock::now();
  const RealtimePacer pacer(1000.0, start);
  std::atomic<bool> stop{false};
  ASSERT_TRUE(pacer.sleep_until_due(30, stop));  // 30 ms
  const double woke_after_s = std::chrono::duration<double>(RealtimePacer::Clock::now() - start).count();
  // Never early. How late is the scheduler's business: only "it woke at all" is bounded
  // (10 s, a generous time-out far beyond any scheduling delay).
  EXPECT_GE(woke_after_s, 0.030);
  EXPECT_LT(woke_after_s, 10.0);
  stop = true;
  const auto t0 = RealtimePacer::Clock::now();
  EXPECT_FALSE(pacer.sleep_until_due(100000, stop));  // 100 s away: returns because of stop, not the deadline
  EXPECT_LT(std::chrono::duration<double>(RealtimePacer::Clock::now() - t0).count(), 10.0);
}

namespace {
// The node's two threads on a simulated clock: the simulation thread computes when
// may_compute() (each chunk costing `cost`; chunk `stall_chunk` costs `stall` more, a
// scheduling delay), the publisher publishes the oldest chunk at max(its due time, when it
// was computed). Events are processed in time order.
struct LeadRun {
  std::vector<std::uint64_t> published;  // last sample index of each published chunk, in order
  std::vector<double> publish_late_s;    // publish time - due time
  std::vector<double> compute_ahead_s;   // due time - compute start
  std::size_t max_queue = 0;
};
LeadRun run_lead(std::chrono::milliseconds lead, std::size_t chunk, std::size_t chunks, std::size_t stall_chunk,
                 RealtimePacer::Clock::duration stall) {
  using C = RealtimePacer::Clock;
  const C::time_point start(std::chrono::seconds(100));
  const RealtimePacer pacer(10000.0, start);
  const LeadScheduler s(pacer, lead);
  const C::duration cost = std::chrono::milliseconds(4);  // 40 % of a 10 ms chunk
  LeadRun r;
  std::deque<std::pair<std::uint64_t, C::time_point>> queue;  // last index, ready at
  std::uint64_t next_first = 0;
  std::size_t computed = 0;
  C::time_point sim_free = start;  // the simulation thread is busy until then
  C::time_point now = start;
  while (r.published.size() < chunks) {
    const std::uint64_t next_last = next_first + chunk - 1;
    // Publisher first: the oldest chunk, once it is ready and due.
    if (!queue.empty() && now >= queue.front().second && now >= s.publish_time(queue.front().first)) {
      r.published.push_back(queue.front().first);
      r.publish_late_s.push_back(std::chrono::duration<double>(now - s.publish_time(queue.front().first)).count());
      queue.pop_front();
      continue;
    }
    if (now >= sim_free && s.may_compute(now, queue.size(), next_last, chunk)) {
      r.compute_ahead_s.push_back(std::chrono::duration<double>(s.publish_time(next_last) - now).count());
      sim_free = now + cost + (computed == stall_chunk ? stall : C::duration::zero());
      queue.emplace_back(next_last, sim_free);
      ++computed;
      next_first += chunk;
      r.max_queue = std::max(r.max_queue, queue.size());
      continue;
    }
    // Next event: the head ready and due, the simulation thread free, or its compute start.
    C::time_point wake = C::time_point::max();
    if (!queue.empty()) wake = std::max(queue.front().second, s.publish_time(queue.front().first));
    wake = std::min(wake, std::max(sim_free, s.compute_start(next_last)));
    EXPECT_GT(wake, now);
    now = wake;
  }
  return r;
}
}  // namespace

TEST(LeadScheduler, ComputesAheadByTheLeadAndPublishesAtTheDueTime) {
  using C = RealtimePacer::Clock;
  const RealtimePacer pacer(10000.0, C::time_point(std::chrono::seconds(100)));
  const LeadScheduler s(pacer, std::chrono::milliseconds(30));
  // Chunk with last sample 99 (due 10 ms) may start at -20 ms, is published at 10 ms.
  EXPECT_EQ(s.publish_time(99), pacer.due_time(99));
  EXPECT_EQ(pacer.due_time(99) - s.compute_start(99), std::chrono::milliseconds(30));
  EXPECT_EQ(s.max_queued(100), 4u);  // 30 ms of 10 ms chunks + the one being published
  EXPECT_EQ(s.max_queued(1000), 1u);
  EXPECT_FALSE(s.may_compute(pacer.due_time(99) - std::chrono::milliseconds(31), 0, 99, 100));
  EXPECT_TRUE(s.may_compute(pacer.due_time(99) - std::chrono::milliseconds(30), 0, 99, 100));
  EXPECT_FALSE(s.may_compute(pacer.due_time(99), 4, 99, 100));  // queue full: wait for the publisher
  EXPECT_EQ(LeadScheduler(pacer, std::chrono::milliseconds(0)).max_queued(100), 1u);
  EXPECT_THROW(LeadScheduler(pacer, std::chrono::milliseconds(-1)), std::invalid_argument);

  const LeadRun r = run_lead(std::chrono::milliseconds(30), 100, 50, 1000, {});
  ASSERT_EQ(r.published.size(), 50u);
  for (std::size_t k = 0; k < r.published.size(); ++k) {
    EXPECT_EQ(r.published[k], 100 * k + 99);     // every chunk once, in order
    EXPECT_DOUBLE_EQ(r.publish_late_s[k], 0.0);  // never early, and on time
  }
  for (double ahead : r.compute_ahead_s) EXPECT_LE(ahead, 0.030 + 1e-12);  // never more than the lead ahead
  EXPECT_LE(r.max_queue, 4u);
}

TEST(LeadScheduler, ADelayShorterThanTheLeadIsNoLatenessALongerOneIsCaughtUp) {
  // The simulation thread held 20 ms (plus 4 ms of computing) with a 30 ms lead: on time.
  const LeadRun hidden = run_lead(std::chrono::milliseconds(30), 100, 40, 10, std::chrono::milliseconds(20));
  for (double late : hidden.publish_late_s) EXPECT_DOUBLE_EQ(late, 0.0);
  // Just in time (lead 0), every chunk is late by its computing time and the same delay
  // is an overrun.
  const LeadRun jit = run_lead(std::chrono::milliseconds(0), 100, 40, 10, std::chrono::milliseconds(20));
  for (double ahead : jit.compute_ahead_s) EXPECT_LE(ahead, 0.0);  // never before its last sample is due
  EXPECT_EQ(jit.max_queue, 1u);
  EXPECT_GT(*std::max_element(jit.publish_late_s.begin(), jit.publish_late_s.end()), 0.010);
  // Held 200 ms: late chunks are published as soon as computed, each once and in order,
  // and the node is back on time afterwards.
  const LeadRun late = run_lead(std::chrono::milliseconds(30), 100, 60, 10, std::chrono::milliseconds(200));
  ASSERT_EQ(late.published.size(), 60u);
  for (std::size_t k = 0; k < late.published.size(); ++k) EXPECT_EQ(late.published[k], 100 * k + 99);
  EXPECT_GT(*std::max_element(late.publish_late_s.begin(), late.publish_late_s.end()), 0.010);  // an overrun
  EXPECT_DOUBLE_EQ(late.publish_late_s.back(), 0.0);
  EXPECT_LE(late.max_queue, 4u);
}

TEST(ChunkAssembler, ChunksAreContiguousAndSizeChangesApplyToTheNextChunk) {
  ChunkAssembler a(3);
  EXPECT_FALSE(a.add(0, sample_with(0)));
  EXPECT_FALSE(a.add(1, sample_with(1)));
  a.set_chunk_samples(2);  // the chunk being filled keeps its size 3
  EXPECT_TRUE(a.add(2, sample_with(2)));
  SampleChunk c = a.take();
  EXPECT_EQ(c.first_sample, 0u);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_FLOAT_EQ(c.accel_x[2], 2.0f);
  EXPECT_FLOAT_EQ(c.displacement_z[1], 1.0f);
  EXPECT_FALSE(a.add(3, sample_with(3)));
  EXPECT_TRUE(a.add(4, sample_with(4)));
  c = a.take();
  EXPECT_EQ(c.first_sample, 3u);
  EXPECT_EQ(c.size(), 2u);
  // A gap or a repeat is refused, so a published chunk can never hide one.
  EXPECT_THROW(a.add(6, sample_with(6)), std::logic_error);
  EXPECT_THROW(a.add(4, sample_with(4)), std::logic_error);
  EXPECT_EQ(a.next_sample(), 5u);
}

TEST(InputValidator, RejectsNonFiniteAndOutOfLimitInputs) {
  InputLimits limits;
  limits.max_force_N = 1000.0;
  limits.max_moment_Nm = 100.0;
  limits.max_speed_rad_s = 10.0;
  Vector5 ok;
  ok << 600.0, 0.0, 0.0, 0.0, 50.0;
  EXPECT_TRUE(check_load(ok, limits, nullptr).accepted);
  Vector5 bad = ok;
  bad[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(check_load(bad, limits, nullptr).accepted);
  bad = ok;
  bad[4] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(check_load(bad, limits, nullptr).accepted);
  bad = ok;
  bad[0] = 800.0;  // |F| = 800 ok; with Fz = 700: |F| = 1063 > 1000
  bad[2] = 700.0;
  EXPECT_FALSE(check_load(bad, limits, nullptr).accepted);
  bad = ok;
  bad[3] = 80.0;  // |M| = sqrt(80^2 + 50^2) = 94 ok
  EXPECT_TRUE(check_load(bad, limits, nullptr).accepted);
  bad[3] = 90.0;  // |M| = 103 > 100
  EXPECT_FALSE(check_load(bad, limits, nullptr).accepted);
  EXPECT_TRUE(check_speed(-9.9, limits).accepted);
  EXPECT_FALSE(check_speed(10.1, limits).accepted);
  EXPECT_FALSE(check_speed(-std::numeric_limits<double>::infinity(), limits).accepted);
  EXPECT_FALSE(check_speed(std::numeric_limits<double>::quiet_NaN(), limits).accepted);
}

TEST(InputValidator, ASpeedBeyondTheBearingsPhysicalLimitIsRefusedWhateverMaxSpeed) {
  // dm 40 mm: 500 m/s on the pitch circle is 25,000 rad/s; max_speed_rad_s allows 1e4 at most,
  // so a node with a small bearing is held by max_speed_rad_s, a large one by its own limit.
  const BearingModel small(bearing_config_from_string(
      "balls_per_row: 12\nball_diameter_mm: 8\npitch_diameter_mm: 40\ncontact_angle_deg: 0\n"
      "inner_groove_curvature: 0.52\nouter_groove_curvature: 0.52\nrotating_mass_kg: 0.2\n"));
  const BearingModel large(bearing_config_from_string(
      "balls_per_row: 100\nball_diameter_mm: 20\npitch_diameter_mm: 1000\ncontact_angle_deg: 0\n"
      "inner_groove_curvature: 0.52\nouter_groove_curvature: 0.52\nrotating_mass_kg: 50\n"));
  InputLimits limits;
  limits.max_speed_rad_s = 1e4;
  EXPECT_TRUE(check_speed(9000.0, limits, &small).accepted);
  const InputCheck fast = check_speed(9000.0, limits, &large);  // limit 1000 rad/s
  EXPECT_FALSE(fast.accepted);
  EXPECT_NE(fast.reason.find("speed 9000 rad/s (8.594e+04 rpm) is beyond +-1000 rad/s"), std::string::npos)
      << fast.reason;
  EXPECT_TRUE(check_speed(-1000.0, limits, &large).accepted);
  EXPECT_FALSE(check_speed(1e300, limits, &small).accepted);
}

TEST(InputValidator, RejectsALoadTheBearingCannotCarry) {
  // Single-row angular contact bearing: its contacts push the moving (outer) ring towards
  // +z (c_r sin a0 > 0), so only an external axial force towards -z can be balanced.
  const BearingModel model(bearing_config_from_string(
      "balls_per_row: 12\nball_diameter_mm: 8\npitch_diameter_mm: 40\ncontact_angle_deg: 25\n"
      "inner_groove_curvature: 0.52\nouter_groove_curvature: 0.52\nrotating_mass_kg: 0.2\n"));
  InputLimits limits;
  Vector5 carried, not_carried;
  carried << 0.0, 0.0, -500.0, 0.0, 0.0;
  not_carried << 0.0, 0.0, 500.0, 0.0, 0.0;
  const InputCheck good = check_load(carried, limits, &model);
  EXPECT_TRUE(good.accepted) << good.reason;
  EXPECT_GT(good.max_contact_pressure_Pa, 0.0);  // the static solution was computed
  const InputCheck bad = check_load(not_carried, limits, &model);
  EXPECT_FALSE(bad.accepted);
  EXPECT_NE(bad.reason.find("not carried"), std::string::npos) << bad.reason;
}

TEST(InputValidator, RejectsABearingWhoseStiffModeWouldStallTheIntegrator) {
  const BearingConfig ct = load_bearing_config(test::bearing_file("ct_gantry_lyc.yaml"));
  // The shipped CT bearing is far below the ceiling.
  double rate = 0.0;
  EXPECT_TRUE(check_integrator_work(BearingModel(ct), ct_load(), &rate).accepted);
  EXPECT_LT(rate, 0.1 * kMaxStiffRateRadS);
  // A tilt inertia a million times too small: the tilt block decouples from the 46 kg ring, so
  // the fastest mode is sqrt(largest eigenvalue of K_tilt / J) to a relative J K_xt^2 /
  // (m K_tt^2) ~ 1e-9.
  BearingConfig tiny = ct;
  tiny.tilt_inertia_kg_m2 = 7.9e-6;
  const BearingModel model(tiny);
  const InputCheck c = check_integrator_work(model, ct_load());
  ASSERT_FALSE(c.accepted);
  EXPECT_NE(c.reason.find("tilt_inertia_kg_m2"), std::string::npos) << c.reason;
  const Matrix5 k = solve_static(model, ct_load()).stiffness;
  const Eigen::Matrix2d k_tilt = 0.5 * (k.bottomRightCorner<2, 2>() + k.bottomRightCorner<2, 2>().transpose());
  const double expected_hz =
      std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(k_tilt).eigenvalues()[1] / 7.9e-6) / (2.0 * M_PI);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(c.reason, m, std::regex("tilt mode at ([0-9.]+) MHz"))) << c.reason;
  EXPECT_NEAR(std::stod(m[1]) * 1e6, expected_hz, 0.005 * expected_hz) << c.reason;  // 3 digits printed
  // Overdamped contacts (1e10 N*s/m): named by their key.
  BearingConfig damped = ct;
  damped.contact_damping_Ns_per_m = 1e10;
  const InputCheck d = check_integrator_work(BearingModel(damped), ct_load());
  ASSERT_FALSE(d.accepted);
  EXPECT_NE(d.reason.find("contact_damping_Ns_per_m"), std::string::npos) << d.reason;
}

TEST(SampleSource, NumbersSamplesFromTheInitialEquilibrium) {
  const BearingModel model(load_bearing_config(test::bearing_file("ct_gantry_lyc.yaml")));
  const StaticSolution s = solve_static(model, ct_load());
  SampleSource source(BearingDynamics(model, ct_load(), test::kCtSpeedRadS));
  const SampleSource::Sample first = source.next();
  EXPECT_EQ(first.index, 0u);
  EXPECT_DOUBLE_EQ(first.time_s, 0.0);
  // Sample 0 is the static equilibrium itself (same solver, same load).
  EXPECT_NEAR((first.state->displacement - s.displacement).norm(), 0.0, 1e-12);
  for (std::uint64_t i = 1; i < 50; ++i) {
    const SampleSource::Sample next = source.next();
    EXPECT_EQ(next.index, i);
    EXPECT_DOUBLE_EQ(next.time_s, static_cast<double>(i) / 10000.0);
    EXPECT_FALSE(next.diverged);
  }
}

TEST(SampleSource, ADivergingStateIsResetToTheEquilibriumAndNeverNaN) {
  // One RK4 step per 2 kHz sample puts omega_max * h near 5 for the CT bearing, beyond
  // RK4's stability limit (2.8): the state must run away. (RK4 explicitly: the default
  // exponential integrator is stable there, the linear part being exact.)
  const BearingModel model(load_bearing_config(test::bearing_file("ct_gantry_lyc.yaml")));
  const StaticSolution s = solve_static(model, ct_load());
  SampleSource source(
      BearingDynamics(model, ct_load(), test::kCtSpeedRadS, DynamicsOptions{2000.0, 1, true, IntegrationMethod::Rk4}));
  std::uint64_t diverged = 0;
  for (std::uint64_t i = 0; i < 4000; ++i) {
    const SampleSource::Sample smp = source.next();
    ASSERT_EQ(smp.index, i);
    ASSERT_TRUE(smp.state->displacement.allFinite() && smp.state->acceleration.allFinite());
    if (smp.diverged) {
      ++diverged;
      // The reset state is the static equilibrium of the load at the current cage angle, at
      // rest (1e-9: the Newton solver converges to ~1e-12; the angle matters at 3e-6).
      const StaticSolution here = solve_static(model, ct_load(), smp.state->cage_angle_rad);
      EXPECT_NEAR((smp.state->displacement - here.displacement).norm(), 0.0, 1e-9 * s.displacement.norm());
      EXPECT_EQ(smp.state->velocity.norm(), 0.0);
    }
  }
  EXPECT_GT(diverged, 0u);
  EXPECT_EQ(source.divergence_count(), diverged);
  EXPECT_FALSE(source.last_divergence().empty());
}

TEST(SampleDivider, FiresOncePerPeriodOnTheSampleGrid) {
  SampleDivider d(10.0, 10000.0);  // every 1000 samples
  int fired = 0;
  std::uint64_t first = 0;
  for (std::uint64_t i = 0; i < 10000; ++i)
    if (d.due(i)) {
      if (fired++ == 0) first = i;
    }
  EXPECT_EQ(fired, 10);
  EXPECT_EQ(first, 999u);
  d.set_rate(30.0, 10000.0);  // 333 samples
  EXPECT_EQ(d.period_samples(), 333u);
  fired = 0;
  for (std::uint64_t i = 10000; i < 20000; ++i) fired += d.due(i);
  EXPECT_EQ(fired, 30);  // 10000 / 333 = 30.03
}

TEST(SampleDivider, ARefusedRateNeverThrowsAndKeepsTheLastGoodPeriod) {
  SampleDivider d(10.0, 10000.0);  // every 1000 samples
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  // Each of these once threw std::invalid_argument in the simulation thread (and so aborted
  // the node), or overflowed the period: refused with false, nothing changed.
  for (double bad : {nan, inf, -inf, 0.0, -1.0, 5e-324, 1e-300}) {
    EXPECT_FALSE(SampleDivider::valid_rates(bad, 10000.0)) << bad;
    bool accepted = true;
    EXPECT_NO_THROW(accepted = d.set_rate(bad, 10000.0)) << bad;
    EXPECT_FALSE(accepted) << bad;
    EXPECT_EQ(d.period_samples(), 1000u) << bad;
  }
  EXPECT_FALSE(d.set_rate(10.0, nan));
  // Still on its grid: outputs at 999, 1999, ... as before any refused call.
  int fired = 0;
  std::uint64_t last = 0;
  for (std::uint64_t i = 0; i < 5000; ++i)
    if (d.due(i)) {
      ++fired;
      last = i;
    }
  EXPECT_EQ(fired, 5);
  EXPECT_EQ(last, 4999u);
  // A good rate after the refused ones applies: 10000 / 250 = 40 samples.
  EXPECT_TRUE(d.set_rate(250.0, 10000.0));
  EXPECT_EQ(d.period_samples(), 40u);
  EXPECT_THROW(SampleDivider(nan, 10000.0), std::invalid_argument);  // at construction (node start-up)
}

TEST(TimingStats, PercentilesOfTheRecentValues) {
  TimingStats t(100);
  for (int i = 1; i <= 300; ++i) t.add(i);  // only 201..300 kept
  EXPECT_EQ(t.size(), 100u);
  EXPECT_DOUBLE_EQ(t.percentile(0.5), 250.0);
  EXPECT_DOUBLE_EQ(t.percentile(0.99), 299.0);
  EXPECT_DOUBLE_EQ(t.max(), 300.0);
}


namespace {
// Records what the pipeline hands out, in order.
struct RecordingSink : PipelineSink {
  std::vector<std::pair<std::uint64_t, std::size_t>> chunks;  // first sample, size
  std::vector<std::uint64_t> chunk_ends;
  std::size_t health_handed = 0, levels = 0;
  std::vector<double> analyses;
  std::vector<std::string> order;  // per chunk: ideal, health, end
  void ideal_chunk(SampleChunk&& c) override {
    chunks.emplace_back(c.first_sample, c.size());
    order.push_back("ideal");
  }
  void measured_chunk(SampleChunk&&) override { ADD_FAILURE() << "no sensor: no measured chunk"; }
  void level(const SampleSource::Sample&, double, double) override { ++levels; }
  void health_samples(std::vector<float>&& x, std::optional<double> t) override {
    health_handed += x.size();
    if (t) analyses.push_back(*t);
    else order.push_back("health");
  }
  void chunk_end(std::uint64_t last, std::size_t, const Vector5&, double) override {
    chunk_ends.push_back(last);
    order.push_back("end");
  }
};
}  // namespace

TEST(SamplePipeline, ContiguousChunksEveryMeasuredSampleHandedOverOnceSettingsFromTheNextChunk) {
  const BearingModel model(load_bearing_config(test::bearing_file("ct_gantry_lyc.yaml")));
  OutputSettings settings;
  settings.chunk_samples = 100;
  settings.level_rate_hz = 100.0;
  SamplePipeline p(BearingDynamics(model, ct_load(), test::kCtSpeedRadS, DynamicsOptions{10000.0, 0}), nullptr, settings, 50.0);
  RecordingSink sink;
  p.run_chunk(sink);
  EXPECT_EQ(p.current_chunk_last_index(), 199u);
  settings.chunk_samples = 60;
  p.apply_settings(settings);  // from the next chunk started: the one from sample 100
  EXPECT_EQ(p.current_chunk_last_index(), 159u);
  for (int i = 0; i < 150; ++i) p.step(sink);
  p.flush(sink);  // the short last one
  const std::vector<std::pair<std::uint64_t, std::size_t>> expected = {{0, 100}, {100, 60}, {160, 60}, {220, 30}};
  EXPECT_EQ(sink.chunks, expected);
  EXPECT_EQ(sink.chunk_ends, (std::vector<std::uint64_t>{99, 159, 219, 249}));
  EXPECT_EQ(sink.health_handed, 250u);  // every measured sample once
  EXPECT_EQ(sink.analyses.size(), 1u);  // at 50 Hz: one due within 250 samples (sample 200)
  EXPECT_EQ(sink.levels, 2u);           // at 100 Hz: samples 100 and 200
  std::vector<std::string> order;
  for (int k = 0; k < 4; ++k) order.insert(order.end(), {"ideal", "health", "end"});
  EXPECT_EQ(sink.order, order);
  EXPECT_EQ(p.ideal_samples(), 250u);
  EXPECT_EQ(p.measured_samples(), 250u);
}
