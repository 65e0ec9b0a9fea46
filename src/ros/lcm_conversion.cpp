#include "bearing_sim/ros/lcm_conversion.hpp"

#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

namespace bearing_sim {
namespace ros_node {
namespace {

// The common length of parallel arrays; throws naming the first that differs.
template <class Vector>
std::int32_t common_length(const char* message, const std::vector<std::pair<const char*, const Vector*>>& arrays) {
  const std::size_t n = arrays.front().second->size();
  for (const auto& a : arrays)
    if (a.second->size() != n)
      throw std::invalid_argument(std::string(message) + "." + a.first + " has " + std::to_string(a.second->size()) +
                                  " elements, " + arrays.front().first + " has " + std::to_string(n) +
                                  ": the LCM type needs equal lengths");
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw std::invalid_argument(std::string(message) + " has more elements than an LCM array can hold");
  return static_cast<std::int32_t>(n);
}

std::int32_t array_length(const char* what, std::size_t n) {
  if (n > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw std::invalid_argument(std::string(what) + " has more elements than an LCM array can hold");
  return static_cast<std::int32_t>(n);
}

}  // namespace

std::int64_t lcm_utime(std::uint32_t sec, std::uint32_t nsec) {
  return static_cast<std::int64_t>(sec) * 1000000 + static_cast<std::int64_t>(nsec / 1000);
}

bearing_sim_lcm::header_t to_lcm(const std_msgs::Header& header) {
  bearing_sim_lcm::header_t h;
  h.utime = lcm_utime(header.stamp.sec, header.stamp.nsec);
  h.stamp_sec = header.stamp.sec;
  h.stamp_nsec = header.stamp.nsec;
  h.seq = header.seq;
  h.frame_id = header.frame_id;
  return h;
}

bearing_sim_lcm::vibration_chunk_t to_lcm(const VibrationChunk& msg) {
  using Array = std::vector<float>;
  bearing_sim_lcm::vibration_chunk_t out;
  out.num_samples = common_length<Array>("VibrationChunk", {{"accel_x", &msg.accel_x},
                                                            {"accel_y", &msg.accel_y},
                                                            {"accel_z", &msg.accel_z},
                                                            {"displacement_x", &msg.displacement_x},
                                                            {"displacement_y", &msg.displacement_y},
                                                            {"displacement_z", &msg.displacement_z},
                                                            {"tilt_x", &msg.tilt_x},
                                                            {"tilt_y", &msg.tilt_y}});
  if (msg.first_sample > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    throw std::invalid_argument("VibrationChunk.first_sample " + std::to_string(msg.first_sample) +
                                " does not fit the LCM int64");
  out.header = to_lcm(msg.header);
  out.first_sample = static_cast<std::int64_t>(msg.first_sample);
  out.sample_rate = msg.sample_rate;
  out.accel_x = msg.accel_x;
  out.accel_y = msg.accel_y;
  out.accel_z = msg.accel_z;
  out.displacement_x = msg.displacement_x;
  out.displacement_y = msg.displacement_y;
  out.displacement_z = msg.displacement_z;
  out.tilt_x = msg.tilt_x;
  out.tilt_y = msg.tilt_y;
  return out;
}

bearing_sim_lcm::vibration_level_t to_lcm(const VibrationLevel& msg) {
  bearing_sim_lcm::vibration_level_t out;
  out.header = to_lcm(msg.header);
  out.level_db = msg.level_db;
  out.accel_rms = msg.accel_rms;
  out.window_s = msg.window_s;
  return out;
}

bearing_sim_lcm::ball_loads_t to_lcm(const BallLoads& msg) {
  using Array = std::vector<float>;
  bearing_sim_lcm::ball_loads_t out;
  out.num_balls = common_length<Array>("BallLoads", {{"azimuth", &msg.azimuth},
                                                     {"load", &msg.load},
                                                     {"contact_angle", &msg.contact_angle},
                                                     {"deflection", &msg.deflection}});
  out.header = to_lcm(msg.header);
  out.rows = msg.rows;
  out.balls_per_row = msg.balls_per_row;
  out.cage_angle = msg.cage_angle;
  out.azimuth = msg.azimuth;
  out.load = msg.load;
  out.contact_angle = msg.contact_angle;
  out.deflection = msg.deflection;
  return out;
}

bearing_sim_lcm::envelope_line_t to_lcm(const EnvelopeLine& msg) {
  bearing_sim_lcm::envelope_line_t out;
  out.label = msg.label;
  out.part = msg.part;
  out.expected_hz = msg.expected_hz;
  out.peak_hz = msg.peak_hz;
  out.amplitude_m_s2 = msg.amplitude_m_s2;
  out.noise_floor_m_s2 = msg.noise_floor_m_s2;
  out.snr_db = msg.snr_db;
  out.harmonics_found = static_cast<std::int8_t>(msg.harmonics_found);
  out.sidebands_required = msg.sidebands_required;
  out.modulation_hz = msg.modulation_hz;
  out.sidebands_found = static_cast<std::int8_t>(msg.sidebands_found);
  out.resolvable = msg.resolvable;
  out.impulsiveness_required = msg.impulsiveness_required;
  out.impulsive = msg.impulsive;
  out.band_kurtosis = msg.band_kurtosis;
  out.suspected = msg.suspected;
  out.note = msg.note;
  return out;
}

bearing_sim_lcm::defect_state_t to_lcm(const DefectState& msg) {
  bearing_sim_lcm::defect_state_t out;
  out.surface = msg.surface;
  out.position_rad = msg.position_rad;
  out.ball = msg.ball;
  out.row = msg.row;
  out.width_m = msg.width_m;
  out.depth_m = msg.depth_m;
  out.width_growth_m_per_s = msg.width_growth_m_per_s;
  out.depth_growth_m_per_s = msg.depth_growth_m_per_s;
  out.age_s = msg.age_s;
  return out;
}

bearing_sim_lcm::bearing_health_t to_lcm(const BearingHealth& msg) {
  bearing_sim_lcm::bearing_health_t out;
  out.header = to_lcm(msg.header);
  out.signal = msg.signal;
  out.sample_rate = msg.sample_rate;
  out.window_s = msg.window_s;
  out.accel_rms = msg.accel_rms;
  out.accel_peak = msg.accel_peak;
  out.crest_factor = msg.crest_factor;
  out.kurtosis = msg.kurtosis;
  out.level_db = msg.level_db;
  out.velocity_rms_mm_s = msg.velocity_rms_mm_s;
  out.velocity_zone = msg.velocity_zone;
  out.envelope_low_hz = msg.envelope_low_hz;
  out.envelope_high_hz = msg.envelope_high_hz;
  out.num_faults = array_length("BearingHealth.faults", msg.faults.size());
  for (const EnvelopeLine& f : msg.faults) out.faults.push_back(to_lcm(f));
  out.level = msg.level;
  out.reason = msg.reason;
  out.num_defects = array_length("BearingHealth.defects", msg.defects.size());
  for (const DefectState& d : msg.defects) out.defects.push_back(to_lcm(d));
  out.ring_speed_rad_s = msg.ring_speed_rad_s;
  out.radial_force_N = msg.radial_force_N;
  out.axial_force_N = msg.axial_force_N;
  out.dynamic_load_rating_N = msg.dynamic_load_rating_N;
  out.equivalent_load_N = msg.equivalent_load_N;
  out.l10_million_rev = msg.l10_million_rev;
  out.l10_hours = msg.l10_hours;
  out.reference_life_million_rev = msg.reference_life_million_rev;
  out.reference_life_hours = msg.reference_life_hours;
  out.miner_damage = msg.miner_damage;
  out.remaining_life_hours = msg.remaining_life_hours;
  out.operated_s = msg.operated_s;
  out.revolutions = msg.revolutions;
  return out;
}

}  // namespace ros_node
}  // namespace bearing_sim
