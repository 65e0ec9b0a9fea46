#pragma once
// The node's virtual sensor (docs/node.md, sensor): a triaxial accelerometer, i.e. three
// core VirtualAccelerometer channels at the sensor file's mounting point, along the
// sensor's own axes (triaxial_frame; for mount: moving_ring at ring angle 0, turning with
// it): channel 0 along the file's `axis`, the direction of a real sensor's positive output;
// for the default axis (1, 0, 0) the bearing frame's x, y and z. Each channel has its own
// noise stream (seed, seed + 1, seed + 2), as three independent sensing elements would.
// ROS-free.
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

// The sensor's axes in the bearing frame, as columns: 0 along `axis`, 2 the bearing's z made
// square to it (x for an axial sensor), 1 = 2 x 0 (right-handed). For a radial axis (1, 0, 0)
// the identity; for (-1, 0, 0), a sensor whose positive output points up at 12 o'clock
// while the load points down, (-x, -y, z).
Eigen::Matrix3d triaxial_frame(const Eigen::Vector3d& axis);

// The config of channel `axis` (0, 1, 2: triaxial_frame's columns) of a triaxial sensor
// built from `config`.
AccelerometerConfig triaxial_channel_config(const AccelerometerConfig& config, int axis);

}  // namespace runtime
}  // namespace bearing_sim
