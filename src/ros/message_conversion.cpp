#include "bearing_sim/ros/message_conversion.hpp"

#include <utility>

namespace bearing_sim {
namespace ros_node {

Vector5 load_from_wrench(const geometry_msgs::Wrench& wrench) {
  Vector5 load;
  load << wrench.force.x, wrench.force.y, wrench.force.z, wrench.torque.x, wrench.torque.y;
  return load;
}

void fill_vibration_chunk(SampleChunk&& chunk, const ros::Time& first_sample_stamp, const std::string& frame_id,
                          double sample_rate_hz, VibrationChunk* msg) {
  msg->header.stamp = first_sample_stamp;
  msg->header.frame_id = frame_id;
  msg->first_sample = chunk.first_sample;
  msg->sample_rate = sample_rate_hz;
  msg->accel_x = std::move(chunk.accel_x);
  msg->accel_y = std::move(chunk.accel_y);
  msg->accel_z = std::move(chunk.accel_z);
  msg->displacement_x = std::move(chunk.displacement_x);
  msg->displacement_y = std::move(chunk.displacement_y);
  msg->displacement_z = std::move(chunk.displacement_z);
}

void fill_ball_loads(const std::vector<BallState>& balls, int rows, int balls_per_row, double cage_angle_rad,
                     BallLoads* msg) {
  msg->rows = static_cast<std::uint8_t>(rows);
  msg->balls_per_row = static_cast<std::uint16_t>(balls_per_row);
  msg->cage_angle = cage_angle_rad;
  const std::size_t n = balls.size();
  msg->azimuth.resize(n);
  msg->load.resize(n);
  msg->contact_angle.resize(n);
  msg->deflection.resize(n);
  // Row-major: the core numbers the balls row by row; place by (row, index) to be sure.
  for (const BallState& b : balls) {
    const std::size_t i = static_cast<std::size_t>(b.row) * static_cast<std::size_t>(balls_per_row) +
                          static_cast<std::size_t>(b.index_in_row);
    if (i >= n) continue;
    msg->azimuth[i] = static_cast<float>(b.azimuth_rad);
    msg->load[i] = static_cast<float>(b.load_N);
    msg->contact_angle[i] = static_cast<float>(b.contact_angle_rad);
    msg->deflection[i] = static_cast<float>(b.deflection_m);
  }
}

}  // namespace ros_node
}  // namespace bearing_sim
