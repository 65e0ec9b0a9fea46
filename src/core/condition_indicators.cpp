#include "bearing_sim/core/condition_indicators.hpp"

#include <algorithm>
#include <cmath>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/speed_estimate.hpp"
#include "bearing_sim/core/vibration_level.hpp"
#include "envelope_evidence.hpp"
#include "fault_evidence.hpp"
#include "fixed_decimals.hpp"
#include "impact_intervals.hpp"
#include "number_text.hpp"

namespace bearing_sim {

const char* velocity_zone_name(VelocityZone zone) {
  switch (zone) {
    case VelocityZone::A:
      return "A";
    case VelocityZone::B:
      return "B";
    case VelocityZone::C:
      return "C";
    case VelocityZone::D:
      return "D";
  }
  return "?";
}

VelocityZone velocity_zone(double v, const VelocityZoneBoundaries& b) {
  if (v < b.ab_mm_s) return VelocityZone::A;
  if (v < b.bc_mm_s) return VelocityZone::B;
  if (v < b.cd_mm_s) return VelocityZone::C;
  return VelocityZone::D;
}

const char* health_level_name(HealthLevel level) {
  switch (level) {
    case HealthLevel::Ok:
      return "OK";
    case HealthLevel::Warn:
      return "WARN";
    case HealthLevel::Error:
      return "ERROR";
  }
  return "?";
}

const char* verdict_outcome_name(VerdictOutcome outcome) {
  switch (outcome) {
    case VerdictOutcome::None:
      return "none";
    case VerdictOutcome::Fault:
      return "fault";
    case VerdictOutcome::Ambiguous:
      return "ambiguous";
  }
  return "?";
}

const char* fault_kind_name(FaultKind kind) {
  switch (kind) {
    case FaultKind::OuterRace:
      return "outer race";
    case FaultKind::InnerRace:
      return "inner race";
    case FaultKind::Ball:
      return "ball";
    case FaultKind::Cage:
      return "cage";
  }
  return "?";
}

const char* fault_frequency_label(FaultKind kind) {
  switch (kind) {
    case FaultKind::OuterRace:
      return "BPFO";
    case FaultKind::InnerRace:
      return "BPFI";
    case FaultKind::Ball:
      return "2xBSF";
    case FaultKind::Cage:
      return "FTF";
  }
  return "?";
}

double fault_frequency_hz(const BearingFrequencies& f, FaultKind kind) {
  switch (kind) {
    case FaultKind::OuterRace:
      return f.ball_pass_outer_race_hz;
    case FaultKind::InnerRace:
      return f.ball_pass_inner_race_hz;
    case FaultKind::Ball:
      return 2.0 * f.ball_spin_hz;  // the spall meets both races once per spin turn
    case FaultKind::Cage:
      return std::abs(f.cage_hz);
  }
  return 0.0;
}

double modulation_frequency_hz(const BearingFrequencies& f, FaultKind kind) {
  switch (kind) {
    case FaultKind::OuterRace:
      return f.outer_ring_hz;
    case FaultKind::InnerRace:
      return f.inner_ring_hz;
    case FaultKind::Ball:
      return std::abs(f.cage_hz);
    case FaultKind::Cage:
      return 0.0;
  }
  return 0.0;
}

Diagnosis diagnose(const ConditionIndicators& c, const DiagnosisThresholds& t) {
  // Collect the findings, worst level wins; the reason lists the findings, worst first.
  struct Finding {
    HealthLevel level;
    double weight;  // orders findings of one level (larger first)
    std::string text;
  };
  std::vector<Finding> findings;
  const std::string velocity = "vibration velocity " + detail::fixed_decimals(c.velocity_rms_mm_s, 2) +
                               " mm/s RMS (zone " + velocity_zone_name(c.zone) + ")";
  if (c.zone >= t.error_zone)
    findings.push_back({HealthLevel::Error, 1e9, velocity + ": damaging vibration, stop and inspect"});
  else if (c.zone >= t.warn_zone)
    findings.push_back({HealthLevel::Warn, 1e9, velocity + ": restricted operation, plan maintenance"});
  for (const FaultIndicator& f : c.faults) {
    if (!f.suspected) continue;
    const SpectralPeak& p = f.envelope_peak;
    if (f.intervals.found) {
      findings.push_back({HealthLevel::Warn, 0.0, "ball defect suspected: " + f.note});
      continue;
    }
    const std::string what = f.kind == FaultKind::Cage ? "cage defect (or a ball defect's cage-rate modulation)"
                                                       : std::string(fault_kind_name(f.kind)) + " defect";
    findings.push_back({HealthLevel::Warn, p.snr_db,
                        what + " suspected: envelope peak at " + detail::fixed_decimals(p.frequency_hz, 1) + " Hz (" +
                            fault_frequency_label(f.kind) + " " + detail::fixed_decimals(p.expected_hz, 1) + " Hz), " +
                            detail::fixed_decimals(p.snr_db, 0) + " dB over noise, " +
                            std::to_string(f.harmonics_found) + " harmonics" +
                            (f.sidebands_required ? ", " + std::to_string(f.sidebands_found) + "/2 sidebands at -+" +
                                                        detail::fixed_decimals(f.modulation_hz, 1) + " Hz"
                                                  : std::string())});
  }
  if (t.kurtosis_warn > 0.0 && c.acceleration.kurtosis >= t.kurtosis_warn)
    findings.push_back({HealthLevel::Warn, 0.0,
                        "impulsive vibration: kurtosis " + detail::fixed_decimals(c.acceleration.kurtosis, 1) +
                            " (Gaussian noise 3), "
                            "typical of a localised defect"});
  Diagnosis d;
  d.verdict = fault_verdict(c.faults);
  // Series the analysis cannot see (too slow for the window, too fast for the band): said,
  // and when no race or ball series can be seen at all, not called healthy.
  std::string unseen;
  int seen = 0;
  for (const FaultIndicator& f : c.faults) {
    if (f.resolvable) {
      seen += f.kind != FaultKind::Cage ? 1 : 0;
      continue;
    }
    unseen += (unseen.empty() ? "" : ", ") + std::string(fault_frequency_label(f.kind));
  }
  if (!unseen.empty()) {
    d.verdict.text += "; the analysis cannot see " + unseen;
    if (seen == 0)
      findings.push_back({HealthLevel::Warn, 0.0,
                          "cannot assess the bearing: none of its fault lines can be seen in this window and band (" +
                              unseen + "; the series' notes say why)"});
  }
  if (findings.empty()) {
    d.reason = "no defect indication: " + velocity + ", kurtosis " +
               detail::fixed_decimals(c.acceleration.kurtosis, 1) +
               ", no fault series in the envelope spectrum (fundamental " +
               detail::fixed_decimals(c.fault_snr_db_used, 1) + " dB over noise with its supporting lines)";
    return d;
  }
  std::stable_sort(findings.begin(), findings.end(), [](const Finding& a, const Finding& b) {
    if (a.level != b.level) return a.level > b.level;
    return a.weight > b.weight;
  });
  d.level = findings.front().level;
  for (std::size_t i = 0; i < findings.size(); ++i) d.reason += (i ? "; " : "") + findings[i].text;
  return d;
}

double iso20816_velocity_low_hz(double shaft_speed_hz) {
  constexpr double kSlowMachineHz = 600.0 / 60.0;
  return std::abs(shaft_speed_hz) < kSlowMachineHz ? 2.0 : 10.0;
}

ConditionIndicators analyze_vibration(const std::vector<double>& accel, double fs, const BearingFrequencies& given,
                                      const AnalysisOptions& o) {
  BearingFrequencies freq = given;
  if (!(fs > 0.0) || !std::isfinite(fs)) throw InvalidInputError("analysis: the sample rate must be > 0 Hz");
  if (!(o.window_s >= 0.0) || !std::isfinite(o.window_s)) throw InvalidInputError("analysis: window_s must be >= 0");
  const double velocity_low_hz =
      o.velocity_low_hz > 0.0 ? o.velocity_low_hz : iso20816_velocity_low_hz(freq.relative_ring_hz);
  if (!(o.velocity_low_hz >= 0.0) || !(o.velocity_high_hz > velocity_low_hz) || !std::isfinite(o.velocity_high_hz))
    throw InvalidInputError("analysis: the velocity band must satisfy 0 < low < high");
  std::size_t n = accel.size();
  if (o.window_s > 0.0) n = std::min(n, static_cast<std::size_t>(std::llround(o.window_s * fs)));
  n = fft_friendly_length(n);
  if (n < 64) throw InvalidInputError("analysis: at least 64 samples are needed in the window");
  const std::vector<double> x(accel.end() - static_cast<long>(n), accel.end());

  ConditionIndicators c;
  c.samples = n;
  c.sample_rate_hz = fs;
  c.window_s = static_cast<double>(n) / fs;
  c.acceleration = signal_statistics(x);
  c.level_db = vibration_level_db(c.acceleration.rms);
  const double nyquist = 0.5 * fs;
  c.velocity_low_hz = velocity_low_hz;
  c.velocity_high_hz = std::min(o.velocity_high_hz, nyquist);
  c.velocity_rms_mm_s =
      velocity_low_hz < nyquist ? 1e3 * band_velocity_rms(x, fs, velocity_low_hz, c.velocity_high_hz) : 0.0;
  c.zone = velocity_zone(c.velocity_rms_mm_s, o.zones);
  // The speed as the recording shows it, where one ring turns and its shaft lines stand
  // clear (speed_estimate.hpp): a hand-read speed is often off by a fault line's window.
  if (o.measure_speed && (freq.inner_ring_hz > 0.0) != (freq.outer_ring_hz > 0.0)) {
    const SpeedEstimate speed = estimate_speed_scale(x, fs, freq.relative_ring_hz, o.speed);
    c.speed_measured = speed.measured;
    c.speed_scale = speed.scale;
    if (speed.measured) freq = scaled_frequencies(freq, speed.scale);
  }

  // Two envelope paths (docs/health.md, "Evidence", rule 10): the window as recorded (the
  // band by options.envelope_band) and the pre-whitened window, whose lines are the
  // cyclostationary impacts of rolling elements, not the machine's discrete lines. The
  // verdict is the recorded path's where it names a defect, else the whitened path's.
  static constexpr FaultKind kKinds[] = {FaultKind::OuterRace, FaultKind::InnerRace, FaultKind::Ball, FaultKind::Cage};
  double lowest_fault_hz = 0.0;
  for (FaultKind k : kKinds) {
    const double f = fault_frequency_hz(freq, k);
    if (f > 0.0 && (lowest_fault_hz == 0.0 || f < lowest_fault_hz)) lowest_fault_hz = f;
  }
  constexpr double kPeriodsPerSegment = 10.0;  // rule 11: the slowest line resolved in each segment
  const double segment_s =
      std::min(c.window_s,
               o.segment_s > 0.0 ? o.segment_s : std::max(1.0, kPeriodsPerSegment / std::max(lowest_fault_hz, 1e-9)));
  EnvelopePathSettings recorded_path;
  recorded_path.segment_samples = fft_friendly_length(static_cast<std::size_t>(std::llround(segment_s * fs)));
  recorded_path.absolute_floor = o.envelope_floor_m_s2;
  // Whitening flattens a line only where broadband noise fills the bins around it: with most
  // bins below the sensor floor (a noise-free simulation) it is not tried.
  double share_below_floor = 1.0;
  const std::vector<double> whitened =
      o.prewhiten ? prewhiten(x, white_noise_bin_magnitude(o.sensor_floor_m_s2_per_sqrt_hz, n, fs), &share_below_floor)
                  : std::vector<double>();
  const bool broadband_floor = o.prewhiten && share_below_floor < 0.5;
  EnvelopeEvidence from_whitened;
  if (broadband_floor) {
    EnvelopePathSettings whitened_path = recorded_path;
    whitened_path.absolute_floor = 0.0;  // no unit: the sensor floor entered the whitening
    from_whitened = envelope_evidence(whitened, fs, freq, o, choose_envelope_band(x, fs, freq, o, EnvelopeBand::Fixed),
                                      whitened_path);
    recorded_path.whitened_fundamentals = &from_whitened.found_fundamentals;
  }
  EnvelopeEvidence chosen =
      envelope_evidence(x, fs, freq, o, choose_envelope_band(x, fs, freq, o, o.envelope_band), recorded_path);
  c.envelope_source = "as recorded";
  if (chosen.verdict.outcome == VerdictOutcome::None && broadband_floor &&
      from_whitened.verdict.outcome != VerdictOutcome::None) {
    chosen = std::move(from_whitened);
    c.envelope_source = "whitened";
  }
  c.envelope_low_hz = chosen.band.low_hz;
  c.envelope_high_hz = chosen.band.high_hz;
  c.envelope_band_source = chosen.band.source;
  c.envelope_band_kurtosis = chosen.band.kurtosis.kurtosis;
  c.envelope_band_independent_samples = chosen.band.kurtosis.independent_samples;
  c.envelope = std::move(chosen.envelope);
  c.envelope_mean_m_s2 = chosen.envelope_mean;
  c.envelope_segments = chosen.segments;
  c.envelope_segment_s = chosen.segment_s;
  c.fault_snr_db_used = chosen.fault_snr_db_used;
  c.evidence_snr_db_used = chosen.evidence_snr_db_used;
  c.faults = std::move(chosen.faults);
  // Rule 14: nothing in either envelope spectrum, yet an impulsive band: a ball struck
  // intermittently, at a rate its slip changes from run to run, is looked for in the times
  // between consecutive impacts.
  const auto ball = std::find_if(c.faults.begin(), c.faults.end(),
                                 [](const FaultIndicator& f) { return f.kind == FaultKind::Ball; });
  const double ball_hz = fault_frequency_hz(freq, FaultKind::Ball);
  if (o.thresholds.ball_impact_intervals && chosen.verdict.outcome == VerdictOutcome::None &&
      c.envelope_band_kurtosis >= o.thresholds.impulsive_band_kurtosis && ball != c.faults.end() &&
      ball->resolvable && ball_hz > 0.0) {
    ball->intervals = impact_intervals(band_envelope(x, fs, c.envelope_low_hz, c.envelope_high_hz), fs,
                                       1.0 / ball_hz, o.thresholds);
    const ImpactIntervals& iv = ball->intervals;
    if (iv.found) {
      ball->suspected = true;
      ball->note = "struck intermittently: " + std::to_string(iv.in_window) + " of the intervals between " +
                   std::to_string(iv.impacts) + " impacts within " +
                   detail::fixed_decimals(100.0 * o.thresholds.interval_tolerance, 0) + " % of 1 / (2xBSF) = " +
                   detail::fixed_decimals(1e3 * iv.period_s, 2) + " ms, " + detail::fixed_decimals(iv.expected, 1) +
                   " expected there by the density around (chance " + detail::format_number(iv.chance) +
                   "), their median " + detail::fixed_decimals(iv.median_ratio, 3) + " x the period";
    }
  }
  c.diagnosis = diagnose(c, o.thresholds);
  return c;
}

}  // namespace bearing_sim
