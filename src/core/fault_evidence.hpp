#pragma once
// The evidence rule of the envelope diagnosis (docs/health.md, "Evidence"): what one fault
// series must show in the envelope spectrum to be suspected, and the decisions between
// series whose lines can stand for each other.
#include <vector>

#include "bearing_sim/core/condition_indicators.hpp"

namespace bearing_sim {

// What the evidence of one series is judged against.
struct EvidenceContext {
  double fault_snr_db = 12.0;      // the fundamental's threshold for this spectrum's averaging
  double evidence_snr_db = 10.0;   // the supporting lines'
  double absolute_floor = 0.0;     // SNRs are taken against at least this per bin
  std::vector<FaultKind> present;  // race and ball series whose fundamental is found
  std::size_t segments = 1;        // averaged into the envelope spectrum (rule 12 needs >= 2)
  double band_width_hz = 0.0;      // of the demodulated band: the highest envelope frequency it carries
};

// The lines a series' hypothesis predicts: n f_fault + j f_mod, n = 1 .. harmonics,
// j = -2 .. 2 (j = 0 alone without modulation): the sidebands rule 6 counts as its own.
std::vector<double> series_lines_hz(const BearingFrequencies& freq, FaultKind kind, int harmonics);

// A peak searched at expected_hz with its SNR and its chance (line_chance against the
// series' other lines).
SpectralPeak series_peak(const Spectrum& envelope, double expected_hz, const std::vector<double>& own_lines_hz,
                         const AnalysisOptions& o, const EvidenceContext& context);

// A line is found: a local maximum threshold_db over its floor that a window of its width
// holds by chance no more often than line_chance_max.
bool line_found(const SpectralPeak& p, double threshold_db, const DiagnosisThresholds& t);

// One series' own evidence: the fundamental (already in f->envelope_peak), harmonics 2 and 3,
// the sidebands where modulation is predicted and resolvable, the resolvability of the
// fundamental itself, and for a series without sideband evidence the impulsiveness of the
// envelope band. Sets f->suspected from these alone.
void collect_fault_evidence(const Spectrum& envelope, const BearingFrequencies& freq, const AnalysisOptions& o,
                            const EvidenceContext& context, const BandKurtosis& band, FaultIndicator* f);

// The verdict from the series left suspected after arbitrate_fault_series.
Verdict fault_verdict(const std::vector<FaultIndicator>& faults);

// Decisions between the suspected series (faults in the order outer, inner, ball, cage):
// a series found only on lines of a better-supported series (its sidebands, or the cage-rate
// comb of a stationary-race or ball series) or too close to one of its harmonics to be
// resolved is withdrawn, and the cage line beside a race or ball series is read as that
// series' cage-rate modulation.
void arbitrate_fault_series(const Spectrum& envelope, const BearingFrequencies& freq, const AnalysisOptions& o,
                            std::vector<FaultIndicator>* faults);

}  // namespace bearing_sim
