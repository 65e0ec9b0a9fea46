// Scenario generation into numpy arrays: the run of `bearing_tool generate` (the same
// ScenarioSimulation, so the same samples to the bit) into an in-memory sink.
#include <pybind11/stl.h>

#include <optional>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/scenario.hpp"
#include "bearing_sim/runtime/scenario_simulation.hpp"
#include "binding_common.hpp"

namespace bearing_sim::python {
namespace {

// Keeps what a dataset writer would write: both vibration channels and the labels.
class MemorySink : public runtime::DatasetSink {
 public:
  void begin(const runtime::DatasetInfo& info) override {
    measured_.reserve(3 * info.measured_samples);
    ideal_.reserve(3 * info.ideal_samples);
  }
  void ideal_chunk(const runtime::SampleChunk& c) override { append(ideal_, c); }
  void measured_chunk(const runtime::SampleChunk& c) override { append(measured_, c); }
  void label(const runtime::LabelState& s) override { labels_.push_back(s); }
  void end() override {}

  std::vector<float> measured_, ideal_;
  std::vector<runtime::LabelState> labels_;

 private:
  static void append(std::vector<float>& out, const runtime::SampleChunk& c) {
    for (std::size_t i = 0; i < c.size(); ++i) {
      out.push_back(c.accel_x[i]);
      out.push_back(c.accel_y[i]);
      out.push_back(c.accel_z[i]);
    }
  }
};

py::array_t<float> rows3(const std::vector<float>& v) {
  return py::array_t<float>({static_cast<py::ssize_t>(v.size() / 3), py::ssize_t{3}}, v.data());
}

py::dict info_dict(const runtime::DatasetInfo& i) {
  py::dict d;
  d["scenario"] = i.scenario;
  d["description"] = i.description;
  d["bearing_name"] = i.bearing_name;
  d["bearing_file"] = i.bearing_file;
  d["sensor_name"] = i.sensor_name;
  d["sensor_file"] = i.sensor_file;
  d["sensor_unit"] = i.sensor_unit;
  d["seed"] = i.seed;
  d["duration_s"] = i.duration_s;
  d["sample_rate_hz"] = i.sample_rate_hz;
  d["measured_rate_hz"] = i.measured_rate_hz;
  d["decimation_ratio"] = i.decimation_ratio;
  d["ideal_samples"] = i.ideal_samples;
  d["measured_samples"] = i.measured_samples;
  d["label_rate_hz"] = i.label_rate_hz;
  d["simd_target"] = i.simd_target;
  return d;
}

py::dict labels_dict(const std::vector<runtime::LabelState>& labels) {
  const auto n = static_cast<py::ssize_t>(labels.size());
  py::array_t<double> time(n), speed(n), angle(n), load({n, py::ssize_t{5}});
  py::list phase, defects;
  for (py::ssize_t k = 0; k < n; ++k) {
    const runtime::LabelState& s = labels[static_cast<std::size_t>(k)];
    time.mutable_at(k) = s.time_s;
    speed.mutable_at(k) = s.inputs.ring_speed_rad_s;
    angle.mutable_at(k) = s.inputs.ring_angle_rad;
    for (int j = 0; j < 5; ++j) load.mutable_at(k, j) = s.inputs.load[j];
    phase.append(s.inputs.phase);
    py::list now;
    for (const runtime::DefectNow& d : s.defects) {
      py::dict e;
      e["surface"] = surface_name(d.spall.surface);
      e["position_rad"] = d.spall.position_rad;
      e["ball"] = d.spall.surface == Surface::Ball ? d.spall.ball : -1;
      e["row"] = d.spall.surface == Surface::Ball ? -1 : d.spall.row;
      e["width_m"] = d.width_m;
      e["depth_m"] = d.depth_m;
      e["age_s"] = d.age_s;
      now.append(e);
    }
    defects.append(now);
  }
  py::dict d;
  d["time_s"] = time;
  d["ring_speed_rad_s"] = speed;
  d["ring_angle_rad"] = angle;
  d["load"] = load;
  d["phase"] = phase;
  d["defects"] = defects;
  return d;
}

// `text` None: the file `source`, read as bearing_tool generate reads it (a regular file of at
// most 1 MiB; what is not YAML is a ConfigError naming it).
py::dict generate(const std::optional<std::string>& text, const std::string& source, std::optional<std::uint64_t> seed,
                  std::optional<double> duration_s, double label_rate_hz, bool allow_long_run) {
  runtime::GenerateSettings settings;
  settings.seed = seed;
  settings.duration_s = duration_s;
  settings.label_rate_hz = label_rate_hz;
  settings.health_rate_hz = 0.0;  // the memory sink takes no health reports
  MemorySink sink;
  runtime::RunStats stats;
  std::optional<runtime::ScenarioSimulation> simulation;
  double samples = 0.0, per_sample = 0.0;
  {
    py::gil_scoped_release release;
    simulation.emplace(text ? Scenario::from_string(*text, source) : Scenario::load(source), source, settings);
    // bearing_tool generate's estimate: the dynamics alone at half time, for runs over 1000 samples
    // (the duration is at most kMaxScenarioDurationS, checked by ScenarioSimulation).
    const Scenario& sc = simulation->scenario();
    const runtime::DatasetInfo& info = simulation->info();
    samples = static_cast<double>(info.ideal_samples);
    if (samples > 1000.0) {
      const BearingModel model(load_bearing_config(sc.bearing_file()));
      const double t = 0.5 * info.duration_s;
      per_sample = probe_seconds_per_sample(model, sc.load_at(t), sc.ring_speed_at(t), info.sample_rate_hz, 0,
                                            kDefaultIntegrationMethod);
    }
  }
  check_long_run(samples, per_sample, allow_long_run, "bearing_sim.generate");
  SignalCheck signals;
  try {
    py::gil_scoped_release release;
    stats = simulation->run({&sink}, [&signals](double) { signals.poll(); });
  } catch (const SignalCheck::Interrupted&) {
    throw py::error_already_set();
  }
  py::dict d;
  d["vibration"] = rows3(sink.measured_);
  d["vibration_ideal"] = rows3(sink.ideal_);
  d["labels"] = labels_dict(sink.labels_);
  d["info"] = info_dict(simulation->info());
  d["cpu_s"] = stats.cpu_s;
  d["divergences"] = stats.divergences;
  return d;
}

py::dict check(const std::string& text, const std::string& source) {
  std::optional<runtime::ScenarioSimulation> simulation;
  {
    py::gil_scoped_release release;
    simulation.emplace(Scenario::from_string(text, source), source, runtime::GenerateSettings{});
  }
  return info_dict(simulation->info());
}

}  // namespace

void bind_scenario(py::module_& m) {
  m.def("generate_from_yaml", &generate, py::arg("text"), py::arg("source"), py::arg("seed") = py::none(),
        py::arg("duration_s") = py::none(), py::arg("label_rate_hz") = 10.0, py::arg("allow_long_run") = false,
        "Runs a scenario given as YAML text, or the file `source` when text is None (docs/scenarios.md), as "
        "`bearing_tool generate` does; relative "
        "bearing and sensor files resolve against the directory of `source`. The GIL is released, Ctrl-C "
        "stops the run within ~0.1 s. duration_s at most 1e7 s; a run estimated over an hour needs "
        "allow_long_run=True (--allow-long-run). Returns vibration (measured, float32 samples x 3), "
        "vibration_ideal, labels, info");
  m.def("check_scenario", &check, py::arg("text"), py::arg("source"),
        "Loads a scenario with its bearing and sensor without running it (ConfigError naming the key); "
        "returns its info");
}

}  // namespace bearing_sim::python
