// bearing_tool simulate: a fixed-load, fixed-speed run of the dynamic model from the
// static equilibrium (docs/model.md section 7), with an optional streamed CSV of the samples.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/simd_info.hpp"
#include "bearing_sim/core/simulation_run.hpp"
#include "commands.hpp"
#include "flexible_ring_report.hpp"
#include "job_size.hpp"
#include "output_size.hpp"
#include "output_space.hpp"
#include "simulated_sensor.hpp"
#include "tool_common.hpp"

namespace bearing_sim::tool {
namespace {

struct SimulateOptions {
  double ring_temperature_difference_K = 0.0;
  std::string bearing;
  std::vector<double> force{0.0, 0.0, 0.0};
  std::vector<double> moment{0.0, 0.0};
  double outer_rpm = 0.0;
  double inner_rpm = 0.0;
  double duration_s = 1.0;
  double rate_hz = 10000.0;
  int substeps = 0;
  std::string integrator = integration_method_name(kDefaultIntegrationMethod);
  std::string csv;
  std::string sensor;
  std::string sensor_csv;
  bool json = false;
  bool allow_long_run = false;
};

const char* const kCsvHeader =
    "time_s,x_m,y_m,z_m,theta_x_rad,theta_y_rad,"
    "ax_m_s2,ay_m_s2,az_m_s2,alpha_x_rad_s2,alpha_y_rad_s2";

// Streams one line per sample; the file is closed (and checked) by close().
class CsvWriter {
 public:
  explicit CsvWriter(const std::string& path) : path_(path), file_(std::fopen(path.c_str(), "w")) {
    if (!file_) throw InputError("--csv: cannot open '" + path + "' for writing: " + std::strerror(errno));
    std::fprintf(file_, "%s\n", kCsvHeader);
  }
  ~CsvWriter() {
    if (file_) std::fclose(file_);
  }
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  void write(const DynamicSample& s) {
    std::fprintf(file_, "%.12g", s.time_s);
    for (int i = 0; i < 5; ++i) std::fprintf(file_, ",%.10e", s.displacement[i]);
    for (int i = 0; i < 5; ++i) std::fprintf(file_, ",%.10e", s.acceleration[i]);
    std::fputc('\n', file_);
  }
  void close() {
    const bool failed = std::ferror(file_) != 0;
    const bool close_failed = std::fclose(file_) != 0;
    file_ = nullptr;
    if (failed || close_failed) throw std::runtime_error("--csv: error writing '" + path_ + "'");
  }

 private:
  std::string path_;
  std::FILE* file_;
};

// The speed of the configured rotating ring; the other ring must be still.
double rotating_ring_speed_rad_s(const BearingModel& model, const SimulateOptions& o) {
  const bool outer = model.config().rotating_ring == RotatingRing::Outer;
  const double fixed_rpm = outer ? o.inner_rpm : o.outer_rpm;
  if (fixed_rpm != 0.0) {
    throw InputError(std::string("--") + (outer ? "inner" : "outer") + "-rpm " + general(fixed_rpm, 6) +
                     ": the bearing file '" + o.bearing + "' has rotating_ring: " + rotating_ring_name(model) +
                     ", and the dynamic model holds the " + (outer ? "inner" : "outer") +
                     " ring fixed; give its speed as 0 (bearing_tool frequencies accepts both speeds)");
  }
  return rpm_to_rad_s(outer ? o.outer_rpm : o.inner_rpm);
}

// The number of samples, checked here to name the options (the core refuses the same runs).
double checked_sample_count(const SimulateOptions& o) {
  const double samples = std::round(o.duration_s * o.rate_hz);
  const std::string run = "--duration " + general(o.duration_s, 6) + " s at --rate " + general(o.rate_hz, 6) + " Hz";
  if (samples < 4.0) throw InputError(run + ": " + general(samples, 6) + " samples; a run holds at least 4");
  if (samples > 1e9) throw InputError(run + ": " + general(samples, 4) + " samples; a run holds at most 1e9");
  return samples;
}

void run(const SimulateOptions& o) {
  const double samples = checked_sample_count(o);
  const BearingModel model = load_model(o.bearing, o.ring_temperature_difference_K);
  const Vector5 load = make_load(o.force, o.moment);
  SimulationRequest request;
  request.load = load;
  request.ring_speed_rad_s = rotating_ring_speed_rad_s(model, o);
  request.duration_s = o.duration_s;
  request.sample_rate_hz = o.rate_hz;
  request.substeps = o.substeps;
  request.method = *integration_method_from_name(o.integrator);  // CLI11 checked the name
  if (model.config().flexible_ring.present) {
    // The flexible-ring model: its own integrators and report (docs/model.md section 18).
    if (!o.sensor.empty() || !o.sensor_csv.empty())
      throw InputError("--sensor: not available with a flexible ring (key 'flexible_ring' of " + o.bearing + ")");
    if (request.method != IntegrationMethod::ExponentialAdamsPec && request.method != IntegrationMethod::Rk4)
      throw InputError("--integrator " + o.integrator + ": a flexible ring is integrated by adams_pec or rk4");
    FlexibleSimulationRequest r;
    r.bearing_path = o.bearing;
    r.load = load;
    r.ring_speed_rad_s = request.ring_speed_rad_s;
    r.ring_speed_rpm = model.config().rotating_ring == RotatingRing::Outer ? o.outer_rpm : o.inner_rpm;
    r.duration_s = o.duration_s;
    r.rate_hz = o.rate_hz;
    r.substeps = o.substeps;
    r.method = request.method;
    r.csv = o.csv;
    r.json = o.json;
    r.allow_long_run = o.allow_long_run;
    run_flexible_simulation(model, r);
    return;
  }

  // The static equilibrium the run starts from (also reported, for comparison with the mean).
  const StaticSolution equilibrium = solve_static(model, load);
  if (model.config().has_dynamics()) {
    if (o.substeps == 0) check_integrator_work(model, load, o.rate_hz, o.bearing, request.method);
    // Short runs cannot take a minute.
    if (samples > 1000.0) {
      const double per_sample =
          measure_seconds_per_sample(model, load, request.ring_speed_rad_s, o.rate_hz, o.substeps, request.method);
      check_job_size(samples, samples * per_sample, o.allow_long_run, "simulate", "--allow-long-run");
    }
  }

  if (!o.sensor_csv.empty() && o.sensor.empty()) throw InputError("--sensor-csv needs --sensor FILE");
  std::unique_ptr<SimulatedSensor> sensor;
  // The sensor's statistics over the summary's window: the second half of the samples.
  if (!o.sensor.empty())
    sensor = std::make_unique<SimulatedSensor>(o.sensor, o.rate_hz, static_cast<std::size_t>(samples) / 2);
  // The files' size against the free space (after the wall time).
  std::vector<PlannedOutput> outputs;
  if (!o.csv.empty())
    outputs.push_back({"--csv '" + o.csv + "'", o.csv,
                       time_series_csv_bytes(samples, 10, static_cast<double>(std::strlen(kCsvHeader) + 1))});
  if (!o.sensor_csv.empty())
    outputs.push_back({"--sensor-csv '" + o.sensor_csv + "'", o.sensor_csv, sensor->csv_bytes(samples, o.rate_hz)});
  check_output_space(outputs);
  if (!o.sensor_csv.empty()) sensor->write_csv(o.sensor_csv);
  std::unique_ptr<CsvWriter> csv;
  if (!o.csv.empty()) csv = std::make_unique<CsvWriter>(o.csv);
  std::function<void(const DynamicSample&)> on_sample;
  if (csv || sensor)
    on_sample = [&csv, &sensor](const DynamicSample& s) {
      if (csv) csv->write(s);
      if (sensor) sensor->push(s);
    };
  const SimulationSummary s = run_simulation(model, request, on_sample);
  if (csv) csv->close();
  if (sensor) sensor->finish();

  const BearingFrequencies f = bearing_frequencies(model, request.ring_speed_rad_s);
  const nlohmann::json result = {
      {"bearing", bearing_json(model, o.bearing)},
      {"load", to_json(load)},
      {"ring_speed_rpm", model.config().rotating_ring == RotatingRing::Outer ? o.outer_rpm : o.inner_rpm},
      {"duration_s", o.duration_s},
      {"rate_hz", o.rate_hz},
      {"samples", s.samples},
      {"integrator", o.integrator},
      {"substeps", s.substeps},
      {"internal_step_s", s.internal_step_s},
      {"window", "second half of the run, mean removed"},
      {"a_rms_x", s.a_rms_x},
      {"a_rms_y", s.a_rms_y},
      {"a_rms_z", s.a_rms_z},
      {"L_dB", s.level_db},  // -infinity (a perfectly still ring) is written as null
      {"mean_displacement", to_json(s.mean_displacement)},
      {"static_displacement", to_json(equilibrium.displacement)},
      {"varying_compliance_hz", f.varying_compliance_hz},
      {"realtime_factor", s.realtime_factor},
      // The realtime factor depends on these: the CPU and the kernel's SIMD target.
      {"cpu", cpu_model_name()},
      {"simd_target", simd_target_name()},
      {"csv", o.csv.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.csv)},
      // null: the ideal ring acceleration only, which no real sensor measures.
      {"sensor", sensor ? sensor->to_json() : nlohmann::json(nullptr)}};
  // L is -inf for a ring at rest (written as null); the realtime factor of a tiny run may be inf.
  require_finite_result(result, "simulate", {"L_dB", "realtime_factor"});
  if (o.json) {
    print_json(result);
    return;
  }

  std::ostream& out = std::cout;
  const auto& c = model.config();
  out << "Bearing: " << c.name << " (" << o.bearing << "), rotating ring: " << rotating_ring_name(model) << " at "
      << general(model.config().rotating_ring == RotatingRing::Outer ? o.outer_rpm : o.inner_rpm, 6) << " rpm\n"
      << "Load: Fx=" << general(load[0], 6) << " N, Fy=" << general(load[1], 6) << " N, Fz=" << general(load[2], 6)
      << " N, Mx=" << general(load[3], 6) << " N*m, My=" << general(load[4], 6) << " N*m\n\n";
  KeyValueList run_info;
  run_info.add("samples",
               std::to_string(s.samples) + " at " + general(o.rate_hz, 6) + " Hz (" + general(o.duration_s, 6) + " s)");
  run_info.add("integration", general(s.substeps, 4) + " " + o.integrator + " steps per sample, step " +
                                  general(s.internal_step_s * 1e6, 4) + " us");
  run_info.add("realtime factor", general(s.realtime_factor, 4) + " (simulated s per wall s, " + cpu_model_name() +
                                      ", SIMD " + simd_target_name() + ")");
  run_info.add("varying compliance", fixed(f.varying_compliance_hz, 3) + " Hz");
  if (csv) run_info.add("CSV", o.csv);
  run_info.print(out);

  out << "\nVibration (second half of the run, mean removed)\n";
  Table v({"quantity", "value", "unit"}, {true, false, true});
  v.add_row({"a_rms x", scientific(s.a_rms_x, 4), "m/s^2"});
  v.add_row({"a_rms y", scientific(s.a_rms_y, 4), "m/s^2"});
  v.add_row({"a_rms z", scientific(s.a_rms_z, 4), "m/s^2"});
  v.add_row({"L (x, JB/T 5314, a0 = 9.81e-3 m/s^2)", fixed(s.level_db, 2), "dB"});
  v.print(out);

  if (sensor) {
    out << "\nSensor '" << o.sensor << "' (" << general(sensor->output_rate_hz(), 6)
        << " Hz, second half of the run, mean removed)\n";
    Table t({"axis", "rms", "crest factor", "kurtosis", "unit"}, {true, false, false, false, true});
    static const char* const axes[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
      const SignalStatistics st = sensor->statistics()[a].statistics();
      t.add_row({axes[a], scientific(st.rms, 4), fixed(st.crest_factor, 2), fixed(st.kurtosis, 2), sensor->unit()});
    }
    t.print(out);
  } else {
    out << "\nNo sensor (--sensor FILE): the ideal ring acceleration above has no noise, no transfer path and\n"
           "no anti-alias filter, so it is no healthy reference for a condition-monitoring analysis.\n";
  }

  out << "\nDisplacement (second half of the run)\n";
  static const char* const names[5] = {"x", "y", "z", "theta_x", "theta_y"};
  Table d({"dof", "mean", "static", "unit"}, {true, false, false, true});
  for (int i = 0; i < 5; ++i)
    d.add_row({names[i], fixed(s.mean_displacement[i] * 1e6, 4), fixed(equilibrium.displacement[i] * 1e6, 4),
               i >= 3 ? "urad" : "um"});
  d.print(out);
}

}  // namespace

void register_simulate_command(CLI::App& app) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* cmd =
      app.add_subcommand("simulate",
                         "Dynamic run from the static equilibrium at a fixed load and ring speed: RMS acceleration, "
                         "vibration level L, mean displacement; optional CSV of every sample");
  add_bearing_option(cmd, &o->bearing);
  add_load_options(cmd, &o->force, &o->moment);
  add_ring_temperature_option(cmd, &o->ring_temperature_difference_K,
                              "Inner minus outer ring temperature, K: changes the clearance (docs/model.md 3.7)");
  add_number_option(cmd, "--outer-rpm", &o->outer_rpm, "RPM",
                    "Outer ring speed, rpm (must be 0 unless the file has rotating_ring: outer)");
  add_number_option(cmd, "--inner-rpm", &o->inner_rpm, "RPM",
                    "Inner ring speed, rpm (must be 0 unless the file has rotating_ring: inner)");
  add_number_option(cmd, "--duration", &o->duration_s, "S", "Simulated time, s")->check(positive_number());
  add_number_option(cmd, "--rate", &o->rate_hz, "HZ", "Output sample rate, Hz (not the integration step), at most 1e6")
      ->check(positive_number() & CLI::Range(0.0, kMaxSampleRateHz));
  cmd->add_option("--integrator", o->integrator,
                  "Integrator (docs/model.md, section 10): adams_pec (1 force evaluation per step), adams_pece (2), "
                  "etdrk4 (4) or rk4 (4, smaller steps)")
      ->type_name("NAME")
      ->check(CLI::IsMember(integration_method_names()))
      ->capture_default_str();
  // At most the node's 1000: a short run of 1e9 steps per sample went on for hours unannounced.
  cmd->add_option("--substeps", o->substeps, "Internal integrator steps per sample, at most 1000 (0: automatic)")
      ->type_name("N")
      ->check(CLI::Range(0, 1000))
      ->capture_default_str();
  cmd->add_option("--csv", o->csv,
                  "Write every sample to this CSV file: time, displacements (5) and accelerations (5), "
                  "header line with units")
      ->type_name("FILE");
  cmd->add_option("--sensor", o->sensor,
                  "Pass the samples through this virtual accelerometer (a sensor file, docs/sensor.md: transfer "
                  "path, anti-alias filter, noise, ADC) and report its output's RMS, crest factor and kurtosis")
      ->type_name("FILE");
  cmd->add_option("--sensor-csv", o->sensor_csv,
                  "With --sensor: write every sensor sample to this CSV file (time, x, y, z in the sensor's unit)")
      ->type_name("FILE");
  cmd->add_flag("--allow-long-run", o->allow_long_run,
                "Start a run estimated (from a short probe) to take over an hour of wall time");
  add_json_flag(cmd, &o->json);
  cmd->callback([o] { run(*o); });
}

}  // namespace bearing_sim::tool
