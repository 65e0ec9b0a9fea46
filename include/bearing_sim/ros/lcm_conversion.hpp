#pragma once
// ROS messages -> LCM types of lcm/ (bearing_sim_lcm), field by field, exactly: stamps as
// (sec, nsec) plus utime, samples in float32 as in ROS. Pure functions, no ROS master.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <std_msgs/Header.h>

#include "bearing_sim/BallLoads.h"
#include "bearing_sim/BearingHealth.h"
#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/VibrationLevel.h"
#include "bearing_sim_lcm/ball_loads_t.hpp"
#include "bearing_sim_lcm/bearing_health_t.hpp"
#include "bearing_sim_lcm/header_t.hpp"
#include "bearing_sim_lcm/vibration_chunk_t.hpp"
#include "bearing_sim_lcm/vibration_level_t.hpp"

namespace bearing_sim {
namespace ros_node {

// LCM's utime (microseconds) of a ROS stamp: sec * 1e6 + floor(nsec / 1000), in integers.
std::int64_t lcm_utime(std::uint32_t sec, std::uint32_t nsec);

bearing_sim_lcm::header_t to_lcm(const std_msgs::Header& header);

// The conversions of messages with parallel arrays throw std::invalid_argument naming the
// array if the arrays differ in length (the LCM types have one length for all of them).
bearing_sim_lcm::vibration_chunk_t to_lcm(const VibrationChunk& msg);
bearing_sim_lcm::vibration_level_t to_lcm(const VibrationLevel& msg);
bearing_sim_lcm::ball_loads_t to_lcm(const BallLoads& msg);
bearing_sim_lcm::envelope_line_t to_lcm(const EnvelopeLine& msg);
bearing_sim_lcm::defect_state_t to_lcm(const DefectState& msg);
bearing_sim_lcm::bearing_health_t to_lcm(const BearingHealth& msg);

// An LCM message's wire bytes (fingerprint included), as lcm::LCM::publish sends them.
template <class LcmType>
std::vector<std::uint8_t> encode_lcm(const LcmType& msg) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
  if (msg.encode(bytes.data(), 0, static_cast<int>(bytes.size())) != static_cast<int>(bytes.size()))
    throw std::runtime_error(std::string("cannot encode LCM message ") + LcmType::getTypeName());
  return bytes;
}

}  // namespace ros_node
}  // namespace bearing_sim
