#include "bearing_sim/runtime/scenario_simulation.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/ring_dynamics.hpp"
#include "bearing_sim/core/simd_info.hpp"
#include "bearing_sim/core/thermal_clearance.hpp"
#include "bearing_sim/core/vibration_level.hpp"
#include "bearing_sim/runtime/defects_now.hpp"
#include "bearing_sim/runtime/sample_pipeline.hpp"

namespace bearing_sim::runtime {
namespace {

double thread_cpu_s() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// CPU time spent in the sinks, for the overhead figure.
class SinkTimer {
 public:
  explicit SinkTimer(double* total) : total_(total), start_(thread_cpu_s()) {}
  ~SinkTimer() { *total_ += thread_cpu_s() - start_; }

 private:
  double* total_;
  double start_;
};

}  // namespace

LabelState scenario_label(const Scenario& scenario, std::uint64_t index, double sample_rate_hz) {
  LabelState s;
  s.index = index;
  s.time_s = static_cast<double>(index) / sample_rate_hz;
  s.inputs = scenario.inputs_at(s.time_s);
  s.defects = runtime::scenario_defects_at(scenario, s.time_s);
  return s;
}

ScenarioSimulation::ScenarioSimulation(Scenario scenario, const std::string& scenario_file, GenerateSettings settings)
    : scenario_(std::move(scenario)), settings_(settings) {
  const std::uint64_t seed = settings_.seed.value_or(scenario_.seed());
  const double duration = settings_.duration_s.value_or(scenario_.duration_s());
  if (!(duration > 0.0) || !std::isfinite(duration)) throw InvalidInputError("duration must be > 0 s");
  if (duration > kMaxScenarioDurationS) {
    char text[160];
    std::snprintf(text, sizeof text, "duration %g s: at most %g s, as a scenario's duration_s", duration,
                  kMaxScenarioDurationS);
    throw InvalidInputError(text);
  }
  BearingConfig config = load_bearing_config(scenario_.bearing_file());
  config.imperfections.seed = seed;  // roughness, ball sizes and cage slip from the run's seed
  config.ring_temperature_difference_K =
      settings_.ring_temperature_difference_K.value_or(scenario_.ring_temperature_difference_at(0.0));
  model_ = std::make_unique<BearingModel>(config);
  const double rate = scenario_.sample_rate_hz();

  info_.scenario = scenario_.name();
  info_.description = scenario_.description();
  info_.scenario_file = scenario_file;
  info_.bearing_name = config.name;
  info_.bearing_file = scenario_.bearing_file();
  info_.seed = seed;
  info_.duration_s = duration;
  info_.sample_rate_hz = rate;
  info_.ideal_samples = static_cast<std::uint64_t>(std::llround(duration * rate));
  info_.measured_rate_hz = rate;
  info_.measured_samples = info_.ideal_samples;
  info_.sensor_unit = "m_s2";
  info_.frame_id = config.rotating_ring == RotatingRing::Outer ? "bearing_outer_ring" : "bearing_inner_ring";
  info_.bearing_frame_id = "bearing";
  info_.phases = scenario_.phases();
  info_.simd_target = simd_target_name();
  if (!(settings_.label_rate_hz > 0.0) || settings_.label_rate_hz > rate)
    throw InvalidInputError("label rate must be in (0, sample rate]");
  label_period_ = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(rate / settings_.label_rate_hz)));
  info_.label_rate_hz = rate / static_cast<double>(label_period_);
  if (!scenario_.sensor_file().empty()) {
    AccelerometerConfig sensor = load_accelerometer_config(scenario_.sensor_file());
    sensor.seed = seed;                                 // noise streams seed, seed + 1, seed + 2 (TriaxialSensor)
    const runtime::TriaxialSensor check(sensor, rate);  // throws for a rate it cannot run at
    info_.sensor_name = sensor.name;
    info_.sensor_file = scenario_.sensor_file();
    info_.sensor_unit = sensor.output_unit == SensorOutputUnit::Voltage_V ? "V" : "m_s2";
    info_.measured_rate_hz = check.output_rate_hz();
    info_.decimation_ratio = check.decimation_ratio();
    info_.measured_samples = info_.ideal_samples / static_cast<std::uint64_t>(info_.decimation_ratio);
    sensor_config_ = sensor;
  }
}

namespace {

// generate's end of the shared pipeline: to the dataset sinks; health analysed here,
// synchronously (the node does it on its worker thread).
class DatasetPipelineSink : public runtime::PipelineSink {
 public:
  DatasetPipelineSink(const std::vector<DatasetSink*>& sinks, RunStats* stats, runtime::HealthMonitor* health,
                      const Scenario& scenario, std::uint64_t label_period, double rate, bool want_balls,
                      const std::function<void(double)>& progress)
      : sinks_(sinks),
        stats_(stats),
        health_(health),
        scenario_(scenario),
        label_period_(label_period),
        rate_(rate),
        want_balls_(want_balls),
        progress_(progress) {}

  void ideal_chunk(runtime::SampleChunk&& chunk) override {
    SinkTimer t(&stats_->sink_cpu_s);
    for (DatasetSink* s : sinks_) {
      s->ideal_chunk(chunk);
      if (!has_sensor_) s->measured_chunk(chunk);  // without a sensor the measured signal is the ideal one
    }
  }
  void measured_chunk(runtime::SampleChunk&& chunk) override {
    SinkTimer t(&stats_->sink_cpu_s);
    for (DatasetSink* s : sinks_) s->measured_chunk(chunk);
  }
  void level(const runtime::SampleSource::Sample& sample, double accel_rms, double window_s) override {
    SinkTimer t(&stats_->sink_cpu_s);
    for (DatasetSink* s : sinks_) s->level(sample.index, accel_rms, window_s);
  }
  bool wants_ball_loads() const override { return want_balls_; }
  void ball_loads(const runtime::SampleSource::Sample& sample, const BearingModel& model,
                  const std::vector<BallState>& balls) override {
    SinkTimer t(&stats_->sink_cpu_s);
    for (DatasetSink* s : sinks_)
      s->ball_loads(sample.index, balls, model.rows(), model.balls_per_row(), sample.state->cage_angle_rad);
  }
  void sample_done(const runtime::SampleSource::Sample& sample) override {
    if (sample.index % label_period_ != 0) return;
    SinkTimer t(&stats_->sink_cpu_s);
    const LabelState label = scenario_label(scenario_, sample.index, rate_);
    for (DatasetSink* s : sinks_) s->label(label);
  }
  void health_samples(std::vector<float>&& x, std::optional<double> analysis_time_s) override {
    health_->push(x.data(), x.size());
    if (!analysis_time_s) return;
    runtime::HealthReport report;
    {
      SinkTimer t(&stats_->health_cpu_s);
      report = health_->analyze_now(*analysis_time_s);
    }
    SinkTimer t(&stats_->sink_cpu_s);
    for (DatasetSink* s : sinks_) s->health(report);
  }
  void chunk_end(std::uint64_t last_index, std::size_t samples, const Vector5& load, double ring_speed_rad_s) override {
    if (health_) health_->add_operation(load, ring_speed_rad_s, static_cast<double>(samples) / rate_);
    if (progress_) progress_(static_cast<double>(last_index + 1) / rate_);
  }

  bool has_sensor_ = false;

 private:
  const std::vector<DatasetSink*>& sinks_;
  RunStats* stats_;
  runtime::HealthMonitor* health_;
  const Scenario& scenario_;
  std::uint64_t label_period_;
  double rate_;
  bool want_balls_;
  const std::function<void(double)>& progress_;
};

}  // namespace

RunStats ScenarioSimulation::run(const std::vector<DatasetSink*>& sinks, const std::function<void(double)>& progress) {
  const double cpu_start = thread_cpu_s();
  RunStats stats;
  const double rate = info_.sample_rate_hz;
  const std::uint64_t n = info_.ideal_samples;

  const ScenarioInputs start = scenario_.inputs_at(0.0);
  const bool want_balls = std::any_of(sinks.begin(), sinks.end(), [](DatasetSink* s) { return s->wants_ball_loads(); });
  const bool want_health = settings_.health_rate_hz > 0.0 &&
                           std::any_of(sinks.begin(), sinks.end(), [](DatasetSink* s) { return s->wants_health(); });
  OutputSettings outputs;
  outputs.chunk_samples = settings_.chunk_samples;
  outputs.level_window_s = settings_.level_window_s;
  outputs.level_rate_hz = settings_.level_rate_hz;
  outputs.ball_loads_rate_hz = settings_.ball_loads_rate_hz;
  // The live node's pipeline: same chunks, sensor, level, dividers and health hand-over.
  SamplePipeline pipeline(make_ring_dynamics(*model_, start.load, start.ring_speed_rad_s, DynamicsOptions{rate, 0}),
                          sensor_config_ ? std::make_unique<TriaxialSensor>(*sensor_config_, rate) : nullptr, outputs,
                          want_health ? settings_.health_rate_hz : 0.0);
  RingDynamics& dynamics = pipeline.source().ring();
  std::unique_ptr<HealthMonitor> health;
  if (want_health) {
    HealthSettings hs;
    hs.sample_rate_hz = info_.measured_rate_hz;
    hs.window_s = settings_.health_window_s;
    hs.analysis.resonance_hz = sensor_config_ ? sensor_config_->path_resonance_hz : 0.0;  // envelope band, as the node
    health = std::make_unique<HealthMonitor>(*model_, start.load, start.ring_speed_rad_s, hs, nullptr);
  }
  DatasetPipelineSink sink(sinks, &stats, health.get(), scenario_, label_period_, rate, want_balls, progress);
  sink.has_sensor_ = pipeline.sensor() != nullptr;

  for (DatasetSink* s : sinks) {
    SinkTimer t(&stats.sink_cpu_s);
    s->begin(info_);
  }
  const auto& events = scenario_.defect_events();
  std::size_t next_event = 0;
  auto apply_events = [&](double time_s) {
    bool changed = false;
    for (; next_event < events.size() && events[next_event].time_s <= time_s; ++next_event) {
      if (events[next_event].kind == ScenarioDefectEvent::Kind::Clear) dynamics.clear_spalls();
      else dynamics.add_spall(events[next_event].spall);  // checked against the bearing when loaded
      changed = true;
    }
    if (changed && health) health->set_defects(dynamics.model().imperfections().spalls());
  };
  apply_events(0.0);

  for (std::uint64_t i = 0; i < n; ++i) {
    if (i > 0) {
      apply_events(static_cast<double>(i - 1) / rate);
      // Inputs of the next step: the scenario at its middle, which for holds and ramps is the
      // mean speed, so that the dynamics' ring angle follows the scenario's integral (and a
      // rotating unbalance turns smoothly). Setters only on change.
      const double t_mid = (static_cast<double>(i) - 0.5) / rate;
      const double speed = scenario_.ring_speed_at(t_mid);
      if (speed != dynamics.ring_speed_rad_s()) dynamics.set_ring_speed(speed);
      // The load: its mid value held over the step, its end value for the sample's reported
      // acceleration (a turning unbalance would otherwise leave a line growing with the step).
      const Vector5 load = scenario_.load_at(t_mid);
      const Vector5 load_at_end = scenario_.load_at(static_cast<double>(i) / rate);
      if (load != dynamics.load() || load_at_end != load) dynamics.set_load(load, load_at_end);
      // The ring temperature difference: a new model on each change (ramps come in steps).
      if (!settings_.ring_temperature_difference_K) {
        const double dT = scenario_.ring_temperature_difference_at(t_mid);
        if (dT != dynamics.model().config().ring_temperature_difference_K) {
          BearingModel hot = with_ring_temperature_difference(dynamics.model(), dT);
          if (health) health->set_model(hot);
          dynamics.set_model(std::move(hot));
        }
      }
    }
    pipeline.step(sink);
  }
  pipeline.flush(sink);  // the short last chunks
  for (DatasetSink* s : sinks) {
    SinkTimer t(&stats.sink_cpu_s);
    s->end();
  }
  stats.simulated_s = static_cast<double>(n) / rate;
  stats.ideal_samples = n;
  stats.measured_samples = pipeline.measured_samples();
  stats.divergences = pipeline.source().divergence_count();
  stats.cpu_s = thread_cpu_s() - cpu_start;
  return stats;
}

}  // namespace bearing_sim::runtime
