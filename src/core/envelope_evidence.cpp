#include "envelope_evidence.hpp"

#include <algorithm>
#include <cmath>

#include "bearing_sim/core/errors.hpp"
#include "fault_evidence.hpp"
#include "fixed_decimals.hpp"

namespace bearing_sim {
namespace {
constexpr FaultKind kKinds[] = {FaultKind::OuterRace, FaultKind::InnerRace, FaultKind::Ball, FaultKind::Cage};

double highest_fault_hz(const BearingFrequencies& freq) {
  double f = 0.0;
  for (FaultKind k : kKinds) f = std::max(f, fault_frequency_hz(freq, k));
  return f;
}

// Some band of the kurtogram's tree is wide enough and starts high enough: the half band
// [fs/4, fs/2] is the widest one off DC.
bool kurtogram_fits(double fs, double highest_hz, double lowest_edge_hz) {
  return 0.25 * fs >= 3.0 * highest_hz && 0.25 * fs >= lowest_edge_hz;
}

}  // namespace

EnvelopeBandChoice choose_envelope_band(const std::vector<double>& x, double fs, const BearingFrequencies& freq,
                                        const AnalysisOptions& o, EnvelopeBand band) {
  const double highest_hz = highest_fault_hz(freq);
  // Well above the fault lines themselves, so that the band holds the resonances they
  // excite rather than the lines (and their low harmonics).
  const double lowest_edge_hz = std::max(500.0, 4.0 * highest_hz);
  EnvelopeBandChoice c;
  if (o.resonance_hz > 0.0) {
    if (!(o.envelope_band_width_hz > 0.0)) throw InvalidInputError("analysis: the envelope band width must be > 0");
    c.low_hz = std::max(0.0, o.resonance_hz - 0.5 * o.envelope_band_width_hz);
    c.high_hz = o.resonance_hz + 0.5 * o.envelope_band_width_hz;
    c.source = "resonance";
  } else if (band == EnvelopeBand::Kurtogram && kurtogram_fits(fs, highest_hz, lowest_edge_hz)) {
    // The most impulsive band wide enough to hold harmonics 1-3 of every fault line.
    const Kurtogram k = fast_kurtogram(x, fs, 3.0 * highest_hz, lowest_edge_hz, 64, o.sensor_floor_m_s2_per_sqrt_hz);
    c.low_hz = k.best.low_hz;
    c.high_hz = k.best.high_hz;
    c.source = "kurtogram";
    c.kurtosis = BandKurtosis{true, k.best.kurtosis, k.best.independent_samples};
  } else {
    c.low_hz = lowest_edge_hz;
    c.high_hz = 0.4 * fs;
    c.source = "fixed";
  }
  const double nyquist = 0.5 * fs;
  if (!(c.high_hz <= nyquist) || !(c.low_hz < c.high_hz))
    throw InvalidInputError("analysis: envelope band " + detail::fixed_decimals(c.low_hz, 0) + "-" +
                            detail::fixed_decimals(c.high_hz, 0) + " Hz does not fit below the Nyquist frequency " +
                            detail::fixed_decimals(nyquist, 0) + " Hz (raise the sample rate or give resonance_hz)");
  // The band's impulsiveness, whichever way it was chosen (the evidence rule asks it of a
  // series without sidebands); the kurtogram has it already, by the same computation.
  if (!c.kurtosis.valid)
    c.kurtosis = band_spectral_kurtosis(x, fs, c.low_hz, c.high_hz, o.sensor_floor_m_s2_per_sqrt_hz);
  return c;
}

EnvelopeEvidence envelope_evidence(const std::vector<double>& demodulated, double fs, const BearingFrequencies& freq,
                                   const AnalysisOptions& o, const EnvelopeBandChoice& band,
                                   const EnvelopePathSettings& settings) {
  EnvelopeEvidence e;
  e.band = band;
  e.envelope = averaged_envelope_spectrum(demodulated, fs, band.low_hz, band.high_hz, settings.segment_samples,
                                          &e.segments, &e.envelope_mean);
  e.segment_s = static_cast<double>(settings.segment_samples) / fs;
  const double averages = equivalent_averages(e.segments);
  EvidenceContext context;
  context.fault_snr_db = e.fault_snr_db_used = averaged_threshold_db(o.thresholds.fault_snr_db, averages);
  context.evidence_snr_db = e.evidence_snr_db_used = averaged_threshold_db(o.thresholds.evidence_snr_db, averages);
  context.absolute_floor = settings.absolute_floor;
  context.segments = e.segments;
  context.band_width_hz = band.high_hz - band.low_hz;
  for (FaultKind k : kKinds) {
    FaultIndicator f;
    f.kind = k;
    f.envelope_peak = series_peak(e.envelope, fault_frequency_hz(freq, k), series_lines_hz(freq, k, 5), o, context);
    f.modulation = e.envelope_mean > 0.0 ? f.envelope_peak.amplitude / e.envelope_mean : 0.0;
    if (k != FaultKind::Cage && line_found(f.envelope_peak, context.fault_snr_db, o.thresholds))
      context.present.push_back(k);
    e.faults.push_back(f);
  }
  for (FaultIndicator& f : e.faults) collect_fault_evidence(e.envelope, freq, o, context, band.kurtosis, &f);
  for (FaultKind k : context.present) e.found_fundamentals.push_back(k);
  if (settings.whitened_fundamentals) {
    // Rule 10: where the recording has a broadband floor, a series found as recorded in a
    // band that is not impulsive and not even as a fundamental in the whitened envelope is
    // a deterministic line series (a speed-locked order of the machine), not impacts.
    const std::vector<FaultKind>& confirmed = *settings.whitened_fundamentals;
    for (FaultIndicator& f : e.faults) {
      if (!f.suspected || band.kurtosis.kurtosis >= o.thresholds.impulsive_band_kurtosis ||
          std::find(confirmed.begin(), confirmed.end(), f.kind) != confirmed.end())
        continue;
      f.suspected = false;
      f.note = "a line series in a band that is not impulsive (spectral kurtosis " +
               detail::fixed_decimals(band.kurtosis.kurtosis, 2) +
               ") and absent from the whitened envelope: deterministic lines of the machine, not impacts";
    }
  }
  arbitrate_fault_series(e.envelope, freq, o, &e.faults);
  e.verdict = fault_verdict(e.faults);
  return e;
}

}  // namespace bearing_sim
