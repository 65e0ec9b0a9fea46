#include "scenario_simulation.hpp"

#include <time.h>

#include <algorithm>
#include <cmath>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/vibration_level.hpp"
#include "bearing_sim/ros/message_conversion.hpp"
#include "bearing_sim/ros/sample_divider.hpp"
#include "bearing_sim/ros/sample_source.hpp"
#include "bearing_sim/ros/triaxial_sensor.hpp"

namespace bearing_sim::tool {
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
  s.defects = ros_node::scenario_defects_at(scenario, s.time_s);
  return s;
}

ScenarioSimulation::ScenarioSimulation(Scenario scenario, const std::string& scenario_file, GenerateSettings settings)
    : scenario_(std::move(scenario)), settings_(settings) {
  const std::uint64_t seed = settings_.seed.value_or(scenario_.seed());
  const double duration = settings_.duration_s.value_or(scenario_.duration_s());
  if (!(duration > 0.0) || !std::isfinite(duration)) throw InvalidInputError("duration must be > 0 s");
  BearingConfig config = load_bearing_config(scenario_.bearing_file());
  config.imperfections.seed = seed;  // roughness, ball sizes and cage slip from the run's seed
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
  if (!(settings_.label_rate_hz > 0.0) || settings_.label_rate_hz > rate)
    throw InvalidInputError("label rate must be in (0, sample rate]");
  label_period_ = std::max<std::uint64_t>(1, static_cast<std::uint64_t>(std::llround(rate / settings_.label_rate_hz)));
  info_.label_rate_hz = rate / static_cast<double>(label_period_);
  if (!scenario_.sensor_file().empty()) {
    AccelerometerConfig sensor = load_accelerometer_config(scenario_.sensor_file());
    sensor.seed = seed;                                  // noise streams seed, seed + 1, seed + 2 (TriaxialSensor)
    const ros_node::TriaxialSensor check(sensor, rate);  // throws for a rate it cannot run at
    info_.sensor_name = sensor.name;
    info_.sensor_file = scenario_.sensor_file();
    info_.sensor_unit = sensor.output_unit == SensorOutputUnit::Voltage_V ? "V" : "m_s2";
    info_.measured_rate_hz = check.output_rate_hz();
    info_.decimation_ratio = check.decimation_ratio();
    info_.measured_samples = info_.ideal_samples / static_cast<std::uint64_t>(info_.decimation_ratio);
    sensor_config_ = sensor;
  }
}

RunStats ScenarioSimulation::run(const std::vector<DatasetSink*>& sinks, const std::function<void(double)>& progress) {
  using namespace ros_node;
  const double cpu_start = thread_cpu_s();
  RunStats stats;
  const double rate = info_.sample_rate_hz;
  const std::uint64_t n = info_.ideal_samples;

  const ScenarioInputs start = scenario_.inputs_at(0.0);
  SampleSource source(BearingDynamics(*model_, start.load, start.ring_speed_rad_s, DynamicsOptions{rate, 0}));
  BearingDynamics& dynamics = source.dynamics();
  std::unique_ptr<TriaxialSensor> sensor;
  std::unique_ptr<ChunkAssembler> measured_assembler;
  ChunkAssembler ideal_assembler(settings_.chunk_samples);
  if (sensor_config_) {
    sensor = std::make_unique<TriaxialSensor>(*sensor_config_, rate);
    // About the same time span per chunk as the ideal ones (as the live node).
    measured_assembler = std::make_unique<ChunkAssembler>(
        std::max<std::size_t>(1, settings_.chunk_samples / static_cast<std::size_t>(sensor->decimation_ratio())));
  }
  const bool want_balls = std::any_of(sinks.begin(), sinks.end(), [](DatasetSink* s) { return s->wants_ball_loads(); });
  const bool want_health = settings_.health_rate_hz > 0.0 &&
                           std::any_of(sinks.begin(), sinks.end(), [](DatasetSink* s) { return s->wants_health(); });
  RunningRms level_rms(
      static_cast<std::size_t>(std::max(1.0, std::round(settings_.level_window_s * info_.measured_rate_hz))));
  SampleDivider level_divider(settings_.level_rate_hz, rate), ball_divider(settings_.ball_loads_rate_hz, rate),
      health_divider(want_health ? settings_.health_rate_hz : 1.0, rate);
  std::unique_ptr<HealthMonitor> health;
  std::vector<float> health_samples;
  if (want_health) {
    HealthSettings hs;
    hs.sample_rate_hz = info_.measured_rate_hz;
    hs.window_s = settings_.health_window_s;
    hs.analysis.resonance_hz = sensor ? sensor->config().path_resonance_hz : 0.0;  // envelope band, as the node
    health = std::make_unique<HealthMonitor>(*model_, start.load, start.ring_speed_rad_s, hs, nullptr);
  }

  for (DatasetSink* s : sinks) {
    SinkTimer t(&stats.sink_cpu_s);
    s->begin(info_);
  }
  const auto& events = scenario_.defect_events();
  std::size_t next_event = 0;
  auto apply_events = [&](double time_s) {
    bool changed = false;
    for (; next_event < events.size() && events[next_event].time_s <= time_s; ++next_event) {
      if (events[next_event].kind == ScenarioDefectEvent::Kind::Clear)
        dynamics.clear_spalls();
      else
        dynamics.add_spall(events[next_event].spall);  // checked against the bearing when loaded
      changed = true;
    }
    if (changed && health) health->set_defects(dynamics.model().imperfections().spalls());
  };
  apply_events(0.0);

  std::uint64_t measured_emitted = 0;
  auto emit_measured = [&]() {
    SampleChunk chunk = measured_assembler->take();
    measured_emitted += chunk.size();
    SinkTimer t(&stats.sink_cpu_s);
    for (DatasetSink* s : sinks) s->measured_chunk(chunk);
  };
  for (std::uint64_t i = 0; i < n; ++i) {
    if (i > 0) {
      apply_events(static_cast<double>(i - 1) / rate);
      // Inputs of the next step: the scenario at its middle, which for holds and ramps is the
      // mean speed, so that the dynamics' ring angle follows the scenario's integral (and a
      // rotating unbalance turns smoothly). Setters only on change.
      const double t_mid = (static_cast<double>(i) - 0.5) / rate;
      const double speed = scenario_.ring_speed_at(t_mid);
      if (speed != dynamics.ring_speed_rad_s()) dynamics.set_ring_speed(speed);
      const Vector5 load = scenario_.load_at(t_mid);
      if (load != dynamics.load()) dynamics.set_load(load);
    }
    const SampleSource::Sample sample = source.next();
    if (sample.diverged) ++stats.divergences;
    const bool full = ideal_assembler.add(sample.index, *sample.state);
    bool measured = true;
    double measured_x = sample.state->acceleration[0];
    if (sensor) {
      Eigen::Vector3d y;
      measured = sensor->push(*sample.state, &y);
      if (measured) {
        measured_x = y[0];
        if (measured_assembler->add(measured_assembler->next_sample(), y, sample.state->displacement)) emit_measured();
      }
    }
    if (measured) {
      level_rms.add(measured_x);
      if (health) health_samples.push_back(static_cast<float>(measured_x));
    }
    if (level_divider.due(sample.index)) {
      SinkTimer t(&stats.sink_cpu_s);
      for (DatasetSink* s : sinks)
        s->level(sample.index, level_rms.rms(), static_cast<double>(level_rms.size()) / info_.measured_rate_hz);
    }
    if (want_balls && ball_divider.due(sample.index)) {
      SinkTimer t(&stats.sink_cpu_s);
      const std::vector<BallState> balls =
          dynamics.model().ball_states(sample.state->displacement, sample.state->cage_angle_rad);
      for (DatasetSink* s : sinks)
        s->ball_loads(sample.index, balls, dynamics.model().rows(), dynamics.model().balls_per_row(),
                      sample.state->cage_angle_rad);
    }
    if (sample.index % label_period_ == 0) {
      SinkTimer t(&stats.sink_cpu_s);
      const LabelState label = scenario_label(scenario_, sample.index, rate);
      for (DatasetSink* s : sinks) s->label(label);
    }
    if (health && health_divider.due(sample.index)) {
      health->push(health_samples.data(), health_samples.size());
      health_samples.clear();
      ros_node::HealthReport report;
      {
        SinkTimer t(&stats.health_cpu_s);
        report = health->analyze_now(sample.time_s);
      }
      SinkTimer t(&stats.sink_cpu_s);
      for (DatasetSink* s : sinks) s->health(report);
    }
    if (full || i + 1 == n) {  // the last chunk may be short
      SampleChunk chunk = ideal_assembler.take();
      const double chunk_s = static_cast<double>(chunk.size()) / rate;
      {
        SinkTimer t(&stats.sink_cpu_s);
        for (DatasetSink* s : sinks) {
          s->ideal_chunk(chunk);
          if (!sensor) s->measured_chunk(chunk);
        }
      }
      if (health) {
        health->push(health_samples.data(), health_samples.size());
        health_samples.clear();
        health->add_operation(dynamics.load(), dynamics.ring_speed_rad_s(), chunk_s);
      }
      if (progress) progress(static_cast<double>(i + 1) / rate);
    }
  }
  if (sensor && measured_assembler->next_sample() > measured_emitted) emit_measured();  // the short last chunk
  for (DatasetSink* s : sinks) {
    SinkTimer t(&stats.sink_cpu_s);
    s->end();
  }
  stats.simulated_s = static_cast<double>(n) / rate;
  stats.ideal_samples = n;
  stats.measured_samples = sensor ? measured_assembler->next_sample() : n;
  stats.divergences = source.divergence_count();
  stats.cpu_s = thread_cpu_s() - cpu_start;
  return stats;
}

}  // namespace bearing_sim::tool
