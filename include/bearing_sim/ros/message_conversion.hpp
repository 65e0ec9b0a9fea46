#pragma once
// Conversions between the core's types and the ROS messages (no logic beyond layout).
#include <vector>

#include <geometry_msgs/Wrench.h>
#include <ros/time.h>

#include "bearing_sim/BallLoads.h"
#include "bearing_sim/BearingHealth.h"
#include "bearing_sim/DefectState.h"
#include "bearing_sim/ScenarioState.h"
#include "bearing_sim/VibrationChunk.h"
#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/runtime/chunk_assembler.hpp"
#include "bearing_sim/runtime/health_monitor.hpp"

namespace bearing_sim {
namespace ros_node {

// (Fx, Fy, Fz, Mx, My); the torque about the axis is not a load (the speed is prescribed).
Vector5 load_from_wrench(const geometry_msgs::Wrench& wrench);

// Moves the chunk's arrays into the message.
void fill_vibration_chunk(runtime::SampleChunk&& chunk, const ros::Time& first_sample_stamp,
                          const std::string& frame_id, double sample_rate_hz, VibrationChunk* msg);

// The health report as a message; `signal` says what was analysed.
void fill_bearing_health(const runtime::HealthReport& report, const std::string& signal, double sample_rate_hz,
                         BearingHealth* msg);

// One spall with its size now.
void fill_defect_state(const runtime::DefectNow& defect, DefectState* msg);

// The labels of a scenario run at scenario time time_s (header left to the caller).
void fill_scenario_state(const std::string& scenario, const std::string& bearing, std::uint64_t seed, double time_s,
                         const ScenarioInputs& inputs, const std::vector<runtime::DefectNow>& defects,
                         ScenarioState* msg);

void fill_ball_loads(const std::vector<BallState>& balls, int rows, int balls_per_row, double cage_angle_rad,
                     BallLoads* msg);

}  // namespace ros_node
}  // namespace bearing_sim
