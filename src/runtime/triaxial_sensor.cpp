#include "bearing_sim/runtime/triaxial_sensor.hpp"

namespace bearing_sim {
namespace runtime {

Eigen::Matrix3d triaxial_frame(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d e0 = axis.normalized();
  // The bearing's z without its part along e0 (x when the axis is axial).
  Eigen::Vector3d e2 = Eigen::Vector3d::UnitZ() - e0.z() * e0;
  if (e2.norm() < 1e-6) e2 = Eigen::Vector3d::UnitX() - e0.x() * e0;
  e2.normalize();
  Eigen::Matrix3d frame;
  frame.col(0) = e0;
  frame.col(1) = e2.cross(e0);
  frame.col(2) = e2;
  return frame;
}

AccelerometerConfig triaxial_channel_config(const AccelerometerConfig& config, int axis) {
  AccelerometerConfig c = config;
  c.axis = triaxial_frame(config.axis).col(axis);
  c.seed = config.seed + static_cast<std::uint64_t>(axis);
  if (axis > 0) c.name = config.name + (axis == 1 ? " (y)" : " (z)");
  return c;
}

TriaxialSensor::TriaxialSensor(const AccelerometerConfig& config, double input_rate_hz)
    : channels_{VirtualAccelerometer(triaxial_channel_config(config, 0), input_rate_hz),
                VirtualAccelerometer(triaxial_channel_config(config, 1), input_rate_hz),
                VirtualAccelerometer(triaxial_channel_config(config, 2), input_rate_hz)} {}

bool TriaxialSensor::push(const DynamicSample& sample, Eigen::Vector3d* out) {
  // The channels decimate in step (same ratio, same phase), so they are due together.
  bool due = false;
  for (int i = 0; i < 3; ++i) due = channels_[i].push(sample, &(*out)[i]);
  return due;
}

void TriaxialSensor::reset() {
  for (auto& c : channels_) c.reset();
}

std::uint64_t TriaxialSensor::clipped_sample_count() const {
  std::uint64_t n = 0;
  for (const auto& c : channels_) n += c.clipped_sample_count();
  return n;
}

}  // namespace runtime
}  // namespace bearing_sim
