#pragma once
// Writes a generated dataset as a rosbag with the live node's topics and messages
// (docs/datasets.md): header stamps are simulated time from 0, so the bag holds no
// wall-clock time and the same run gives the same bytes.
#include <memory>
#include <string>

#include "bearing_sim/runtime/dataset_sink.hpp"

namespace rosbag {
class Bag;
}

namespace bearing_sim::tool {

class DatasetBagWriter : public runtime::DatasetSink {
 public:
  explicit DatasetBagWriter(std::string path);
  ~DatasetBagWriter() override;

  void begin(const runtime::DatasetInfo& info) override;
  void ideal_chunk(const runtime::SampleChunk& chunk) override;
  void measured_chunk(const runtime::SampleChunk& chunk) override;
  void level(std::uint64_t index, double accel_rms, double window_s) override;
  bool wants_ball_loads() const override { return true; }
  void ball_loads(std::uint64_t index, const std::vector<BallState>& balls, int rows, int balls_per_row,
                  double cage_angle_rad) override;
  bool wants_health() const override { return true; }
  void health(const runtime::HealthReport& report) override;
  void label(const runtime::LabelState& state) override;
  void end() override;

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  runtime::DatasetInfo info_;
  std::unique_ptr<rosbag::Bag> bag_;
};

}  // namespace bearing_sim::tool
