#include "fault_evidence.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "fixed_decimals.hpp"

namespace bearing_sim {
namespace {
constexpr int kHarmonics = 4;

// The lowest frequency told apart from its neighbour in the envelope spectrum: a line there
// has its search window (+-1 bin) outside the excluded main lobe (+-noise_exclude_bins) of
// a line at 0 Hz (the envelope's mean) or of its carrier.
double resolvable_hz_for(double resolution_hz, const AnalysisOptions& o) {
  return (o.peak_search.noise_exclude_bins + 2) * resolution_hz;
}
double resolvable_hz(const Spectrum& envelope, const AnalysisOptions& o) {
  return resolvable_hz_for(envelope.resolution_hz, o);
}

// Half width of find_peak's search window around f, Hz: +-tolerance_rel, at least
// tolerance_min_bins bins.
double search_half_width_hz(double f_hz, double resolution_hz, const PeakSearchOptions& o) {
  return std::max(o.tolerance_rel * f_hz, o.tolerance_min_bins * resolution_hz);
}

// The comb line m >= 1 of spacing `spacing_hz` whose search window holds x, or 0 when none
// does or the comb cannot be told (its spacing not wider than a window: then every
// frequency lies on it).
double comb_line(double x_hz, double spacing_hz, double resolution_hz, const PeakSearchOptions& o) {
  const double tol = search_half_width_hz(x_hz, resolution_hz, o);
  const double m = std::round(x_hz / spacing_hz);
  return m >= 1.0 && 2.0 * tol < spacing_hz && std::abs(x_hz - m * spacing_hz) <= tol ? m : 0.0;
}

FaultIndicator* find(std::vector<FaultIndicator>* faults, FaultKind kind) {
  for (FaultIndicator& f : *faults)
    if (f.kind == kind) return &f;
  return nullptr;
}

// Whether a line of series a (its fundamental as found, or that -+ k f_mod, k = 1, 2: the
// sidebands of its carrier, searched or not) sits within the peak search window of series
// b's fundamental as found: b may then be nothing but a's lines.
bool lines_coincide(const FaultIndicator& a, double a_fmod_hz, const FaultIndicator& b, double resolution_hz,
                    const PeakSearchOptions& o) {
  const double fb = b.envelope_peak.frequency_hz;
  const double tol = search_half_width_hz(fb, resolution_hz, o);
  for (int k = 0; k <= 2; ++k)
    for (double sign : {-1.0, 1.0})
      if (std::abs(a.envelope_peak.frequency_hz + sign * k * a_fmod_hz - fb) <= tol) return true;
  // Half orders m/2 of a's fundamental (m odd, up to 7/2): a loose housing or a ring rocking
  // in its seat is struck every other impact (period doubling), which puts lines at the
  // half orders; 1.5 BPFO of the 6205 lies 0.7 % from BPFI.
  for (int m = 1; m <= 7; m += 2)
    if (std::abs(0.5 * m * a.envelope_peak.frequency_hz - fb) <= tol) return true;
  return false;
}
// Whether the healthy varying compliance (Z |f_c|, balls passing the load zone) can give this
// series: the series lies on Z |f_c| (+-1 %, at least one bin), or is the cage line, and the
// bearing has few enough balls for the compliance to matter. Its excitation is the Z-th
// harmonic of the load distribution over the azimuth, which has a (cos psi - cos psi_l)^1.5
// edge at the load zone's limits: its harmonics fall as n^-2.5, i.e. 68 dB from Z = 9 (the
// 6205: series up to 31 dB over a quiet sensor) to Z = 207 (the CT bearing: none seen).
bool compliance_series(const BearingFrequencies& freq, FaultKind kind, double resolution_hz, const AnalysisOptions& o) {
  const double vc = freq.varying_compliance_hz, cage = std::abs(freq.cage_hz);
  if (!(vc > 0.0) || !(cage > 0.0) || vc / cage > o.thresholds.compliance_max_balls) return false;
  if (kind == FaultKind::Cage) return true;
  const double f = fault_frequency_hz(freq, kind);
  return std::abs(f - vc) <= search_half_width_hz(f, resolution_hz, o.peak_search);
}

// The spacing of the cage-rate comb that series a's envelope carries, as measured, or 0 when
// a does not repeat at the cage rate (docs/health.md, "Evidence", rule 8). A race standing in
// the load frame (its ball pass is Z |f_c|, the varying compliance's frequency) is struck by Z
// balls of unequal size in a pattern that repeats once per cage turn: an impact train of
// period 1 / |f_c|, whose lines lie at every multiple of |f_c| = its fundamental as found / Z.
// A spalled ball is carried through the load zone once per cage turn: its impacts are
// amplitude-modulated at |f_c|, and the modulation itself (the order-0 term of the train,
// whose first line is the cage line of rule 7) lies at the multiples of |f_c|, as found on
// the cage line or else as expected. A turning race is modulated at its ring speed instead.
double cage_comb_spacing_hz(const FaultIndicator& a, const FaultIndicator* cage, const BearingFrequencies& freq,
                            double resolution_hz, const PeakSearchOptions& o) {
  const double fc = std::abs(freq.cage_hz), vc = freq.varying_compliance_hz;
  if (!(fc > 0.0)) return 0.0;
  if (a.kind == FaultKind::Ball)
    return cage && !cage->harmonics.empty() && cage->harmonics[0].found ? cage->envelope_peak.frequency_hz : fc;
  if (a.kind == FaultKind::Cage || !(vc > 0.0)) return 0.0;
  const double f = fault_frequency_hz(freq, a.kind);
  if (std::abs(f - vc) > search_half_width_hz(f, resolution_hz, o)) return 0.0;
  return a.envelope_peak.frequency_hz / std::round(vc / fc);
}

// Whether every line a series was found on lies on the healthy compliance's cage-rate comb:
// with balls of unequal size the ball-pass excitation repeats once per cage turn, so its
// lines lie at every m |f_c|, not only at Z |f_c| and the cage line (rule 5). Only where the
// compliance matters (compliance_max_balls) and the comb can be told (spacing resolvable and
// wider than each line's search window).
bool lines_on_compliance_comb(const FaultIndicator& f, const BearingFrequencies& freq, double resolution_hz,
                              const AnalysisOptions& o) {
  const double fc = std::abs(freq.cage_hz), vc = freq.varying_compliance_hz;
  if (!(fc > 0.0) || !(vc > 0.0) || vc / fc > o.thresholds.compliance_max_balls ||
      fc < resolvable_hz_for(resolution_hz, o))
    return false;
  const auto on_comb = [&](const EvidenceLine& l) {
    return comb_line(l.peak.frequency_hz, fc, resolution_hz, o.peak_search) > 0.0;
  };
  for (int n = 0; n < f.harmonics_found; ++n)
    if (!on_comb(f.harmonics[static_cast<std::size_t>(n)])) return false;
  for (const EvidenceLine& sb : f.sidebands)
    if (sb.found && !on_comb(sb)) return false;
  return f.harmonics_found > 0;
}
}  // namespace

std::vector<double> series_lines_hz(const BearingFrequencies& freq, FaultKind kind, int harmonics) {
  const double f0 = fault_frequency_hz(freq, kind), fm = modulation_frequency_hz(freq, kind);
  const int orders = fm > 0.0 ? 2 : 0;  // the sidebands rule 6 counts as the series' own
  std::vector<double> lines;
  for (int n = 1; n <= harmonics; ++n)
    for (int j = -orders; j <= orders; ++j) lines.push_back(n * f0 + j * fm);
  return lines;
}

SpectralPeak series_peak(const Spectrum& envelope, double expected_hz, const std::vector<double>& own_lines_hz,
                         const AnalysisOptions& o, const EvidenceContext& context) {
  SpectralPeak p = find_peak(envelope, expected_hz, o.peak_search, context.absolute_floor);
  // A single spectrum's maxima are its own noise's (a maximum every third bin or so), against
  // which the single-spectrum thresholds are set: the density is asked of averages only.
  if (context.segments < 2) {
    p.chance = 0.0;
    return p;
  }
  p.chance = line_chance(envelope, p, search_half_width_hz(expected_hz, envelope.resolution_hz, o.peak_search),
                         own_lines_hz, o.thresholds.line_neighbourhood_rel, o.peak_search);
  return p;
}

bool line_found(const SpectralPeak& p, double threshold_db, const DiagnosisThresholds& t) {
  return p.searched && p.local_maximum && p.snr_db >= threshold_db && p.chance <= t.line_chance_max;
}

Verdict fault_verdict(const std::vector<FaultIndicator>& faults) {
  Verdict v;
  bool cage = false;
  for (const FaultIndicator& f : faults) {
    if (!f.suspected) continue;
    if (f.kind == FaultKind::Cage) cage = true;
    else v.kinds.push_back(f.kind);
  }
  if (v.kinds.empty() && cage) v.kinds = {FaultKind::Ball, FaultKind::Cage};  // cage-rate lines alone
  if (v.kinds.empty()) {
    v.text = "no bearing defect indicated";
    return v;
  }
  v.outcome = v.kinds.size() == 1 ? VerdictOutcome::Fault : VerdictOutcome::Ambiguous;
  if (v.outcome == VerdictOutcome::Fault) {
    v.text = std::string(fault_kind_name(v.kinds[0])) + " defect";
    return v;
  }
  v.text = "cannot tell between ";
  for (std::size_t i = 0; i < v.kinds.size(); ++i)
    v.text += std::string(i == 0 ? "" : i + 1 == v.kinds.size() ? " and " : ", ") + fault_kind_name(v.kinds[i]);
  v.text += cage && v.kinds[0] == FaultKind::Ball && v.kinds.size() == 2 && v.kinds[1] == FaultKind::Cage
                ? " (cage-rate lines alone: a cage defect or a ball defect's modulation)"
                : " defects (each series has evidence of its own; one defect or both)";
  return v;
}

void collect_fault_evidence(const Spectrum& envelope, const BearingFrequencies& freq, const AnalysisOptions& o,
                            const EvidenceContext& context, const BandKurtosis& band, FaultIndicator* f) {
  const DiagnosisThresholds& t = o.thresholds;
  const double min_hz = resolvable_hz(envelope, o);
  const std::vector<double> own = series_lines_hz(freq, f->kind, kHarmonics + 1);
  // Visible: above the lowest resolvable frequency, and within what the envelope of the band
  // can carry (its width) and its spectrum shows (below its last bins).
  const double expected_hz = f->envelope_peak.expected_hz;
  const double last_hz = envelope.frequency_hz(envelope.amplitude.empty() ? 0 : envelope.amplitude.size() - 2);
  const bool too_high = !(expected_hz <= std::min(context.band_width_hz, last_hz));
  f->resolvable = envelope.resolution_hz > 0.0 && expected_hz >= min_hz && !too_high;
  EvidenceLine first;
  first.peak = f->envelope_peak;
  first.found = f->resolvable && line_found(first.peak, context.fault_snr_db, t);
  f->harmonics.push_back(first);
  // Higher harmonics at n x the fundamental as found (as expected if it was not found); one
  // within the window of a line of another series that is present is shared: evidence for
  // neither (rule 10).
  const double base_hz = first.found ? first.peak.frequency_hz : first.peak.expected_hz;
  const double nominal_hz = fault_frequency_hz(freq, f->kind);
  const auto half_width = [&](double hz) { return search_half_width_hz(hz, envelope.resolution_hz, o.peak_search); };
  for (int n = 2; n <= kHarmonics; ++n) {
    EvidenceLine h;
    h.order = n;
    h.peak = series_peak(envelope, n * base_hz, own, o, context);
    h.found = f->resolvable && line_found(h.peak, context.evidence_snr_db, t);
    for (FaultKind other : context.present) {
      if (other == f->kind || f->kind == FaultKind::Cage) continue;
      // Only between series told apart at their fundamentals (else rule 6 decides between
      // them), and harmonic on harmonic: the sidebands' coincidences are rule 6's too.
      const double other_hz = fault_frequency_hz(freq, other);
      if (std::abs(other_hz - nominal_hz) <= half_width(other_hz) + half_width(nominal_hz)) continue;
      for (int m = 1; m <= 3; ++m)  // the other series' fundamental and the harmonics it is judged on
        if (std::abs(n * nominal_hz - m * other_hz) <= half_width(n * nominal_hz) + half_width(m * other_hz))
          h.shared = true;
    }
    f->harmonics.push_back(h);
  }
  f->harmonics_found = 0;
  for (const EvidenceLine& h : f->harmonics) {
    if (h.shared) continue;
    if (!h.found) break;
    ++f->harmonics_found;
  }
  // Sidebands: only when the modulation is resolvable, i.e. the sideband's search window
  // (+-1 bin at least) lies outside the carrier's excluded main lobe (+-noise_exclude_bins).
  const double fm = modulation_frequency_hz(freq, f->kind);
  if (f->resolvable && fm >= min_hz && base_hz - fm > min_hz) {
    f->sidebands_required = f->kind != FaultKind::Ball;  // rule 3: a ball's are support, not a requirement
    f->modulation_hz = fm;
    for (double sign : {-1.0, 1.0}) {
      EvidenceLine sb;
      sb.offset_hz = sign * fm;
      sb.peak = series_peak(envelope, base_hz + sign * fm, own, o, context);
      sb.found = line_found(sb.peak, context.evidence_snr_db, t);
      f->sidebands_found += sb.found ? 1 : 0;
      f->sidebands.push_back(sb);
    }
  }
  const bool lines = first.found && f->harmonics_found >= 2 && (!f->sidebands_required || f->sidebands_found >= 1);
  // A series at the varying-compliance frequency Z |f_c| (the stationary race's ball pass)
  // without sidebands, or the cage line (balls of unequal size repeat once per cage turn), is
  // also what a healthy bearing's ball-pass excitation gives, and so is a series found only on
  // that excitation's cage-rate comb m |f_c| (e.g. the 6205's 2xBSF = 11.8 |f_c| within 1 %
  // of 12 |f_c| with cage slip): impacts must then show as an impulsive band (docs/health.md,
  // "Evidence", rule 5).
  const bool on_comb = lines && lines_on_compliance_comb(*f, freq, envelope.resolution_hz, o);
  f->impulsiveness_required =
      t.impulsive_band_kurtosis > 0.0 &&
      ((!f->sidebands_required && compliance_series(freq, f->kind, envelope.resolution_hz, o)) || on_comb);
  f->band_kurtosis = band.kurtosis;
  f->impulsive = !f->impulsiveness_required || band.kurtosis >= t.impulsive_band_kurtosis;
  f->suspected = lines && f->impulsive;
  if (too_high)
    f->note = std::string(fault_frequency_label(f->kind)) + " " + detail::fixed_decimals(expected_hz, 1) +
              " Hz lies above what the envelope can show (band " + detail::fixed_decimals(context.band_width_hz, 0) +
              " Hz wide, spectrum to " + detail::fixed_decimals(last_hz, 0) + " Hz): the analysis cannot see it";
  else if (!f->resolvable)
    f->note = std::string(fault_frequency_label(f->kind)) + " " +
              detail::fixed_decimals(f->envelope_peak.expected_hz, 2) + " Hz is not resolvable in a " +
              detail::fixed_decimals(1.0 / envelope.resolution_hz, 2) + " s window (" +
              detail::fixed_decimals(envelope.resolution_hz, 2) + " Hz bins); a window of at least " +
              detail::fixed_decimals(resolvable_hz_for(1.0, o) / f->envelope_peak.expected_hz, 1) + " s is needed";
  else if (lines && !f->impulsive)
    f->note = std::string(on_comb ? "lines on the cage-rate comb (m x " +
                                        detail::fixed_decimals(std::abs(freq.cage_hz), 2) + " Hz)"
                                  : "lines without sidebands") +
              " in a band that is not impulsive (spectral kurtosis " + detail::fixed_decimals(band.kurtosis, 2) +
              " < " + detail::fixed_decimals(t.impulsive_band_kurtosis, 1) +
              "): the varying compliance of a healthy bearing";
}

void arbitrate_fault_series(const Spectrum& envelope, const BearingFrequencies& freq, const AnalysisOptions& o,
                            std::vector<FaultIndicator>* faults) {
  // Series whose lines stand for each other (e.g. outer ring turning: BPFO + f_r lies within
  // 1 % of BPFI): a series whose fundamental is a line of another's pattern (its fundamental
  // -+ 0, 1, 2 f_mod) is withdrawn, unless that one's fundamental is a line of its own pattern
  // as well and the stronger.
  const FaultKind kinds[] = {FaultKind::OuterRace, FaultKind::InnerRace, FaultKind::Ball};
  for (FaultKind ka : kinds) {
    for (FaultKind kb : kinds) {
      FaultIndicator* a = find(faults, ka);
      FaultIndicator* b = find(faults, kb);
      if (ka == kb || !a || !b || !a->suspected || !b->suspected) continue;
      // b's fundamental is a line of a's pattern; a's is not one of b's, or both are (their
      // lines overlap, e.g. a modulation too slow to resolve) and a is the stronger.
      const double df = envelope.resolution_hz;
      if (!lines_coincide(*a, modulation_frequency_hz(freq, ka), *b, df, o.peak_search)) continue;
      if (lines_coincide(*b, modulation_frequency_hz(freq, kb), *a, df, o.peak_search) &&
          a->envelope_peak.snr_db < b->envelope_peak.snr_db)
        continue;
      b->suspected = false;
      b->note = std::string("its fundamental is a line of the stronger ") + fault_frequency_label(ka) + " series (" +
                detail::fixed_decimals(a->envelope_peak.snr_db, 0) + " dB, -+" +
                detail::fixed_decimals(modulation_frequency_hz(freq, ka), 2) + " Hz sidebands)";
    }
  }
  // A series on the cage-rate comb of a stronger one (rule 8): a stationary-race or ball
  // series has a line at every multiple m |f_c| (cage_comb_spacing_hz); a weaker series whose
  // fundamental as found lies within its search window of one is no evidence of its own
  // (618/22: BPFO = 8.09 |f_c|, and BPFI = 10 |f_c| on a ball spall's comb). Only where the
  // comb is resolvable (spacing of at least the resolvable frequency of rule 4, and wider
  // than the window: beyond 50 |f_c| every frequency lies on it).
  const FaultIndicator* cage_line = find(faults, FaultKind::Cage);
  const double min_hz = resolvable_hz(envelope, o);
  for (FaultKind ka : kinds) {
    const FaultIndicator* a = find(faults, ka);
    if (!a || !a->suspected) continue;
    const double spacing = cage_comb_spacing_hz(*a, cage_line, freq, envelope.resolution_hz, o.peak_search);
    if (!(spacing >= min_hz)) continue;
    for (FaultKind kb : kinds) {
      FaultIndicator* b = find(faults, kb);
      if (kb == ka || !b || !b->suspected || !(b->envelope_peak.snr_db < a->envelope_peak.snr_db)) continue;
      const double m = comb_line(b->envelope_peak.frequency_hz, spacing, envelope.resolution_hz, o.peak_search);
      if (m == 0.0) continue;
      b->suspected = false;
      b->note = "its fundamental is line " + detail::fixed_decimals(m, 0) + " of the cage-rate comb (" +
                detail::fixed_decimals(spacing, 2) + " Hz) of the stronger " + fault_frequency_label(ka) + " series (" +
                detail::fixed_decimals(a->envelope_peak.snr_db, 0) + " dB)";
    }
  }
  // A series too close to a stronger one's harmonic (found) to be told from it (rule 9): a line within
  // (noise_exclude_bins + 2) bins of another is not resolvable from it (rule 4's measure: 5 Hz
  // in 1 s), and a turning race's harmonics are smeared over a few Hz by the cage slip's
  // fluctuation (BPFO = Z (f_o - f_c) wanders by Z df_c, n times that at the n-th harmonic).
  for (FaultKind ka : kinds) {
    const FaultIndicator* a = find(faults, ka);
    if (!a || !a->suspected) continue;
    for (FaultKind kb : kinds) {
      FaultIndicator* b = find(faults, kb);
      if (kb == ka || !b || !b->suspected || !(b->envelope_peak.snr_db < a->envelope_peak.snr_db)) continue;
      for (std::size_t n = 0; n < a->harmonics.size(); ++n) {
        const EvidenceLine& h = a->harmonics[n];
        const double line = h.peak.frequency_hz;
        if (!h.found || std::abs(b->envelope_peak.frequency_hz - line) >= min_hz) continue;
        b->suspected = false;
        b->note = "its fundamental lies within " + detail::fixed_decimals(min_hz, 1) + " Hz of harmonic " +
                  std::to_string(n + 1) + " (" + detail::fixed_decimals(line, 2) + " Hz) of the stronger " +
                  fault_frequency_label(ka) + " series (" + detail::fixed_decimals(a->envelope_peak.snr_db, 0) +
                  " dB): not resolvable from it";
        break;
      }
    }
  }
  // The cage line beside a race or ball series: with balls of unequal size the impacts (and
  // the healthy ball-pass excitation) repeat once per cage turn, so that series carries FTF.
  FaultIndicator* cage = find(faults, FaultKind::Cage);
  if (!cage || !cage->suspected) return;
  for (FaultKind k : kinds) {
    const FaultIndicator* f = find(faults, k);
    if (!f || !f->suspected) continue;
    cage->suspected = false;
    cage->note = std::string("cage-rate modulation of the ") + fault_frequency_label(k) +
                 " series (balls of unequal size), not a cage defect of its own";
    return;
  }
}

}  // namespace bearing_sim
