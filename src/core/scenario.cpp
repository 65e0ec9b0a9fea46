#include "bearing_sim/core/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/bearing_dynamics.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/core/thermal_clearance.hpp"
#include "bearing_sim/core/virtual_accelerometer.hpp"
#include "number_text.hpp"

namespace bearing_sim {
using detail::format_number;

// --- speed ---------------------------------------------------------------------------

double Scenario::piece_speed(const SpeedPiece& p, double t) {
  const double dt = t - p.start_s;
  switch (p.kind) {
    case SpeedPiece::Kind::Hold:
      return p.start_speed;
    case SpeedPiece::Kind::Ramp:
      return p.start_speed + (p.end_speed - p.start_speed) * dt / (p.end_s - p.start_s);
    case SpeedPiece::Kind::Coast:
      return p.start_speed * std::exp(-dt / p.time_constant_s);
  }
  return 0.0;
}

double Scenario::piece_acceleration(const SpeedPiece& p, double t) {
  switch (p.kind) {
    case SpeedPiece::Kind::Hold:
      return 0.0;
    case SpeedPiece::Kind::Ramp:
      return (p.end_speed - p.start_speed) / (p.end_s - p.start_s);
    case SpeedPiece::Kind::Coast:
      return -piece_speed(p, t) / p.time_constant_s;
  }
  return 0.0;
}

// Closed-form integral of the piece's speed from its start.
double Scenario::piece_angle(const SpeedPiece& p, double t) {
  const double dt = t - p.start_s;
  switch (p.kind) {
    case SpeedPiece::Kind::Hold:
      return p.start_angle + p.start_speed * dt;
    case SpeedPiece::Kind::Ramp:
      return p.start_angle + p.start_speed * dt + 0.5 * (p.end_speed - p.start_speed) * dt * dt / (p.end_s - p.start_s);
    case SpeedPiece::Kind::Coast:
      return p.start_angle - p.start_speed * p.time_constant_s * std::expm1(-dt / p.time_constant_s);
  }
  return 0.0;
}

const Scenario::SpeedPiece& Scenario::speed_piece(double t) const {
  if (!(t >= 0.0) || !std::isfinite(t))
    throw InvalidInputError("scenario '" + name_ + "': time must be finite and >= 0, got " + format_number(t));
  // The last piece starting at or before t.
  auto it = std::upper_bound(speed_.begin(), speed_.end(), t,
                             [](double time, const SpeedPiece& p) { return time < p.start_s; });
  return *std::prev(it);
}

double Scenario::ring_speed_at(double t) const { return piece_speed(speed_piece(t), t); }

std::vector<Scenario::InputExtreme> Scenario::input_extremes() const {
  std::vector<double> times{0.0, duration_s_};
  for (const LoadPiece& p : load_) times.insert(times.end(), {p.start_s, p.end_s});
  for (const SpeedPiece& p : speed_) times.insert(times.end(), {p.start_s, p.end_s});
  times.erase(std::remove_if(times.begin(), times.end(), [&](double t) { return !(t >= 0.0 && t <= duration_s_); }),
              times.end());
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  const double me = unbalance_.mass_kg * unbalance_.radius_m;
  std::vector<InputExtreme> out;
  // The inputs at `t` from the pieces that hold at `probe` (t itself, or the middle of the
  // stretch t ends or starts: its one-sided value).
  const auto add = [&](double t, double probe) {
    InputExtreme e;
    e.time_s = t;
    Vector5 load = initial_load_;
    e.force_key = "load.initial.force_N";
    e.moment_key = "load.initial.moment_Nm";
    const auto it = std::upper_bound(load_.begin(), load_.end(), probe,
                                     [](double time, const LoadPiece& p) { return time < p.start_s; });
    if (it != load_.begin()) {
      const LoadPiece& p = *std::prev(it);
      const bool at_start = t <= p.start_s && p.end_s > p.start_s;  // a ramp's start: the load it starts from
      if (t >= p.end_s) load = p.to;
      else if (at_start) load = p.from;
      else load = p.from + (p.to - p.from) * ((t - p.start_s) / (p.end_s - p.start_s));
      e.force_key = at_start ? p.from_force_key : p.to_force_key;
      e.moment_key = at_start ? p.from_moment_key : p.to_moment_key;
    }
    const SpeedPiece& s = speed_piece(probe);
    const double w = piece_speed(s, t), alpha = piece_acceleration(s, t);
    e.speed_signed_rad_s = w;
    e.speed_rad_s = std::abs(w);
    e.speed_key = (s.kind == SpeedPiece::Kind::Ramp && t > s.start_s) ? s.end_key : s.start_key;
    e.unbalance_N = me * std::sqrt(w * w * w * w + alpha * alpha);
    e.force_N = std::hypot(std::hypot(load[0], load[1]) + e.unbalance_N, load[2]);
    e.load_force_N = load.head<3>().norm();
    e.moment_Nm = std::hypot(load[3], load[4]);
    out.push_back(e);
  };
  for (std::size_t i = 0; i + 1 < times.size(); ++i) {
    const double middle = 0.5 * (times[i] + times[i + 1]);
    add(times[i], middle);
    add(times[i + 1], middle);
  }
  add(times.back(), times.back());
  return out;
}
double Scenario::ring_angle_at(double t) const { return piece_angle(speed_piece(t), t); }

// --- load ----------------------------------------------------------------------------

Vector5 Scenario::base_load_at(double t) const {
  speed_piece(t);  // checks t
  auto it =
      std::upper_bound(load_.begin(), load_.end(), t, [](double time, const LoadPiece& p) { return time < p.start_s; });
  if (it == load_.begin()) return initial_load_;
  const LoadPiece& p = *std::prev(it);
  if (t >= p.end_s) return p.to;
  return p.from + (p.to - p.from) * ((t - p.start_s) / (p.end_s - p.start_s));
}

Vector5 Scenario::unbalance_load(double w, double alpha, double ring_angle) const {
  Vector5 f = Vector5::Zero();
  if (unbalance_.mass_kg == 0.0) return f;
  const double me = unbalance_.mass_kg * unbalance_.radius_m;
  const double a = ring_angle + unbalance_.phase_rad;
  const double c = std::cos(a), s = std::sin(a);
  f[0] = me * (w * w * c + alpha * s);
  f[1] = me * (w * w * s - alpha * c);
  return f;
}

Vector5 Scenario::load_at(double t) const {
  const SpeedPiece& p = speed_piece(t);
  return base_load_at(t) + unbalance_load(piece_speed(p, t), piece_acceleration(p, t), piece_angle(p, t));
}

std::string Scenario::phase_at(double t) const {
  speed_piece(t);
  std::string phase;
  for (const ScenarioPhase& p : phases_)
    if (p.start_s <= t) phase = p.name;
  return phase;
}

ScenarioInputs Scenario::inputs_at(double t) const {
  const SpeedPiece& p = speed_piece(t);
  ScenarioInputs in;
  in.ring_speed_rad_s = piece_speed(p, t);
  in.ring_angle_rad = piece_angle(p, t);
  in.load = load_at(t);
  in.phase = phase_at(t);
  in.ring_temperature_difference_K = ring_temperature_difference_at(t);
  return in;
}

// --- ring temperature difference ---------------------------------------------------

double Scenario::ring_temperature_difference_at(double t) const {
  speed_piece(t);  // checks t
  auto it = std::upper_bound(temperature_.begin(), temperature_.end(), t,
                             [](double time, const TemperaturePiece& p) { return time < p.start_s; });
  if (it == temperature_.begin()) return initial_temperature_K_;
  const TemperaturePiece& p = *std::prev(it);
  if (t >= p.end_s) return p.to_K;
  // Whole steps of kTemperatureStepK from the ramp's start, never past its end value.
  const double exact = (p.to_K - p.from_K) * ((t - p.start_s) / (p.end_s - p.start_s));
  const double steps = std::floor(std::abs(exact) / kTemperatureStepK);
  return p.from_K + std::copysign(steps * kTemperatureStepK, exact);
}

// --- defects -------------------------------------------------------------------------

double Scenario::spall_width_at(const Spall& s, double t) {
  // No cap needed here: the scenario refuses a spall whose size at its end would not fit the
  // bearing (spall_limit via Imperfections::validate), so this law never passes the limit.
  return grown_size(s.width_m, s.width_growth_m_per_s, std::max(0.0, t - s.created_at_s),
                    std::numeric_limits<double>::infinity());
}

double Scenario::spall_depth_at(const Spall& s, double t) {
  return grown_size(s.depth_m, s.depth_growth_m_per_s, std::max(0.0, t - s.created_at_s),
                    std::numeric_limits<double>::infinity());
}

std::vector<Spall> Scenario::spalls_at(double t) const {
  std::vector<Spall> present;
  for (const ScenarioDefectEvent& e : defect_events_) {
    if (e.time_s > t) break;
    if (e.kind == ScenarioDefectEvent::Kind::Clear) present.clear();
    else present.push_back(e.spall);
  }
  return present;
}

}  // namespace bearing_sim
