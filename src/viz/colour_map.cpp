#include "bearing_sim/viz/colour_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace bearing_sim {
namespace viz {
namespace {
// matplotlib viridis sampled at 0, 0.1, ..., 1 (entries 0, 25/26, 51, ... of its 256-entry
// table); linear interpolation between them is within a few 1/255 of the full table.
constexpr std::array<std::array<float, 3>, 11> kViridis{{
    {0.267004f, 0.004874f, 0.329415f},
    {0.282623f, 0.140926f, 0.457517f},
    {0.253935f, 0.265254f, 0.529983f},
    {0.206756f, 0.371758f, 0.553117f},
    {0.163625f, 0.471133f, 0.558148f},
    {0.127568f, 0.566949f, 0.550556f},
    {0.134692f, 0.658636f, 0.517649f},
    {0.266941f, 0.748751f, 0.440573f},
    {0.477504f, 0.821444f, 0.318195f},
    {0.741388f, 0.873449f, 0.149561f},
    {0.993248f, 0.906157f, 0.143936f},
}};
}  // namespace

Rgba viridis(double fraction) {
  if (!(fraction > 0.0)) fraction = 0.0;  // also NaN
  fraction = std::min(fraction, 1.0);
  const double x = fraction * (kViridis.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(x), kViridis.size() - 2);
  const float t = static_cast<float>(x - static_cast<double>(i));
  const auto& p = kViridis[i];
  const auto& q = kViridis[i + 1];
  return Rgba{p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2]), 1.0f};
}

Rgba load_colour(double load_N, double full_scale_N) {
  if (!(load_N > 0.0) || !std::isfinite(load_N)) return kUnloadedGrey;
  // A zero or missing scale still shows contact: every loaded ball at the top of the map.
  if (!(full_scale_N > 0.0)) return viridis(1.0);
  return viridis(load_N / full_scale_N);
}

double luma(const Rgba& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

bool is_grey(const Rgba& c) { return std::abs(c.r - c.g) < 1e-6f && std::abs(c.g - c.b) < 1e-6f; }

}  // namespace viz
}  // namespace bearing_sim
