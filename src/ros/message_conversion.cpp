#include "bearing_sim/ros/message_conversion.hpp"

#include <cmath>
#include <cstdint>
#include <utility>

namespace bearing_sim {
namespace ros_node {

Vector5 load_from_wrench(const geometry_msgs::Wrench& wrench) {
  Vector5 load;
  load << wrench.force.x, wrench.force.y, wrench.force.z, wrench.torque.x, wrench.torque.y;
  return load;
}

void fill_vibration_chunk(runtime::SampleChunk&& chunk, const ros::Time& first_sample_stamp,
                          const std::string& frame_id, double sample_rate_hz, VibrationChunk* msg) {
  msg->header.stamp = first_sample_stamp;
  msg->header.frame_id = frame_id;
  msg->first_sample = chunk.first_sample;
  msg->sample_rate = sample_rate_hz;
  msg->accel_x = std::move(chunk.accel_x);
  msg->accel_y = std::move(chunk.accel_y);
  msg->accel_z = std::move(chunk.accel_z);
  msg->displacement_x = std::move(chunk.displacement_x);
  msg->displacement_y = std::move(chunk.displacement_y);
  msg->displacement_z = std::move(chunk.displacement_z);
  msg->tilt_x = std::move(chunk.tilt_x);
  msg->tilt_y = std::move(chunk.tilt_y);
}

void fill_bearing_health(const runtime::HealthReport& r, const std::string& signal, double sample_rate_hz,
                         BearingHealth* msg) {
  const ConditionIndicators& c = r.indicators;
  msg->signal = signal;
  msg->sample_rate = sample_rate_hz;
  if (r.analysed) {
    msg->window_s = c.window_s;
    msg->accel_rms = c.acceleration.rms;
    msg->accel_peak = c.acceleration.peak;
    msg->crest_factor = c.acceleration.crest_factor;
    msg->kurtosis = c.acceleration.kurtosis;
    msg->level_db = c.level_db;
    msg->velocity_rms_mm_s = c.velocity_rms_mm_s;
    msg->velocity_zone = velocity_zone_name(c.zone);
    msg->envelope_low_hz = c.envelope_low_hz;
    msg->envelope_high_hz = c.envelope_high_hz;
    for (const FaultIndicator& f : c.faults) {
      EnvelopeLine line;
      line.label = fault_frequency_label(f.kind);
      line.part = fault_kind_name(f.kind);
      line.expected_hz = fault_frequency_hz(r.frequencies, f.kind);
      line.peak_hz = f.envelope_peak.frequency_hz;
      line.amplitude_m_s2 = f.envelope_peak.amplitude;
      line.noise_floor_m_s2 = f.envelope_peak.noise_floor;
      line.snr_db = f.envelope_peak.snr_db;
      for (const EvidenceLine& h : f.harmonics) line.harmonic_snr_db.push_back(h.peak.snr_db);
      line.harmonics_found = static_cast<std::uint8_t>(f.harmonics_found);
      line.sidebands_required = f.sidebands_required;
      line.modulation_hz = f.modulation_hz;
      for (const EvidenceLine& s : f.sidebands) line.sideband_snr_db.push_back(s.peak.snr_db);
      line.sidebands_found = static_cast<std::uint8_t>(f.sidebands_found);
      line.resolvable = f.resolvable;
      line.impulsiveness_required = f.impulsiveness_required;
      line.impulsive = f.impulsive;
      line.band_kurtosis = f.band_kurtosis;
      line.suspected = f.suspected;
      line.note = f.note;
      msg->faults.push_back(line);
    }
    msg->level = static_cast<std::uint8_t>(c.diagnosis.level);
    msg->reason = c.diagnosis.reason;
  } else {
    // No window yet (OK) or a failed analysis (WARN): say which.
    msg->level = r.error.rfind("collecting", 0) == 0 ? BearingHealth::OK : BearingHealth::WARN;
    msg->reason = r.error;
  }
  for (const runtime::DefectNow& d : r.defects) fill_defect_state(d, &msg->defects.emplace_back());
  msg->ring_speed_rad_s = r.ring_speed_rad_s;
  msg->radial_force_N = std::hypot(r.load[0], r.load[1]);
  msg->axial_force_N = std::abs(r.load[2]);
  msg->dynamic_load_rating_N = r.iso281.dynamic_load_rating_N;
  msg->equivalent_load_N = r.iso281.equivalent.load_N;
  msg->l10_million_rev = r.iso281.life_million_rev;
  msg->l10_hours = r.iso281.life_hours;
  msg->reference_life_million_rev = r.reference_life_million_rev;
  msg->reference_life_hours = r.reference_life_hours;
  msg->miner_damage = r.miner_damage;
  msg->remaining_life_hours = r.remaining_life_hours;
  msg->operated_s = r.operated_s;
  msg->revolutions = r.revolutions;
}

void fill_defect_state(const runtime::DefectNow& d, DefectState* s) {
  s->surface = surface_name(d.spall.surface);
  s->position_rad = d.spall.position_rad;
  s->ball = d.spall.surface == Surface::Ball ? d.spall.ball : -1;
  s->row = d.spall.surface == Surface::Ball ? -1 : d.spall.row;
  s->width_m = d.width_m;
  s->depth_m = d.depth_m;
  s->width_growth_m_per_s = d.spall.width_growth_m_per_s;
  s->depth_growth_m_per_s = d.spall.depth_growth_m_per_s;
  s->age_s = d.age_s;
}

void fill_scenario_state(const std::string& scenario, const std::string& bearing, std::uint64_t seed, double time_s,
                         const ScenarioInputs& inputs, const std::vector<runtime::DefectNow>& defects,
                         ScenarioState* msg) {
  msg->scenario = scenario;
  msg->bearing = bearing;
  msg->seed = seed;
  msg->scenario_time_s = time_s;
  msg->phase = inputs.phase;
  msg->ring_speed_rad_s = inputs.ring_speed_rad_s;
  for (int i = 0; i < 5; ++i) msg->load[static_cast<std::size_t>(i)] = inputs.load[i];
  msg->defects.clear();
  for (const runtime::DefectNow& d : defects) fill_defect_state(d, &msg->defects.emplace_back());
}

void fill_ball_loads(const std::vector<BallState>& balls, int rows, int balls_per_row, double cage_angle_rad,
                     BallLoads* msg) {
  msg->rows = static_cast<std::uint8_t>(rows);
  msg->balls_per_row = static_cast<std::uint16_t>(balls_per_row);
  msg->cage_angle = cage_angle_rad;
  const std::size_t n = balls.size();
  msg->azimuth.resize(n);
  msg->load.resize(n);
  msg->contact_angle.resize(n);
  msg->deflection.resize(n);
  // Row-major: the core numbers the balls row by row; place by (row, index) to be sure.
  for (const BallState& b : balls) {
    const std::size_t i = static_cast<std::size_t>(b.row) * static_cast<std::size_t>(balls_per_row) +
                          static_cast<std::size_t>(b.index_in_row);
    if (i >= n) continue;
    msg->azimuth[i] = static_cast<float>(b.azimuth_rad);
    msg->load[i] = static_cast<float>(b.load_N);
    msg->contact_angle[i] = static_cast<float>(b.contact_angle_rad);
    msg->deflection[i] = static_cast<float>(b.deflection_m);
  }
}

}  // namespace ros_node
}  // namespace bearing_sim
