#include "bearing_sim/runtime/sample_pipeline.hpp"

#include <algorithm>
#include <cmath>

namespace bearing_sim {
namespace runtime {
namespace {

std::size_t window_samples(double window_s, double rate_hz) {
  return static_cast<std::size_t>(std::max(1.0, std::round(window_s * rate_hz)));
}

std::size_t sensor_chunk_samples(std::size_t ideal_chunk_samples, int decimation_ratio) {
  // About the same time span as the ideal chunks.
  return std::max<std::size_t>(1, ideal_chunk_samples / static_cast<std::size_t>(decimation_ratio));
}

}  // namespace

SamplePipeline::SamplePipeline(std::unique_ptr<RingDynamics> dynamics, std::unique_ptr<TriaxialSensor> sensor,
                               const OutputSettings& settings, double health_rate_hz)
    : source_(std::move(dynamics)),
      sensor_(std::move(sensor)),
      settings_(settings),
      sample_rate_hz_(source_.ring().sample_rate_hz()),
      measured_rate_hz_(sensor_ ? sensor_->output_rate_hz() : sample_rate_hz_),
      assembler_(settings.chunk_samples),
      level_rms_(window_samples(settings.level_window_s, measured_rate_hz_)),
      level_divider_(settings.level_rate_hz, sample_rate_hz_),
      ball_loads_divider_(settings.ball_loads_rate_hz, sample_rate_hz_) {
  if (sensor_)
    sensor_assembler_ =
        std::make_unique<ChunkAssembler>(sensor_chunk_samples(settings.chunk_samples, sensor_->decimation_ratio()));
  if (health_rate_hz > 0.0) {
    health_divider_.emplace(health_rate_hz, sample_rate_hz_);
    health_samples_.reserve(settings.chunk_samples + 1);
  }
}

bool SamplePipeline::step(PipelineSink& sink) {
  const SampleSource::Sample sample = source_.next();
  if (sample.diverged) sink.divergence(source_.last_divergence());
  const bool full = assembler_.add(sample.index, *sample.state);
  // The measured signal (sensor, or the ideal x without one): L and health.
  bool measured = true;
  double measured_x = sample.state->acceleration[0];
  if (sensor_) {
    Eigen::Vector3d y;
    measured = sensor_->push(*sample.state, &y);
    if (measured) {
      measured_x = y[0];
      if (sensor_assembler_->add(sensor_assembler_->next_sample(), y, sample.state->displacement))
        close_sensor_chunk(sink);
    }
  }
  if (measured) {
    level_rms_.add(measured_x);
    if (health_divider_) health_samples_.push_back(static_cast<float>(measured_x));
  }
  if (level_divider_.due(sample.index))
    sink.level(sample, level_rms_.rms(), static_cast<double>(level_rms_.size()) / measured_rate_hz_);
  if (ball_loads_divider_.due(sample.index)) {
    if (sink.wants_ball_loads()) sink.ball_loads(sample, source_.ring().model(), source_.ring().ball_states());
    const FlexibleSample* flexible = source_.ring().flexible_state();
    if (flexible && sink.wants_ring_deformation())
      sink.ring_deformation(sample, source_.ring().flexible()->bearing().deformation(
                                        flexible->coordinates, flexible->phase, kRingDeformationPoints));
  }
  sink.sample_done(sample);
  if (health_divider_ && health_divider_->due(sample.index)) {
    std::vector<float> x = take_health_samples();
    sink.health_samples(std::move(x), sample.time_s);
  }
  if (full) close_ideal_chunk(sink);
  return full;
}

std::vector<float> SamplePipeline::take_health_samples() {
  // Handed over at least once per chunk: a chunk's worth never reallocates. The sink owns
  // the vector (the node's publisher thread frees it), hence a fresh one each time.
  std::vector<float> x = std::move(health_samples_);
  health_samples_ = std::vector<float>();
  health_samples_.reserve(assembler_.current_target() + 1);
  return x;
}

void SamplePipeline::close_ideal_chunk(PipelineSink& sink) {
  SampleChunk chunk = assembler_.take();
  const std::size_t n = chunk.size();
  ideal_taken_ += n;
  const std::uint64_t last_index = chunk.first_sample + n - 1;
  sink.ideal_chunk(std::move(chunk));
  // Hand the measured samples over once per chunk; Miner damage for the chunk's inputs.
  if (health_divider_) {
    std::vector<float> x = take_health_samples();
    sink.health_samples(std::move(x), std::nullopt);
  }
  sink.chunk_end(last_index, n, source_.ring().load(), source_.ring().ring_speed_rad_s());
}

void SamplePipeline::close_sensor_chunk(PipelineSink& sink) {
  SampleChunk chunk = sensor_assembler_->take();
  sensor_taken_ += chunk.size();
  sink.measured_chunk(std::move(chunk));
}

void SamplePipeline::flush(PipelineSink& sink) {
  if (assembler_.next_sample() > ideal_taken_) close_ideal_chunk(sink);
  if (sensor_ && sensor_assembler_->next_sample() > sensor_taken_) close_sensor_chunk(sink);
}

void SamplePipeline::apply_settings(const OutputSettings& s) {
  if (s.chunk_samples != settings_.chunk_samples) {
    assembler_.set_chunk_samples(s.chunk_samples);
    if (sensor_)
      sensor_assembler_->set_chunk_samples(sensor_chunk_samples(s.chunk_samples, sensor_->decimation_ratio()));
  }
  if (s.level_window_s != settings_.level_window_s)
    level_rms_.resize(window_samples(s.level_window_s, measured_rate_hz_));
  if (s.level_rate_hz != settings_.level_rate_hz) level_divider_.set_rate(s.level_rate_hz, sample_rate_hz_);
  if (s.ball_loads_rate_hz != settings_.ball_loads_rate_hz)
    ball_loads_divider_.set_rate(s.ball_loads_rate_hz, sample_rate_hz_);
  settings_ = s;
}

}  // namespace runtime
}  // namespace bearing_sim
