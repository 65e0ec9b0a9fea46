#pragma once
// Condition indicators of a vibration window and a diagnosis (docs/model.md section 13; docs/health.md):
// RMS, peak, crest factor, kurtosis, L, velocity RMS with its ISO 20816-3 zone, and the
// envelope spectrum at the fault frequencies.
#include <string>
#include <vector>

#include "bearing_sim/core/frequencies.hpp"
#include "bearing_sim/core/signal_statistics.hpp"
#include "bearing_sim/core/spectrum.hpp"
#include "bearing_sim/core/speed_estimate.hpp"

namespace bearing_sim {

// Velocity RMS zone boundaries, mm/s. Default: ISO 10816-3 / ISO 20816-3, machine group 2
// (15 kW - 300 kW, shaft height 160-315 mm) on a RIGID foundation. Other common sets:
// group 2 flexible 2.3 / 4.5 / 7.1; group 1 (300 kW - 50 MW) rigid 2.3 / 4.5 / 7.1,
// flexible 3.5 / 7.1 / 11.0.
struct VelocityZoneBoundaries {
  double ab_mm_s = 1.4;  // A: newly commissioned | B: unrestricted long-term operation
  double bc_mm_s = 2.8;  // C: restricted operation, plan maintenance
  double cd_mm_s = 4.5;  // D: vibration severe enough to cause damage
};

enum class VelocityZone { A, B, C, D };
const char* velocity_zone_name(VelocityZone zone);  // "A" .. "D"
VelocityZone velocity_zone(double velocity_rms_mm_s, const VelocityZoneBoundaries& b);

enum class HealthLevel { Ok, Warn, Error };        // same order as diagnostic_msgs OK/WARN/ERROR
const char* health_level_name(HealthLevel level);  // "OK", "WARN", "ERROR"

struct DiagnosisThresholds {
  // Envelope peak this far over the noise floor (median of the neighbouring bins): defect
  // suspected -> WARN. The peak is the largest of the ~13 bins searched around each of 4
  // lines; in pure noise (Rayleigh bins) 10 dB is exceeded in ~4% of analyses, 12 dB in ~0.1%.
  double fault_snr_db = 12.0;
  // Supporting lines (the 2nd harmonic, the modulation sidebands) this far over their noise
  // floor. They are only looked at once the fundamental has passed fault_snr_db, so a lower
  // bar is safe: a noise bin exceeds its median by 10 dB with probability 0.1% (Rayleigh),
  // ~1% as the largest of the ~13 bins searched; with the fundamental's 0.1% that is ~1e-5
  // per fault type. Evidence rule: docs/health.md, "Evidence".
  double evidence_snr_db = 10.0;
  // A series the healthy varying compliance can give (at Z |f_c| without sidebands: the
  // stationary race's; the cage line) needs the envelope band's spectral kurtosis at least
  // this (<= 0: not required). A train
  // of bursts filling a fraction d of each period has SK = 1/d - 2: 2 means the band's
  // energy comes in bursts filling at most a quarter of the period. Gaussian noise: 0; a
  // line series: < 0; the simulated healthy ball-pass excitation under a quiet sensor:
  // 0.1-1.8 (docs/health.md, "Benchmark").
  double impulsive_band_kurtosis = 2.0;
  // ... asked only of bearings with at most this many balls per row (Z = varying compliance
  // / cage frequency): the compliance excitation falls as Z^-2.5 (fault_evidence.cpp); the
  // 6205 (9) and the 618/22 (10) show it, the CT bearing (207) does not.
  double compliance_max_balls = 40.0;
  // A line is found only where a window of its width holds no line of that height by chance
  // more often than this (line_chance): 0.1, a tenth of the windows of the neighbourhood.
  double line_chance_max = 0.1;
  // The neighbourhood (+- this fraction of the frequency) that line_chance counts lines in.
  double line_neighbourhood_rel = 0.2;
  // Rule 14 (docs/health.md): where the envelope spectrum names nothing and the band is
  // impulsive, a spalled ball struck intermittently is looked for in the times between
  // consecutive impacts. An impact is an envelope maximum over impact_over_median x the
  // envelope's median (a Rayleigh envelope of Gaussian noise exceeds 4 x its median with
  // probability 1.5e-5); intervals within +-interval_tolerance of 1 / (2 x BSF) are counted
  // against the density of intervals around (+-4 x the tolerance). The tolerance holds the
  // ball's speed scatter from pass to pass (slip in and out of the load zone, a few %) and
  // the envelope peak's place in a burst (a few cycles of a 2-6 kHz resonance: 3 % of the
  // 6205's 7 ms). Found: at least intervals_min in the window, a Poisson chance of that
  // many at the surrounding density of at most interval_chance_max, and the window's
  // intervals centred on the period (their median within half the tolerance): a ball's mean
  // speed is the kinematic one within its slip, while another periodic source near the
  // period (a shaft order 5 x f_r lies 6 % from the 6205's 2 x BSF) sits off centre.
  bool ball_impact_intervals = true;
  double impact_over_median = 4.0;
  double interval_tolerance = 0.07;
  double intervals_min = 10.0;
  double interval_chance_max = 1e-3;
  double kurtosis_warn = 6.0;                 // impulsive signal -> WARN (Gaussian noise: 3); <= 0 disables
  VelocityZone warn_zone = VelocityZone::C;   // velocity zone at or above: WARN
  VelocityZone error_zone = VelocityZone::D;  // ... ERROR
};
// The thresholds a user may set (bearing_tool analyze --snr-db / --kurtosis-warn, the node's
// fault_snr_db). A fault SNR from 0 dB (a line no higher than its noise floor: below, every
// bin is a fault) to 60 dB (a million times the floor's power, beyond the dynamic range of a
// recorded envelope spectrum); a kurtosis WARN of 0 (off) or from 3 (Gaussian noise: below,
// every healthy signal warns) to 1000 (a single impulse in 1000 samples).
constexpr double kMinFaultSnrDb = 0.0, kMaxFaultSnrDb = 60.0;
constexpr double kMinKurtosisWarn = 3.0, kMaxKurtosisWarn = 1000.0;

// How the envelope band is chosen when no resonance_hz is given (docs/health.md).
enum class EnvelopeBand { Kurtogram, Fixed };

struct AnalysisOptions {
  // Analyse the last window_s seconds of the signal (0: all of it). The window is then
  // shortened to an FFT-friendly length (2^a 3^b 5^c samples, a few percent at most).
  double window_s = 0.0;
  // Envelope band: centred on resonance_hz (the sensor's transmission-path resonance,
  // typically 3-5 kHz) with envelope_band_width_hz; when resonance_hz is 0, by
  // envelope_band: Kurtogram, the band of the largest spectral kurtosis (fast_kurtogram)
  // among those at least 3 x the highest fault frequency wide with a low edge at or above
  // max(500 Hz, 4 x the highest fault frequency); Fixed, from that low edge up to 0.4 x the
  // sample rate.
  double resonance_hz = 0.0;
  double envelope_band_width_hz = 2000.0;
  EnvelopeBand envelope_band = EnvelopeBand::Kurtogram;  // of the path as recorded
  // The noise floor of the best real measurement chain (1e-5: 1 ug/sqrt(Hz), below the best
  // IEPE sensors): the analysis sees a signal as such a sensor would record it. Bands'
  // spectral kurtosis is taken with this floor added (fast_kurtogram), so that a noise-free
  // simulation's faint periodic bursts are not impacts, and pre-whitening leaves the bins
  // below it relative to it.
  double sensor_floor_m_s2_per_sqrt_hz = 1e-5;
  // Cepstral pre-whitening of the window before the envelope (prewhiten, spectrum.hpp):
  // the machine's discrete lines and the path's resonances flattened, impacts kept. The
  // band's spectral kurtosis is always of the signal as recorded.
  bool prewhiten = true;
  // Take the turning ring's speed from its 1-3 x lines where they stand clear and agree
  // (estimate_speed_scale), the fault frequencies scaled with it.
  bool measure_speed = true;
  SpeedEstimateOptions speed;
  // Envelope spectrum averaged over segments of segment_s (averaged_envelope_spectrum);
  // 0: max(1 s, 10 periods of the lowest fault frequency), the window at most.
  double segment_s = 0.0;
  // Velocity band; a low edge of 0 takes ISO 20816-3's for the machine's speed
  // (iso20816_velocity_low_hz of the relative ring speed).
  double velocity_low_hz = 0.0;
  double velocity_high_hz = 1000.0;
  VelocityZoneBoundaries zones;
  PeakSearchOptions peak_search;
  // Envelope-spectrum floor per bin, m/s^2: SNRs are taken against at least this, so that
  // a near-perfect (simulated, noise-free) signal's tiny lines are not called defects.
  // 1e-5 m/s^2 is below the per-bin floor of a good IEPE accelerometer (about 0.5 mg
  // broadband over 10 kHz gives 5e-5 m/s^2 in a 1 Hz bin).
  double envelope_floor_m_s2 = 1e-5;
  DiagnosisThresholds thresholds;
};

enum class FaultKind { OuterRace, InnerRace, Ball, Cage };

// One line of a fault's evidence in the envelope spectrum: a harmonic n f_fault (order n)
// or a sideband f_fault + offset_hz (offset -f_mod or +f_mod).
struct EvidenceLine {
  int order = 1;  // harmonic number (1: the fundamental); sidebands: 1
  // Within the search window of a line of another series whose fundamental is found
  // (2 x BPFI and 3 x BPFO of the 6205 lie 0.7 % apart): evidence for neither, skipped.
  bool shared = false;
  double offset_hz = 0.0;  // 0 for a harmonic; -+ the modulation frequency for a sideband
  SpectralPeak peak;       // searched at expected_hz (amplitude in m/s^2, snr_db over noise)
  bool found = false;      // a local maximum with snr_db >= its threshold
};
const char* fault_kind_name(FaultKind kind);        // "outer race", "inner race", "ball", "cage"
const char* fault_frequency_label(FaultKind kind);  // "BPFO", "BPFI", "2xBSF", "FTF"

// Rule 14 (docs/health.md): the intervals between consecutive impacts in the band envelope
// against one period (1 / (2 x BSF) for a spalled ball).
struct ImpactIntervals {
  bool tested = false;         // asked: nothing in the envelope spectrum, an impulsive band
  double period_s = 0.0;       // the period looked for
  std::size_t impacts = 0;     // envelope maxima over impact_over_median x its median
  std::size_t in_window = 0;   // consecutive intervals within +-interval_tolerance of the period
  std::size_t around = 0;      // within +-4 x the tolerance, outside the window
  double expected = 0.0;       // in the window at the density around: (around + 1/2) / 3
  double chance = 1.0;         // Poisson P(count >= in_window) at that expectation
  double median_ratio = 0.0;   // median of the window's intervals / the period (0: none)
  // in_window >= intervals_min, chance <= interval_chance_max and the median ratio within
  // half the tolerance of 1
  bool found = false;
};

struct FaultIndicator {
  FaultKind kind = FaultKind::OuterRace;
  SpectralPeak envelope_peak;  // searched at the fault frequency (amplitude in m/s^2)
  // Line amplitude over the mean of the envelope: near 1 for a spall's impact train,
  // well below for the weak periodicity of distributed roughness (informative only).
  double modulation = 0.0;
  // Evidence (docs/health.md "Evidence"): harmonics 1..3 (the 1st is envelope_peak; the 2nd
  // and 3rd searched at n x the found fundamental), and the sidebands f_fault -+ f_mod when
  // the physics predicts amplitude modulation (inner race: the inner ring's speed in the
  // load frame; outer race: the outer ring's; ball: the cage's), else empty.
  std::vector<EvidenceLine> harmonics;
  std::vector<EvidenceLine> sidebands;
  double modulation_hz = 0.0;       // f_mod (0: no modulation predicted or not resolvable)
  int harmonics_found = 0;          // consecutive from the 1st, shared ones skipped: 0 .. 4
  int sidebands_found = 0;          // 0 .. 2
  bool sidebands_required = false;  // modulation predicted and resolvable
  // The fault frequency is >= noise_exclude_bins + 2 bins (else nothing of it is "found").
  bool resolvable = true;
  // No sideband evidence: the band must be impulsive (impulsive_band_kurtosis).
  bool impulsiveness_required = false;
  bool impulsive = true;
  double band_kurtosis = 0.0;  // the envelope band's spectral kurtosis
  ImpactIntervals intervals;   // the ball series only (rule 14)
  // Fundamental found (fault_snr_db) AND 2nd harmonic found (evidence_snr_db) AND, when
  // sidebands_required, at least one sideband found (evidence_snr_db) AND, when
  // impulsiveness_required, an impulsive band; AND not withdrawn beside another series
  // (docs/health.md, "Evidence"); or, for the ball where no series is, intervals.found (rule 14).
  bool suspected = false;
  // Why a series is not suspected or what else explains it (empty when nothing to say).
  std::string note;
};

// What the envelope evidence says, beside the health level: nothing; one fault type; or
// that it cannot tell between several (two race or ball series each with its own evidence,
// or a cage-rate series alone: a cage defect or a ball defect's modulation).
enum class VerdictOutcome { None, Fault, Ambiguous };
const char* verdict_outcome_name(VerdictOutcome outcome);  // "none", "fault", "ambiguous"
struct Verdict {
  VerdictOutcome outcome = VerdictOutcome::None;
  std::vector<FaultKind> kinds;  // the type (Fault) or the types it cannot tell between
  std::string text;
};

struct Diagnosis {
  HealthLevel level = HealthLevel::Ok;
  std::string reason;  // one line for a maintenance engineer
  Verdict verdict;
};

struct ConditionIndicators {
  std::size_t samples = 0;  // analysed (after windowing)
  double window_s = 0.0;
  double sample_rate_hz = 0.0;
  SignalStatistics acceleration;                         // m/s^2: rms, peak, crest factor, kurtosis
  double level_db = 0.0;                                 // L = 20 lg(a_rms / 9.81e-3 m/s^2), JB/T 5314
  double velocity_rms_mm_s = 0.0;                        // in [velocity_low_hz, velocity_high_hz]
  double velocity_low_hz = 0.0, velocity_high_hz = 0.0;  // the band used
  VelocityZone zone = VelocityZone::A;
  double envelope_low_hz = 0.0, envelope_high_hz = 0.0;
  std::string envelope_band_source;  // "resonance", "kurtogram" or "fixed"
  // Spectral kurtosis of the band (band_spectral_kurtosis, any band source) and the number
  // of independent envelope samples it rests on (Gaussian noise: 0 +- 2 / sqrt of that).
  double envelope_band_kurtosis = 0.0;
  double envelope_band_independent_samples = 0.0;
  double envelope_mean_m_s2 = 0.0;  // mean of the band envelope (the demodulated level)
  // The envelope path the verdict comes from: "whitened" (the pre-whitened window; its
  // envelope has no unit) or "as recorded".
  std::string envelope_source;
  std::size_t envelope_segments = 1;  // averaged segments (averaged_envelope_spectrum)
  // The speed the fault frequencies were taken at, over the given one (1: as given).
  bool speed_measured = false;
  double speed_scale = 1.0;
  double envelope_segment_s = 0.0;
  // The detection thresholds for that average (averaged_threshold_db of the options').
  double fault_snr_db_used = 0.0, evidence_snr_db_used = 0.0;
  Spectrum envelope;                   // envelope spectrum, m/s^2 (pre-whitened: relative to the whitened level)
  std::vector<FaultIndicator> faults;  // outer race, inner race, ball, cage in that order
  Diagnosis diagnosis;
};

// Throws InvalidInputError for bad input (too few samples, non-finite, a band outside
// the sample rate).
ConditionIndicators analyze_vibration(const std::vector<double>& accel_m_s2, double sample_rate_hz,
                                      const BearingFrequencies& frequencies, const AnalysisOptions& options = {});

// Low edge of ISO 20816-3's broadband velocity range: 2 Hz for machines below 600 rpm
// (the standard's 120-600 rpm range; the CT gantry turns at up to ~240 rpm), 10 Hz above.
double iso20816_velocity_low_hz(double shaft_speed_hz);

// The fault frequency searched for a kind: BPFO, BPFI, 2 x ball spin, |cage|.
double fault_frequency_hz(const BearingFrequencies& f, FaultKind kind);

// The frequency that amplitude-modulates a defect of this kind: the speed, in the frame of
// the (fixed) load, of what carries the defect through the load zone. Inner race:
// inner_ring_hz; outer race: outer_ring_hz; ball: |cage_hz|; cage: 0 (none predicted).
double modulation_frequency_hz(const BearingFrequencies& f, FaultKind kind);

// The diagnosis from indicators already computed (analyze_vibration calls it).
Diagnosis diagnose(const ConditionIndicators& indicators, const DiagnosisThresholds& thresholds);

}  // namespace bearing_sim
