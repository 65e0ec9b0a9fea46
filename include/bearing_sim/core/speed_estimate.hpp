#pragma once
// The shaft speed as the recording shows it (docs/health.md, "Speed from the signal"): a
// speed read off a tachometer, a display or by hand is often off by a percent or two, the
// width of a fault line's search window. The turning ring's unbalance and misalignment put
// lines at 1, 2 and 3 x its speed; where they stand clear, they give the speed.
#include <vector>

#include "bearing_sim/core/frequencies.hpp"

namespace bearing_sim {

struct SpeedEstimate {
  bool measured = false;                      // the lines agreed and stood clear: scale applies
  double scale = 1.0;                         // measured / given speed
  double implied_scale[3] = {0.0, 0.0, 0.0};  // from harmonics 1, 2, 3 (0: none found)
};

struct SpeedEstimateOptions {
  double tolerance_rel = 0.03;   // search each harmonic within +-3 % of the given speed
  double line_snr_db = 20.0;     // over the median of +-30 bins around it
  double agreement_rel = 0.003;  // two of the three speeds within this of their median
};

// From the Hann amplitude spectrum of x: for h = 1, 2, 3 the largest bin within
// +-tolerance_rel of h f (Gaussian interpolation) and its SNR; the speed is measured when
// at least two of the three lines stand line_snr_db clear and their implied speeds agree
// within agreement_rel of their median (one line may be another source's, e.g. the supply
// at 60 Hz beside 2 x 29.95 Hz), and the search window spans at least 4 bins.
SpeedEstimate estimate_speed_scale(const std::vector<double>& x, double sample_rate_hz, double ring_hz,
                                   const SpeedEstimateOptions& options = {});

// All the frequencies multiplied by s (they are proportional to the speed at a fixed
// contact angle).
BearingFrequencies scaled_frequencies(const BearingFrequencies& f, double s);

}  // namespace bearing_sim
