#include "flexible_ring_report.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <vector>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/flexible_dynamics.hpp"
#include "bearing_sim/core/vibration_level.hpp"
#include "job_size.hpp"
#include "output_size.hpp"
#include "output_space.hpp"
#include "tool_common.hpp"

namespace bearing_sim::tool {
namespace {
const char* direction_name(const RingMode& m) {
  return m.direction == RingModeDirection::Radial ? "in_plane" : "out_of_plane";
}

// "ring_in_plane_n2_cos_m" etc.: the CSV column of modal coordinate c.
std::string coordinate_name(const std::vector<RingMode>& modes, int c) {
  const RingMode& m = modes[c / 2];
  return std::string("ring_") + direction_name(m) + "_n" + std::to_string(m.order) + (c % 2 ? "_sin_m" : "_cos_m");
}

}  // namespace

nlohmann::json flexible_ring_static_json(const FlexibleBearing& bearing, const FlexibleStaticSolution& solution,
                                         const StaticSolution& rigid) {
  nlohmann::json modes = nlohmann::json::array();
  const auto& m = bearing.modes();
  for (std::size_t i = 0; i < m.size(); ++i) {
    const double a = solution.coordinates[5 + 2 * i], b = solution.coordinates[6 + 2 * i];
    modes.push_back({{"direction", direction_name(m[i])},
                     {"order", m[i].order},
                     {"frequency_hz", m[i].frequency_rad_s() / kTwoPi},
                     {"modal_mass_kg", m[i].modal_mass_kg},
                     {"modal_stiffness_N_per_m", m[i].stiffness_N_per_m()},
                     {"static_cos_m", a},
                     {"static_sin_m", b},
                     {"static_amplitude_m", std::hypot(a, b)}});
  }
  nlohmann::json natural = nullptr;
  if (bearing.model().config().has_dynamics()) {
    natural = nlohmann::json::array();
    const Eigen::VectorXd w = flexible_natural_frequencies_rad_s(bearing, solution);
    for (int i = 0; i < w.size(); ++i) natural.push_back(w[i] / kTwoPi);
  }
  const double flexible_peak = solution.rigid_coordinates.max_ball_load_N;
  return {{"modes", modes},
          {"natural_frequencies_hz", natural},
          {"max_ball_load_N", flexible_peak},
          {"rigid_ring_max_ball_load_N", rigid.max_ball_load_N},
          {"max_ball_load_change_percent", 100.0 * (flexible_peak / rigid.max_ball_load_N - 1.0)}};
}

void print_flexible_ring_static(const nlohmann::json& ring) {
  std::ostream& out = std::cout;
  out << "\nFlexible ring (docs/model.md section 18): the loads above are with the ring's modes\n";
  KeyValueList k;
  k.add("max ball load", fixed(ring["max_ball_load_N"].get<double>(), 2) + " N, rigid ring " +
                             fixed(ring["rigid_ring_max_ball_load_N"].get<double>(), 2) + " N (" +
                             fixed(ring["max_ball_load_change_percent"].get<double>(), 1) + " %)");
  k.print(out);
  Table t({"mode", "n", "frequency Hz (free, on its seat)", "static amplitude um"}, {true});
  for (const auto& m : ring["modes"])
    t.add_row({m["direction"].get<std::string>(), std::to_string(m["order"].get<int>()),
               fixed(m["frequency_hz"].get<double>(), 1), fixed(m["static_amplitude_m"].get<double>() * 1e6, 4)});
  t.print(out);
  if (!ring["natural_frequencies_hz"].is_null()) {
    out << "\nNatural frequencies on the loaded contacts, ring and rigid-body coordinates together (Hz):\n  ";
    int i = 0;
    for (const auto& f : ring["natural_frequencies_hz"]) out << (i++ ? ", " : "") << fixed(f.get<double>(), 1);
    out << "\n";
  }
}

void run_flexible_simulation(const BearingModel& model, const FlexibleSimulationRequest& r) {
  FlexibleDynamics dynamics(FlexibleBearing(model), r.load, r.ring_speed_rad_s, r.rate_hz, r.substeps, r.method);
  const long samples = std::lround(r.duration_s * r.rate_hz);
  const auto& modes = dynamics.bearing().modes();
  const int n = dynamics.bearing().size();
  std::string csv_header =
      "time_s,x_m,y_m,z_m,theta_x_rad,theta_y_rad,ax_m_s2,ay_m_s2,az_m_s2,alpha_x_rad_s2,alpha_y_rad_s2";
  for (int c = 0; c < n - 5; ++c) csv_header += "," + coordinate_name(modes, c);
  csv_header += "\n";
  // Its cost from a probe on a copy, before anything is written, as the rigid ring's.
  if (samples > 1000) {
    FlexibleDynamics probe = dynamics;
    const double per_sample = measure_seconds_per_step([&probe] { probe.step(); });
    check_job_size(static_cast<double>(samples), static_cast<double>(samples) * per_sample, r.allow_long_run,
                   "simulate", "--allow-long-run");
  }
  // The CSV's size against the free space (after the wall time): the 10 rigid-body columns
  // and the ring's.
  if (!r.csv.empty())
    check_output_space(
        {{"--csv '" + r.csv + "'", r.csv,
          time_series_csv_bytes(static_cast<double>(samples), 10 + (n - 5), static_cast<double>(csv_header.size()))}});
  std::FILE* csv = nullptr;
  if (!r.csv.empty()) {
    csv = std::fopen(r.csv.c_str(), "w");
    if (!csv) throw InputError("--csv: cannot open '" + r.csv + "' for writing: " + std::strerror(errno));
    std::fputs(csv_header.c_str(), csv);
  }
  // Statistics over the second half (as simulate's rigid ring): mean and RMS of the rigid
  // accelerations and of each modal coordinate.
  const long first = samples / 2;
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(n), sum_sq = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd acc_sum = Eigen::VectorXd::Zero(5), acc_sq = Eigen::VectorXd::Zero(5);
  for (long i = 0; i < samples; ++i) {
    const FlexibleSample& s = dynamics.step();
    if (csv) {
      std::fprintf(csv, "%.12g", s.time_s);
      for (int j = 0; j < 5; ++j) std::fprintf(csv, ",%.10e", s.coordinates[j]);
      for (int j = 0; j < 5; ++j) std::fprintf(csv, ",%.10e", s.accelerations[j]);
      for (int j = 5; j < n; ++j) std::fprintf(csv, ",%.10e", s.coordinates[j]);
      std::fputc('\n', csv);
    }
    if (i < first) continue;
    sum += s.coordinates;
    sum_sq += s.coordinates.cwiseAbs2();
    acc_sum += s.accelerations.head<5>();
    acc_sq += s.accelerations.head<5>().cwiseAbs2();
  }
  if (csv) {
    const bool failed = std::ferror(csv) != 0;
    if (std::fclose(csv) != 0 || failed) throw std::runtime_error("--csv: error writing '" + r.csv + "'");
  }
  const double count = static_cast<double>(samples - first);
  const auto rms_about_mean = [count](double s, double sq) {
    return std::sqrt(std::max(0.0, sq / count - s * s / count / count));
  };
  const double ax = rms_about_mean(acc_sum[0], acc_sq[0]), ay = rms_about_mean(acc_sum[1], acc_sq[1]);
  const double az = rms_about_mean(acc_sum[2], acc_sq[2]);
  nlohmann::json ring = nlohmann::json::array();
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const int c = 5 + 2 * static_cast<int>(i);
    ring.push_back(
        {{"direction", direction_name(modes[i])},
         {"order", modes[i].order},
         {"frequency_hz", modes[i].frequency_rad_s() / kTwoPi},
         {"static_amplitude_m",
          std::hypot(dynamics.equilibrium().coordinates[c], dynamics.equilibrium().coordinates[c + 1])},
         {"rms_m", std::hypot(rms_about_mean(sum[c], sum_sq[c]), rms_about_mean(sum[c + 1], sum_sq[c + 1]))}});
  }
  const nlohmann::json result = {{"bearing", bearing_json(model, r.bearing_path)},
                                 {"load", to_json(r.load)},
                                 {"ring_speed_rpm", r.ring_speed_rpm},
                                 {"duration_s", r.duration_s},
                                 {"rate_hz", r.rate_hz},
                                 {"samples", samples},
                                 {"integrator", integration_method_name(r.method)},
                                 {"substeps", dynamics.substeps()},
                                 {"internal_step_s", dynamics.internal_step_s()},
                                 {"window", "second half of the run, mean removed"},
                                 {"a_rms_x", ax},
                                 {"a_rms_y", ay},
                                 {"a_rms_z", az},
                                 {"L_dB", vibration_level_db(ax)},
                                 {"flexible_ring", ring},
                                 {"csv", r.csv.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.csv)}};
  require_finite_result(result, "simulate", {"L_dB"});
  if (r.json) {
    print_json(result);
    return;
  }
  std::ostream& out = std::cout;
  out << "Bearing: " << model.config().name << " (" << r.bearing_path << "), flexible " << rotating_ring_name(model)
      << " ring at " << general(r.ring_speed_rpm, 6) << " rpm (docs/model.md section 18)\n\n";
  KeyValueList info;
  info.add("samples", std::to_string(samples) + " at " + general(r.rate_hz, 6) + " Hz");
  info.add("integration", std::to_string(dynamics.substeps()) + " " + integration_method_name(r.method) +
                              " steps per sample, step " + general(dynamics.internal_step_s() * 1e6, 4) + " us");
  info.add("a_rms x, y, z (rigid-body coordinates)",
           scientific(ax, 4) + ", " + scientific(ay, 4) + ", " + scientific(az, 4) + " m/s^2");
  info.add("L (x, JB/T 5314)", fixed(vibration_level_db(ax), 2) + " dB");
  if (!r.csv.empty()) info.add("CSV", r.csv);
  info.print(out);
  out << "\nRing modes (second half of the run)\n";
  Table t({"mode", "n", "frequency Hz (free)", "static um", "rms in the ring's frame um"}, {true});
  for (const auto& m : ring)
    t.add_row({m["direction"].get<std::string>(), std::to_string(m["order"].get<int>()),
               fixed(m["frequency_hz"].get<double>(), 1), fixed(m["static_amplitude_m"].get<double>() * 1e6, 4),
               scientific(m["rms_m"].get<double>() * 1e6, 3)});
  t.print(out);
}

}  // namespace bearing_sim::tool
