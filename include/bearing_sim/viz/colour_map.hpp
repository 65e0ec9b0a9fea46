#pragma once
// Colour map for ball contact loads (ROS-free).
//
// Loaded balls: viridis (matplotlib's perceptually uniform map, dark purple at zero load
// -> blue -> green -> yellow at full scale). Its luminance rises strictly along the map,
// so brighter always means more load, also in greyscale and for colour-blind readers.
// Balls out of contact (load <= 0) are neutral grey: "no contact" is a category, not a
// point on the scale.

namespace bearing_sim {
namespace viz {

struct Rgba {
  float r = 0.0f, g = 0.0f, b = 0.0f, a = 1.0f;
};

// Grey of the balls out of contact.
constexpr Rgba kUnloadedGrey{0.6f, 0.6f, 0.6f, 1.0f};

// Viridis at `fraction` in [0, 1] (clamped; NaN gives the start of the map).
Rgba viridis(double fraction);

// Colour of a ball carrying `load_N` on a scale 0..full_scale_N: grey for load <= 0 (or a
// non-finite load), viridis(load / full_scale) otherwise (clamped at full scale).
Rgba load_colour(double load_N, double full_scale_N);

// Rec. 709 luma of the (gamma-encoded) colour: the scalar that increases along viridis;
// tests and readers use it to order colours.
double luma(const Rgba& c);

// True for the unloaded grey (r = g = b, within float rounding).
bool is_grey(const Rgba& c);

}  // namespace viz
}  // namespace bearing_sim
