#include "bearing_sim/core/condition_indicators.hpp"

#include <algorithm>
#include <cmath>

#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/vibration_level.hpp"
#include "fault_evidence.hpp"
#include "fixed_decimals.hpp"

namespace bearing_sim {
namespace {
// Some band of the kurtogram's tree is wide enough and starts high enough: the half band
// [fs/4, fs/2] is the widest one off DC.
bool kurtogram_fits(double fs, double highest_fault_hz, double lowest_edge_hz) {
  return 0.25 * fs >= 3.0 * highest_fault_hz && 0.25 * fs >= lowest_edge_hz;
}

}  // namespace


const char* velocity_zone_name(VelocityZone zone) {
  switch (zone) {
    case VelocityZone::A: return "A";
    case VelocityZone::B: return "B";
    case VelocityZone::C: return "C";
    case VelocityZone::D: return "D";
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
    case HealthLevel::Ok: return "OK";
    case HealthLevel::Warn: return "WARN";
    case HealthLevel::Error: return "ERROR";
  }
  return "?";
}

const char* fault_kind_name(FaultKind kind) {
  switch (kind) {
    case FaultKind::OuterRace: return "outer race";
    case FaultKind::InnerRace: return "inner race";
    case FaultKind::Ball: return "ball";
    case FaultKind::Cage: return "cage";
  }
  return "?";
}

const char* fault_frequency_label(FaultKind kind) {
  switch (kind) {
    case FaultKind::OuterRace: return "BPFO";
    case FaultKind::InnerRace: return "BPFI";
    case FaultKind::Ball: return "2xBSF";
    case FaultKind::Cage: return "FTF";
  }
  return "?";
}

double fault_frequency_hz(const BearingFrequencies& f, FaultKind kind) {
  switch (kind) {
    case FaultKind::OuterRace: return f.ball_pass_outer_race_hz;
    case FaultKind::InnerRace: return f.ball_pass_inner_race_hz;
    case FaultKind::Ball: return 2.0 * f.ball_spin_hz;  // the spall meets both races once per spin turn
    case FaultKind::Cage: return std::abs(f.cage_hz);
  }
  return 0.0;
}

double modulation_frequency_hz(const BearingFrequencies& f, FaultKind kind) {
  switch (kind) {
    case FaultKind::OuterRace: return f.outer_ring_hz;
    case FaultKind::InnerRace: return f.inner_ring_hz;
    case FaultKind::Ball: return std::abs(f.cage_hz);
    case FaultKind::Cage: return 0.0;
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
  const std::string velocity = "vibration velocity " + detail::fixed_decimals(c.velocity_rms_mm_s, 2) + " mm/s RMS (zone " +
                               velocity_zone_name(c.zone) + ")";
  if (c.zone >= t.error_zone)
    findings.push_back({HealthLevel::Error, 1e9, velocity + ": damaging vibration, stop and inspect"});
  else if (c.zone >= t.warn_zone)
    findings.push_back({HealthLevel::Warn, 1e9, velocity + ": restricted operation, plan maintenance"});
  for (const FaultIndicator& f : c.faults) {
    if (!f.suspected) continue;
    const SpectralPeak& p = f.envelope_peak;
    const std::string what = f.kind == FaultKind::Cage ? "cage defect (or a ball defect's cage-rate modulation)"
                                                       : std::string(fault_kind_name(f.kind)) + " defect";
    findings.push_back({HealthLevel::Warn, p.snr_db,
                        what + " suspected: envelope peak at " +
                            detail::fixed_decimals(p.frequency_hz, 1) + " Hz (" + fault_frequency_label(f.kind) + " " +
                            detail::fixed_decimals(p.expected_hz, 1) + " Hz), " + detail::fixed_decimals(p.snr_db, 0) + " dB over noise, " +
                            std::to_string(f.harmonics_found) + " harmonics" +
                            (f.sidebands_required ? ", " + std::to_string(f.sidebands_found) + "/2 sidebands at -+" +
                                                        detail::fixed_decimals(f.modulation_hz, 1) + " Hz"
                                                  : std::string())});
  }
  if (t.kurtosis_warn > 0.0 && c.acceleration.kurtosis >= t.kurtosis_warn)
    findings.push_back({HealthLevel::Warn, 0.0,
                        "impulsive vibration: kurtosis " + detail::fixed_decimals(c.acceleration.kurtosis, 1) + " (Gaussian noise 3), "
                        "typical of a localised defect"});
  Diagnosis d;
  if (findings.empty()) {
    d.reason = "no defect indication: " + velocity + ", kurtosis " + detail::fixed_decimals(c.acceleration.kurtosis, 1) +
               ", no envelope peak " + detail::fixed_decimals(t.fault_snr_db, 0) + " dB over noise at the fault frequencies";
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

ConditionIndicators analyze_vibration(const std::vector<double>& accel, double fs, const BearingFrequencies& freq,
                                      const AnalysisOptions& o) {
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

  // Envelope band.
  static constexpr FaultKind kKinds[] = {FaultKind::OuterRace, FaultKind::InnerRace, FaultKind::Ball,
                                         FaultKind::Cage};
  double highest_fault_hz = 0.0;
  for (FaultKind k : kKinds) highest_fault_hz = std::max(highest_fault_hz, fault_frequency_hz(freq, k));
  // Well above the fault lines themselves, so that the band holds the resonances they
  // excite rather than the lines (and their low harmonics).
  const double lowest_edge_hz = std::max(500.0, 4.0 * highest_fault_hz);
  BandKurtosis sk;  // of the chosen band
  if (o.resonance_hz > 0.0) {
    if (!(o.envelope_band_width_hz > 0.0)) throw InvalidInputError("analysis: the envelope band width must be > 0");
    c.envelope_low_hz = std::max(0.0, o.resonance_hz - 0.5 * o.envelope_band_width_hz);
    c.envelope_high_hz = o.resonance_hz + 0.5 * o.envelope_band_width_hz;
    c.envelope_band_source = "resonance";
  } else if (o.envelope_band == EnvelopeBand::Kurtogram && kurtogram_fits(fs, highest_fault_hz, lowest_edge_hz)) {
    // The most impulsive band wide enough to hold harmonics 1-3 of every fault line.
    const Kurtogram k = fast_kurtogram(x, fs, 3.0 * highest_fault_hz, lowest_edge_hz);
    c.envelope_low_hz = k.best.low_hz;
    c.envelope_high_hz = k.best.high_hz;
    c.envelope_band_source = "kurtogram";
    sk = BandKurtosis{true, k.best.kurtosis, k.best.independent_samples};
  } else {
    c.envelope_low_hz = lowest_edge_hz;
    c.envelope_high_hz = 0.4 * fs;
    c.envelope_band_source = "fixed";
  }
  if (!(c.envelope_high_hz <= nyquist) || !(c.envelope_low_hz < c.envelope_high_hz))
    throw InvalidInputError("analysis: envelope band " + detail::fixed_decimals(c.envelope_low_hz, 0) + "-" + detail::fixed_decimals(c.envelope_high_hz, 0) +
                            " Hz does not fit below the Nyquist frequency " + detail::fixed_decimals(nyquist, 0) +
                            " Hz (raise the sample rate or give resonance_hz)");
  // The band's impulsiveness, whichever way it was chosen (the evidence rule asks it of a
  // series without sidebands); the kurtogram has it already, by the same computation.
  if (!sk.valid) sk = band_spectral_kurtosis(x, fs, c.envelope_low_hz, c.envelope_high_hz);
  c.envelope_band_kurtosis = sk.kurtosis;
  c.envelope_band_independent_samples = sk.independent_samples;
  const std::vector<double> envelope = band_envelope(x, fs, c.envelope_low_hz, c.envelope_high_hz);
  c.envelope_mean_m_s2 = signal_statistics(envelope).mean;
  c.envelope = amplitude_spectrum(envelope, fs);
  for (FaultKind k : kKinds) {
    FaultIndicator f;
    f.kind = k;
    f.envelope_peak = find_peak(c.envelope, fault_frequency_hz(freq, k), o.peak_search, o.envelope_floor_m_s2);
    f.modulation = c.envelope_mean_m_s2 > 0.0 ? f.envelope_peak.amplitude / c.envelope_mean_m_s2 : 0.0;
    collect_fault_evidence(c.envelope, freq, o, sk, &f);
    c.faults.push_back(f);
  }
  arbitrate_fault_series(c.envelope, freq, o, &c.faults);
  c.diagnosis = diagnose(c, o.thresholds);
  return c;
}

}  // namespace bearing_sim
