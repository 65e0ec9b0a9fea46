#pragma once
// The node's virtual sensor (docs/node.md, sensor): a triaxial accelerometer, i.e. three
// core VirtualAccelerometer channels at the sensor file's mounting point, along the
// bearing frame's x, y and z (for mount: moving_ring, the ring's axes at angle 0, turning
// with it). The file's `axis` is not used: a triaxial sensor has all three. Each channel
// has its own noise stream (seed, seed + 1, seed + 2), as three independent sensing
// elements would. ROS-free.
#include <array>
#include <cstdint>

#include <Eigen/Dense>

#include "bearing_sim/core/virtual_accelerometer.hpp"

namespace bearing_sim {
namespace runtime {

class TriaxialSensor {
 public:
  // Throws InvalidInputError when the sensor cannot run at this input rate (output rate
  // not dividing it, above 51.2 kHz, path resonance too high, ...).
  TriaxialSensor(const AccelerometerConfig& config, double input_rate_hz);

  // One dynamics sample in; true with *out = (x, y, z) in the output unit when a sensor
  // sample is due (every decimation_ratio() inputs).
  bool push(const DynamicSample& sample, Eigen::Vector3d* out);
  void reset();

  const AccelerometerConfig& config() const { return channels_[0].config(); }
  double output_rate_hz() const { return channels_[0].output_rate_hz(); }
  int decimation_ratio() const { return channels_[0].decimation_ratio(); }
  std::uint64_t clipped_sample_count() const;

 private:
  std::array<VirtualAccelerometer, 3> channels_;
};

// The config of channel `axis` (0 x, 1 y, 2 z) of a triaxial sensor built from `config`.
AccelerometerConfig triaxial_channel_config(const AccelerometerConfig& config, int axis);

}  // namespace runtime
}  // namespace bearing_sim
