#pragma once
// The per-sample pipeline shared by bearing_sim_node and `bearing_tool generate` (ROS-free):
// dynamics samples (SampleSource) -> ideal chunks, the virtual sensor and its chunks, the
// running level RMS, the level / ball-load / health dividers and the hand-over of the
// measured samples to health. What becomes of the outputs is the sink's business: the
// node's sink makes messages and queues them for their due time, generate's writes files
// and analyses health synchronously. Inputs (load, speed, defects) are set on
// source().ring() between steps by the caller; the ring is rigid or flexible (RingDynamics).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bearing_sim/core/ring_dynamics.hpp"
#include "bearing_sim/core/vibration_level.hpp"
#include "bearing_sim/runtime/chunk_assembler.hpp"
#include "bearing_sim/runtime/sample_divider.hpp"
#include "bearing_sim/runtime/sample_source.hpp"
#include "bearing_sim/runtime/triaxial_sensor.hpp"

namespace bearing_sim {
namespace runtime {

// Azimuths of a flexible ring's published deformation: 5 degrees, 12 points per wave of the
// highest order the shipped rings have (6).
inline constexpr int kRingDeformationPoints = 72;

// Outputs that may change while running (the node's dynamic_reconfigure).
struct OutputSettings {
  std::size_t chunk_samples = 100;
  double level_window_s = 1.0;
  double level_rate_hz = 10.0;
  double ball_loads_rate_hz = 30.0;
};

class PipelineSink {
 public:
  virtual ~PipelineSink() = default;
  // Dynamics-rate chunk, numbered in dynamics samples.
  virtual void ideal_chunk(SampleChunk&& chunk) = 0;
  // With a sensor: its chunk, numbered in sensor samples (sample k is the output at
  // dynamics sample (k + 1) R - 1). Without one, never called (the measured signal is the
  // ideal chunk).
  virtual void measured_chunk(SampleChunk&& chunk) = 0;
  // Running RMS of the measured x over the level window, at dynamics sample `sample.index`.
  virtual void level(const SampleSource::Sample& sample, double accel_rms, double window_s) = 0;
  // Only asked when a ball-load sample is due (per-ball states cost microseconds per ball).
  virtual bool wants_ball_loads() const { return false; }
  // The balls' states at the sample (RingDynamics::ball_states: with a flexible ring's
  // deformation).
  virtual void ball_loads(const SampleSource::Sample& sample, const BearingModel& model,
                          const std::vector<BallState>& balls) {
    (void)sample, (void)model, (void)balls;
  }
  // A flexible ring's deformation at the ball loads' samples, when wanted (docs/node.md).
  virtual bool wants_ring_deformation() const { return false; }
  virtual void ring_deformation(const SampleSource::Sample& sample, const FlexibleBearing::Deformation& deformation) {
    (void)sample, (void)deformation;
  }
  // After the level and ball loads of every sample (generate's labels).
  virtual void sample_done(const SampleSource::Sample& sample) { (void)sample; }
  // The measured x since the last hand-over (health enabled only); analysis_time_s: an
  // analysis is due at this simulated time (at the health rate), else a per-chunk hand-over.
  virtual void health_samples(std::vector<float>&& x, std::optional<double> analysis_time_s) {
    (void)x, (void)analysis_time_s;
  }
  // After each ideal chunk and its health hand-over: the inputs at its end (Miner damage).
  virtual void chunk_end(std::uint64_t last_index, std::size_t samples, const Vector5& load, double ring_speed_rad_s) {
    (void)last_index, (void)samples, (void)load, (void)ring_speed_rad_s;
  }
  virtual void divergence(const std::string& message) { (void)message; }
};

class SamplePipeline {
 public:
  // sensor: null for none. health_rate_hz 0: no health hand-over.
  SamplePipeline(std::unique_ptr<RingDynamics> dynamics, std::unique_ptr<TriaxialSensor> sensor,
                 const OutputSettings& settings, double health_rate_hz);
  SamplePipeline(BearingDynamics dynamics, std::unique_ptr<TriaxialSensor> sensor, const OutputSettings& settings,
                 double health_rate_hz)
      : SamplePipeline(std::make_unique<RigidRingDynamics>(std::move(dynamics)), std::move(sensor), settings,
                       health_rate_hz) {}

  // One dynamics sample through everything; returns true when it closed an ideal chunk.
  bool step(PipelineSink& sink);
  // Steps until an ideal chunk is closed.
  void run_chunk(PipelineSink& sink) {
    while (!step(sink)) {
    }
  }
  // End of a finite run: the short last ideal and sensor chunks, if any.
  void flush(PipelineSink& sink);
  // Chunk size from the next chunk, level window (restarts), output rates.
  void apply_settings(const OutputSettings& settings);

  SampleSource& source() { return source_; }
  const SampleSource& source() const { return source_; }
  const TriaxialSensor* sensor() const { return sensor_.get(); }
  const OutputSettings& settings() const { return settings_; }
  double sample_rate_hz() const { return sample_rate_hz_; }
  double measured_rate_hz() const { return measured_rate_hz_; }
  // The chunk being filled: its size and the index of its last sample.
  std::size_t current_chunk_samples() const { return assembler_.current_target(); }
  std::uint64_t current_chunk_last_index() const { return assembler_.next_sample() + assembler_.current_target() - 1; }
  std::uint64_t ideal_samples() const { return assembler_.next_sample(); }
  std::uint64_t measured_samples() const { return sensor_ ? sensor_assembler_->next_sample() : ideal_samples(); }

 private:
  void close_ideal_chunk(PipelineSink& sink);
  void close_sensor_chunk(PipelineSink& sink);
  std::vector<float> take_health_samples();

  SampleSource source_;
  std::unique_ptr<TriaxialSensor> sensor_;
  OutputSettings settings_;
  double sample_rate_hz_, measured_rate_hz_;
  ChunkAssembler assembler_;
  std::unique_ptr<ChunkAssembler> sensor_assembler_;  // numbered in sensor samples
  std::uint64_t ideal_taken_ = 0, sensor_taken_ = 0;  // samples handed out in chunks
  RunningRms level_rms_;
  SampleDivider level_divider_, ball_loads_divider_;
  std::optional<SampleDivider> health_divider_;
  std::vector<float> health_samples_;  // measured x since the last hand-over
};

}  // namespace runtime
}  // namespace bearing_sim
