#pragma once
// The evidence rule of the envelope diagnosis (docs/health.md, "Evidence"): what one fault
// series must show in the envelope spectrum to be suspected, and the decisions between
// series whose lines can stand for each other.
#include <vector>

#include "bearing_sim/core/condition_indicators.hpp"

namespace bearing_sim {

// One series' own evidence: the fundamental (already in f->envelope_peak), harmonics 2 and 3,
// the sidebands where modulation is predicted and resolvable, the resolvability of the
// fundamental itself, and for a series without sideband evidence the impulsiveness of the
// envelope band. Sets f->suspected from these alone.
void collect_fault_evidence(const Spectrum& envelope, const BearingFrequencies& freq, const AnalysisOptions& o,
                            const BandKurtosis& band, FaultIndicator* f);

// Decisions between the suspected series (faults in the order outer, inner, ball, cage):
// a series found only on lines of a better-supported series (its sidebands, or the cage-rate
// comb of a stationary-race or ball series) or too close to one of its harmonics to be
// resolved is withdrawn, and the cage line beside a race or ball series is read as that
// series' cage-rate modulation.
void arbitrate_fault_series(const Spectrum& envelope, const BearingFrequencies& freq, const AnalysisOptions& o,
                            std::vector<FaultIndicator>* faults);

}  // namespace bearing_sim
