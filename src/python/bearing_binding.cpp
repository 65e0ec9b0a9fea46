// Bearing: a loaded bearing file with its static equilibrium, stiffness, frequencies and
// a fixed-input dynamic run (the core's run_simulation, as `bearing_tool simulate`).
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <sstream>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/ring_dynamics.hpp"
#include "bearing_sim/core/simulation_run.hpp"
#include "binding_common.hpp"

namespace bearing_sim::python {
namespace {

py::dict frequencies_dict(const BearingFrequencies& f) {
  py::dict d;
  d["cage_hz"] = f.cage_hz;
  d["ball_pass_outer_race_hz"] = f.ball_pass_outer_race_hz;
  d["ball_pass_inner_race_hz"] = f.ball_pass_inner_race_hz;
  d["ball_spin_hz"] = f.ball_spin_hz;
  d["relative_ring_hz"] = f.relative_ring_hz;
  d["varying_compliance_hz"] = f.varying_compliance_hz;
  return d;
}

py::dict static_dict(const StaticSolution& s) {
  py::dict d;
  d["displacement"] = to_numpy(s.displacement);
  d["stiffness"] = to_numpy(s.stiffness);
  d["max_ball_load_N"] = s.max_ball_load_N;
  d["max_contact_pressure_Pa"] = s.max_contact_pressure_Pa;
  d["exceeds_permissible_pressure"] = s.exceeds_permissible_pressure();
  d["residual_norm_N"] = s.residual_norm;
  d["iterations"] = s.iterations;
  const auto n = static_cast<py::ssize_t>(s.balls.size());
  py::array_t<double> load(n), azimuth(n), angle(n), pressure(n);
  py::array_t<int> row(n);
  py::array_t<double> normal({n, py::ssize_t{3}});
  for (py::ssize_t i = 0; i < n; ++i) {
    const BallState& b = s.balls[static_cast<std::size_t>(i)];
    for (int k = 0; k < 3; ++k) normal.mutable_at(i, k) = b.normal[k];
    load.mutable_at(i) = b.load_N;
    azimuth.mutable_at(i) = b.azimuth_rad;
    angle.mutable_at(i) = b.contact_angle_rad;
    pressure.mutable_at(i) = b.pressure_Pa;
    row.mutable_at(i) = b.row;
  }
  d["ball_load_N"] = load;
  d["ball_azimuth_rad"] = azimuth;
  d["ball_contact_angle_rad"] = angle;
  d["ball_pressure_Pa"] = pressure;
  d["ball_row"] = row;
  d["ball_normal"] = normal;  // contact line, inner to outer
  return d;
}

std::string duration_text(double s) {
  std::ostringstream o;
  o.precision(3);
  if (s >= 86400.0 * 365.0) o << s / (86400.0 * 365.0) << " years";
  else if (s >= 86400.0) o << s / 86400.0 << " days";
  else if (s >= 3600.0) o << s / 3600.0 << " hours";
  else if (s >= 60.0) o << s / 60.0 << " minutes";
  else o << s << " s";
  return o.str();
}

}  // namespace

double probe_seconds_per_sample(const BearingModel& model, const Vector5& load, double ring_speed_rad_s,
                                double sample_rate_hz, int substeps, IntegrationMethod method) {
  using Clock = std::chrono::steady_clock;
  try {
    const std::unique_ptr<RingDynamics> dynamics =
        make_ring_dynamics(model, load, ring_speed_rad_s, DynamicsOptions{sample_rate_hz, substeps, true, method});
    const Clock::time_point start = Clock::now();
    int n = 0;
    double elapsed = 0.0;
    while (n < 200 && elapsed < 0.2) {
      try {
        dynamics->step();
      } catch (const DivergenceError&) {
        dynamics->reset_to_equilibrium();
      }
      ++n;
      elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    }
    return elapsed / n;
  } catch (const LoadNotCarriedError&) {
    return 0.0;
  }
}

void check_long_run(double samples, double seconds_per_sample, bool allow_long_run, const std::string& what) {
  const double estimate_s = samples * seconds_per_sample;
  if (!(estimate_s > kAnnounceRunS)) return;
  std::ostringstream text;
  text.precision(4);
  text << what << ": " << samples << " samples at the ";
  text.precision(3);
  text << seconds_per_sample * 1e6 << " us per sample measured on this machine: about " << duration_text(estimate_s);
  if (estimate_s > kLongRunLimitS && !allow_long_run)
    throw InvalidInputError(text.str() + ", more than " + duration_text(kLongRunLimitS) +
                            " (the limit of bearing_tool without --allow-long-run); give allow_long_run=True "
                            "to start it anyway");
  if (PyErr_WarnEx(PyExc_UserWarning, text.str().c_str(), 1) != 0) throw py::error_already_set();
}

void bind_bearing(py::module_& m) {
  py::class_<PyBearing>(m, "Bearing", "A bearing file (docs/bearing_file.md), loaded and validated")
      .def_static(
          "from_file",
          [](const std::string& path) {
            return PyBearing{std::make_shared<const BearingModel>(load_bearing_config(path)), path};
          },
          py::arg("path"), "Loads a bearing file; ConfigError names the file and the key")
      .def_static(
          "from_yaml",
          [](const std::string& text, const std::string& source) {
            return PyBearing{std::make_shared<const BearingModel>(bearing_config_from_string(text, source)), source};
          },
          py::arg("text"), py::arg("source") = "<string>", "A bearing file's text; `source` names it in errors")
      .def_property_readonly("name", [](const PyBearing& b) { return b.model->config().name; })
      .def_property_readonly("source", [](const PyBearing& b) { return b.source; })
      .def_property_readonly("rows", [](const PyBearing& b) { return b.model->rows(); })
      .def_property_readonly("balls_per_row", [](const PyBearing& b) { return b.model->balls_per_row(); })
      .def_property_readonly("ball_diameter_m", [](const PyBearing& b) { return b.model->config().ball_diameter_m; })
      .def_property_readonly("pitch_diameter_m", [](const PyBearing& b) { return b.model->config().pitch_diameter_m; })
      .def_property_readonly("contact_angle_rad",
                             [](const PyBearing& b) { return b.model->config().contact_angle_rad; })
      .def_property_readonly(
          "rotating_ring",
          [](const PyBearing& b) { return b.model->config().rotating_ring == RotatingRing::Outer ? "outer" : "inner"; })
      .def_property_readonly("has_dynamics", [](const PyBearing& b) { return b.model->config().has_dynamics(); })
      .def_property_readonly("mass_matrix", [](const PyBearing& b) { return to_numpy(b.model->mass_matrix()); })
      .def(
          "static",
          [](const PyBearing& b, const std::vector<double>& force, const std::vector<double>& moment,
             double cage_angle_rad) {
            const Vector5 load = make_load(force, moment);
            StaticSolution s;
            {
              py::gil_scoped_release release;
              s = solve_static(*b.model, load, cage_angle_rad);
            }
            return static_dict(s);
          },
          py::arg("force_N") = std::vector<double>{0.0, 0.0, 0.0}, py::arg("moment_Nm") = std::vector<double>{0.0, 0.0},
          py::arg("cage_angle_rad") = 0.0,
          "Static equilibrium of the moving ring under (Fx, Fy, Fz) N and (Mx, My) N*m: displacement "
          "(x, y, z, theta_x, theta_y), the 5x5 stiffness and every ball's load")
      .def(
          "frequencies",
          [](const PyBearing& b, double ring_speed_rad_s) {
            return frequencies_dict(bearing_frequencies(*b.model, ring_speed_rad_s));
          },
          py::arg("ring_speed_rad_s"), "Fault frequencies for a speed of the configured rotating ring")
      .def(
          "frequencies_of_rings",
          [](const PyBearing& b, double inner_rad_s, double outer_rad_s) {
            return frequencies_dict(bearing_frequencies(*b.model, inner_rad_s, outer_rad_s));
          },
          py::arg("inner_rad_s"), py::arg("outer_rad_s"), "Fault frequencies for both ring speeds")
      .def(
          "simulate",
          [](const PyBearing& b, const std::vector<double>& force, double ring_speed_rad_s,
             const std::vector<double>& moment, double duration_s, double sample_rate_hz, int substeps,
             const std::string& integrator, bool allow_long_run) {
            SimulationRequest r;
            r.load = make_load(force, moment);
            r.ring_speed_rad_s = ring_speed_rad_s;
            r.duration_s = duration_s;
            r.sample_rate_hz = sample_rate_hz;
            r.substeps = substeps;
            const std::optional<IntegrationMethod> method = integration_method_from_name(integrator);
            if (!method) {
              std::string names;
              for (const std::string& n : integration_method_names()) names += (names.empty() ? "" : ", ") + n;
              throw InvalidInputError("integrator \"" + integrator + "\": must be one of " + names);
            }
            r.method = *method;
            if (!(duration_s > 0.0) || !std::isfinite(duration_s)) throw InvalidInputError("duration_s must be > 0");
            if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz))
              throw InvalidInputError("sample_rate_hz must be > 0");
            if (sample_rate_hz > kMaxSampleRateHz) {
              std::ostringstream text;
              text << "sample_rate_hz " << sample_rate_hz << ": at most " << kMaxSampleRateHz
                   << " Hz (as bearing_tool simulate --rate and a scenario's sample_rate_hz)";
              throw InvalidInputError(text.str());
            }
            if (substeps < 0) throw InvalidInputError("substeps must be >= 0 (0: automatic)");
            // The CLI's rules (bearing_tool simulate): a probe for runs over 1000 samples of a
            // bearing with dynamics; the core refuses a run of fewer than 4 or over 1e9 samples.
            const double samples = std::round(duration_s * sample_rate_hz);
            if (samples > 1000.0 && samples <= 1e9 && b.model->config().has_dynamics()) {
              double per_sample = 0.0;
              {
                py::gil_scoped_release release;
                per_sample =
                    probe_seconds_per_sample(*b.model, r.load, ring_speed_rad_s, sample_rate_hz, substeps, r.method);
              }
              check_long_run(samples, per_sample, allow_long_run, "bearing_sim.simulate");
            }
            std::vector<double> time, displacement, acceleration;
            SimulationSummary s;
            SignalCheck signals;
            try {
              py::gil_scoped_release release;
              s = run_simulation(*b.model, r, [&](const DynamicSample& x) {
                time.push_back(x.time_s);
                displacement.insert(displacement.end(), x.displacement.data(), x.displacement.data() + 5);
                acceleration.insert(acceleration.end(), x.acceleration.data(), x.acceleration.data() + 5);
                signals.poll();
              });
            } catch (const SignalCheck::Interrupted&) {
              throw py::error_already_set();
            }
            const auto n = static_cast<py::ssize_t>(time.size());
            py::dict d;
            d["time_s"] = py::array_t<double>(n, time.data());
            d["displacement"] = py::array_t<double>({n, py::ssize_t{5}}, displacement.data());
            d["acceleration"] = py::array_t<double>({n, py::ssize_t{5}}, acceleration.data());
            d["integrator"] = integrator;
            d["substeps"] = s.substeps;
            d["internal_step_s"] = s.internal_step_s;
            d["a_rms"] = py::make_tuple(s.a_rms_x, s.a_rms_y, s.a_rms_z);
            d["level_db"] = s.level_db;
            d["mean_displacement"] = to_numpy(s.mean_displacement);
            d["realtime_factor"] = s.realtime_factor;
            return d;
          },
          py::arg("force_N"), py::arg("ring_speed_rad_s"), py::arg("moment_Nm") = std::vector<double>{0.0, 0.0},
          py::arg("duration_s") = 1.0, py::arg("sample_rate_hz") = 10000.0, py::arg("substeps") = 0,
          py::arg("integrator") = std::string(integration_method_name(kDefaultIntegrationMethod)),
          py::arg("allow_long_run") = false,
          "Dynamic run at a fixed load and speed from the static equilibrium (the GIL is released, Ctrl-C "
          "stops it within ~0.1 s): time_s, displacement and acceleration (samples x 5) and the summary of "
          "`bearing_tool simulate`. sample_rate_hz at most 1e6; a run estimated over an hour needs "
          "allow_long_run=True (--allow-long-run)")
      .def("__repr__", [](const PyBearing& b) {
        return "<bearing_sim.Bearing '" + b.model->config().name + "' from " + b.source + ">";
      });
}

}  // namespace bearing_sim::python
