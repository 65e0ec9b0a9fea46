#pragma once
// Field-by-field comparison of a ROS message with its LCM counterpart, bit-exact (floats
// and doubles by their bits, so NaN payloads, -0 and infinities count too). Shared by
// test_lcm_conversion and test_lcm_bridge.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <std_msgs/Header.h>

#include "bearing_sim/BallLoads.h"
#include "bearing_sim/BearingHealth.h"
#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/VibrationLevel.h"
#include "bearing_sim_lcm/ball_loads_t.hpp"
#include "bearing_sim_lcm/bearing_health_t.hpp"
#include "bearing_sim_lcm/vibration_chunk_t.hpp"
#include "bearing_sim_lcm/vibration_level_t.hpp"

namespace lcm_test {

inline std::uint32_t bits(float v) {
  std::uint32_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}
inline std::uint64_t bits(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// Equal length and every element's bits equal; names the first element that differs.
inline ::testing::AssertionResult same_floats(const std::vector<float>& ros, const std::vector<float>& lcm) {
  if (ros.size() != lcm.size())
    return ::testing::AssertionFailure() << "sizes " << ros.size() << " (ROS) and " << lcm.size() << " (LCM)";
  for (std::size_t i = 0; i < ros.size(); ++i)
    if (bits(ros[i]) != bits(lcm[i]))
      return ::testing::AssertionFailure() << "element " << i << ": " << ros[i] << " (ROS) and " << lcm[i] << " (LCM)";
  return ::testing::AssertionSuccess();
}

#define LCM_EXPECT_SAME_DOUBLE(ros, lcm) \
  EXPECT_EQ(lcm_test::bits(static_cast<double>(ros)), lcm_test::bits(lcm)) << #ros

inline void expect_equal(const std_msgs::Header& ros, const bearing_sim_lcm::header_t& lcm) {
  EXPECT_EQ(static_cast<std::int64_t>(ros.stamp.sec), lcm.stamp_sec);
  EXPECT_EQ(static_cast<std::int64_t>(ros.stamp.nsec), lcm.stamp_nsec);
  // utime from an independent formula: whole microseconds of the stamp.
  EXPECT_EQ(static_cast<std::int64_t>(ros.stamp.sec) * 1000000 + static_cast<std::int64_t>(ros.stamp.nsec) / 1000,
            lcm.utime);
  EXPECT_EQ(static_cast<std::int64_t>(ros.seq), lcm.seq);
  EXPECT_EQ(ros.frame_id, lcm.frame_id);
}

inline void expect_equal(const bearing_sim::VibrationChunk& ros, const bearing_sim_lcm::vibration_chunk_t& lcm) {
  expect_equal(ros.header, lcm.header);
  EXPECT_EQ(static_cast<std::int64_t>(ros.first_sample), lcm.first_sample);
  LCM_EXPECT_SAME_DOUBLE(ros.sample_rate, lcm.sample_rate);
  EXPECT_EQ(static_cast<std::int64_t>(ros.accel_x.size()), lcm.num_samples);
  EXPECT_TRUE(same_floats(ros.accel_x, lcm.accel_x)) << "accel_x";
  EXPECT_TRUE(same_floats(ros.accel_y, lcm.accel_y)) << "accel_y";
  EXPECT_TRUE(same_floats(ros.accel_z, lcm.accel_z)) << "accel_z";
  EXPECT_TRUE(same_floats(ros.displacement_x, lcm.displacement_x)) << "displacement_x";
  EXPECT_TRUE(same_floats(ros.displacement_y, lcm.displacement_y)) << "displacement_y";
  EXPECT_TRUE(same_floats(ros.displacement_z, lcm.displacement_z)) << "displacement_z";
  EXPECT_TRUE(same_floats(ros.tilt_x, lcm.tilt_x)) << "tilt_x";
  EXPECT_TRUE(same_floats(ros.tilt_y, lcm.tilt_y)) << "tilt_y";
}

inline void expect_equal(const bearing_sim::VibrationLevel& ros, const bearing_sim_lcm::vibration_level_t& lcm) {
  expect_equal(ros.header, lcm.header);
  LCM_EXPECT_SAME_DOUBLE(ros.level_db, lcm.level_db);
  LCM_EXPECT_SAME_DOUBLE(ros.accel_rms, lcm.accel_rms);
  LCM_EXPECT_SAME_DOUBLE(ros.window_s, lcm.window_s);
}

inline void expect_equal(const bearing_sim::BallLoads& ros, const bearing_sim_lcm::ball_loads_t& lcm) {
  expect_equal(ros.header, lcm.header);
  EXPECT_EQ(ros.rows, lcm.rows);
  EXPECT_EQ(static_cast<std::int32_t>(ros.balls_per_row), lcm.balls_per_row);
  LCM_EXPECT_SAME_DOUBLE(ros.cage_angle, lcm.cage_angle);
  EXPECT_EQ(static_cast<std::int64_t>(ros.load.size()), lcm.num_balls);
  EXPECT_TRUE(same_floats(ros.azimuth, lcm.azimuth)) << "azimuth";
  EXPECT_TRUE(same_floats(ros.load, lcm.load)) << "load";
  EXPECT_TRUE(same_floats(ros.contact_angle, lcm.contact_angle)) << "contact_angle";
  EXPECT_TRUE(same_floats(ros.deflection, lcm.deflection)) << "deflection";
}

inline void expect_equal(const bearing_sim::BearingHealth& ros, const bearing_sim_lcm::bearing_health_t& lcm) {
  expect_equal(ros.header, lcm.header);
  EXPECT_EQ(ros.signal, lcm.signal);
  LCM_EXPECT_SAME_DOUBLE(ros.sample_rate, lcm.sample_rate);
  LCM_EXPECT_SAME_DOUBLE(ros.window_s, lcm.window_s);
  LCM_EXPECT_SAME_DOUBLE(ros.accel_rms, lcm.accel_rms);
  LCM_EXPECT_SAME_DOUBLE(ros.accel_peak, lcm.accel_peak);
  LCM_EXPECT_SAME_DOUBLE(ros.crest_factor, lcm.crest_factor);
  LCM_EXPECT_SAME_DOUBLE(ros.kurtosis, lcm.kurtosis);
  LCM_EXPECT_SAME_DOUBLE(ros.level_db, lcm.level_db);
  LCM_EXPECT_SAME_DOUBLE(ros.velocity_rms_mm_s, lcm.velocity_rms_mm_s);
  EXPECT_EQ(ros.velocity_zone, lcm.velocity_zone);
  LCM_EXPECT_SAME_DOUBLE(ros.envelope_low_hz, lcm.envelope_low_hz);
  LCM_EXPECT_SAME_DOUBLE(ros.envelope_high_hz, lcm.envelope_high_hz);
  EXPECT_EQ(static_cast<std::int64_t>(ros.faults.size()), lcm.num_faults);
  ASSERT_EQ(ros.faults.size(), lcm.faults.size());
  for (std::size_t i = 0; i < ros.faults.size(); ++i) {
    SCOPED_TRACE("fault " + std::to_string(i));
    const auto& r = ros.faults[i];
    const auto& l = lcm.faults[i];
    EXPECT_EQ(r.label, l.label);
    EXPECT_EQ(r.part, l.part);
    LCM_EXPECT_SAME_DOUBLE(r.expected_hz, l.expected_hz);
    LCM_EXPECT_SAME_DOUBLE(r.peak_hz, l.peak_hz);
    LCM_EXPECT_SAME_DOUBLE(r.amplitude_m_s2, l.amplitude_m_s2);
    LCM_EXPECT_SAME_DOUBLE(r.noise_floor_m_s2, l.noise_floor_m_s2);
    LCM_EXPECT_SAME_DOUBLE(r.snr_db, l.snr_db);
    EXPECT_EQ(static_cast<int>(r.harmonics_found), static_cast<int>(l.harmonics_found));
    EXPECT_EQ(static_cast<bool>(r.sidebands_required), l.sidebands_required);
    LCM_EXPECT_SAME_DOUBLE(r.modulation_hz, l.modulation_hz);
    EXPECT_EQ(static_cast<int>(r.sidebands_found), static_cast<int>(l.sidebands_found));
    EXPECT_EQ(static_cast<bool>(r.resolvable), l.resolvable);
    EXPECT_EQ(static_cast<bool>(r.impulsiveness_required), l.impulsiveness_required);
    EXPECT_EQ(static_cast<bool>(r.impulsive), l.impulsive);
    LCM_EXPECT_SAME_DOUBLE(r.band_kurtosis, l.band_kurtosis);
    EXPECT_EQ(static_cast<bool>(r.suspected), l.suspected);
    EXPECT_EQ(r.note, l.note);
  }
  EXPECT_EQ(ros.level, lcm.level);
  EXPECT_EQ(ros.reason, lcm.reason);
  EXPECT_EQ(static_cast<std::int64_t>(ros.defects.size()), lcm.num_defects);
  ASSERT_EQ(ros.defects.size(), lcm.defects.size());
  for (std::size_t i = 0; i < ros.defects.size(); ++i) {
    SCOPED_TRACE("defect " + std::to_string(i));
    const auto& r = ros.defects[i];
    const auto& l = lcm.defects[i];
    EXPECT_EQ(r.surface, l.surface);
    LCM_EXPECT_SAME_DOUBLE(r.position_rad, l.position_rad);
    EXPECT_EQ(r.ball, l.ball);
    EXPECT_EQ(r.row, l.row);
    LCM_EXPECT_SAME_DOUBLE(r.width_m, l.width_m);
    LCM_EXPECT_SAME_DOUBLE(r.depth_m, l.depth_m);
    LCM_EXPECT_SAME_DOUBLE(r.width_growth_m_per_s, l.width_growth_m_per_s);
    LCM_EXPECT_SAME_DOUBLE(r.depth_growth_m_per_s, l.depth_growth_m_per_s);
    LCM_EXPECT_SAME_DOUBLE(r.age_s, l.age_s);
  }
  LCM_EXPECT_SAME_DOUBLE(ros.ring_speed_rad_s, lcm.ring_speed_rad_s);
  LCM_EXPECT_SAME_DOUBLE(ros.radial_force_N, lcm.radial_force_N);
  LCM_EXPECT_SAME_DOUBLE(ros.axial_force_N, lcm.axial_force_N);
  LCM_EXPECT_SAME_DOUBLE(ros.dynamic_load_rating_N, lcm.dynamic_load_rating_N);
  LCM_EXPECT_SAME_DOUBLE(ros.equivalent_load_N, lcm.equivalent_load_N);
  LCM_EXPECT_SAME_DOUBLE(ros.l10_million_rev, lcm.l10_million_rev);
  LCM_EXPECT_SAME_DOUBLE(ros.l10_hours, lcm.l10_hours);
  LCM_EXPECT_SAME_DOUBLE(ros.reference_life_million_rev, lcm.reference_life_million_rev);
  LCM_EXPECT_SAME_DOUBLE(ros.reference_life_hours, lcm.reference_life_hours);
  LCM_EXPECT_SAME_DOUBLE(ros.miner_damage, lcm.miner_damage);
  LCM_EXPECT_SAME_DOUBLE(ros.remaining_life_hours, lcm.remaining_life_hours);
  LCM_EXPECT_SAME_DOUBLE(ros.operated_s, lcm.operated_s);
  LCM_EXPECT_SAME_DOUBLE(ros.revolutions, lcm.revolutions);
}

}  // namespace lcm_test
