#pragma once
// One envelope path of the diagnosis (docs/health.md, "Envelope analysis" and "Evidence"): a
// band, the band's envelope spectrum averaged over segments, each fault series' evidence in
// it and the decisions between the series. analyze_vibration runs it on the window as
// recorded and on the pre-whitened window.
#include <string>
#include <vector>

#include "bearing_sim/core/condition_indicators.hpp"

namespace bearing_sim {

struct EnvelopeBandChoice {
  double low_hz = 0.0, high_hz = 0.0;
  std::string source;     // "resonance", "kurtogram" or "fixed"
  BandKurtosis kurtosis;  // of the signal as recorded in that band, the sensor floor added
};

// The band for this path: resonance_hz when given, else by `band` (the kurtogram of x, or
// the fixed range from max(500 Hz, 4 x the highest fault frequency) to 0.4 fs).
EnvelopeBandChoice choose_envelope_band(const std::vector<double>& x, double sample_rate_hz,
                                        const BearingFrequencies& freq, const AnalysisOptions& o, EnvelopeBand band);

struct EnvelopeEvidence {
  EnvelopeBandChoice band;
  Spectrum envelope;
  double envelope_mean = 0.0;
  std::size_t segments = 1;
  double segment_s = 0.0;
  double fault_snr_db_used = 0.0, evidence_snr_db_used = 0.0;
  std::vector<FaultIndicator> faults;         // outer race, inner race, ball, cage
  std::vector<FaultKind> found_fundamentals;  // race and ball series whose fundamental is found
  Verdict verdict;
};

struct EnvelopePathSettings {
  double absolute_floor = 0.0;  // per envelope bin (0 for a whitened envelope: no unit)
  std::size_t segment_samples = 0;
  // The series whose fundamental the whitened envelope found: given (the recording has a
  // broadband floor), a series of a non-impulsive band outside it is withdrawn (rule 10).
  const std::vector<FaultKind>* whitened_fundamentals = nullptr;
};

// The evidence of every series in the band envelope of `demodulated` (the window as
// recorded or pre-whitened).
EnvelopeEvidence envelope_evidence(const std::vector<double>& demodulated, double sample_rate_hz,
                                   const BearingFrequencies& freq, const AnalysisOptions& o,
                                   const EnvelopeBandChoice& band, const EnvelopePathSettings& settings);

}  // namespace bearing_sim
