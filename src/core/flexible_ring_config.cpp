#include "flexible_ring_config.hpp"

#include <algorithm>
#include <cmath>

namespace bearing_sim::detail {
namespace {

// Thin-ring theory needs a bending wavelength (2 pi R / n) well above the section depth; 50
// is already more modes than that allows for the shipped rings, and than the dynamics need.
constexpr int kMaxOrder = 50;

// St Venant torsion constant of a solid rectangle with sides a >= b (Roark, table 10.7).
double rectangle_torsion_constant(double side1, double side2) {
  const double a = std::max(side1, side2), b = std::min(side1, side2);
  const double r = b / a;
  return a * b * b * b * (1.0 / 3.0 - 0.21 * r * (1.0 - r * r * r * r / 12.0));
}

int read_order(const Reader& r, const std::string& key, int fallback, bool allow_zero) {
  const int n = r.integer(key, fallback, !allow_zero);
  const bool ok = (n >= 2 && n <= kMaxOrder) || (allow_zero && n == 0);
  r.require(ok, key,
            std::string("must be ") + (allow_zero ? "0 (none) or " : "") + "between 2 and " +
                std::to_string(kMaxOrder) +
                " (the highest mode order n; n = 0 and 1 are the rigid ring's motion), got " + std::to_string(n));
  return n;
}

}  // namespace

void read_flexible_ring(const Reader& r, BearingConfig* c) {
  r.check_keys({"ring", "section_width_mm", "section_height_mm", "section_area_mm2", "in_plane_second_moment_mm4",
                "out_of_plane_second_moment_mm4", "torsion_constant_mm4", "centroid_radius_mm", "youngs_modulus_GPa",
                "density_kg_m3", "in_plane_max_order", "out_of_plane_max_order", "modal_damping_ratio",
                "mounting_radial_stiffness_N_per_m2", "mounting_axial_stiffness_N_per_m2"});
  FlexibleRingSpec& s = c->flexible_ring;
  s.present = true;
  const std::string ring = r.text("ring", "rotating");
  r.require(ring == "rotating", "ring",
            "must be rotating (the moving ring; a flexible fixed ring is not modelled yet), got '" + ring + "'");

  // Section: a rectangle width (axial) x height (radial), each property replaceable by its own key.
  const bool rectangle = r.has("section_width_mm") || r.has("section_height_mm");
  const bool all_given = r.has("section_area_mm2") && r.has("in_plane_second_moment_mm4") &&
                         r.has("out_of_plane_second_moment_mm4") && r.has("torsion_constant_mm4");
  double b = 0.0, h = 0.0;
  if (rectangle || !all_given) {
    b = r.number("section_width_mm", 0.0, true) * 1e-3;
    r.require(b > 0.0, "section_width_mm", "must be > 0 (axial width of the ring's section)");
    h = r.number("section_height_mm", 0.0, true) * 1e-3;
    r.require(h > 0.0, "section_height_mm", "must be > 0 (radial height of the ring's section)");
  }
  const auto property = [&r](const std::string& key, double rectangle_value, double scale) {
    const double v = r.number(key, rectangle_value / scale) * scale;
    r.require(v > 0.0, key, "must be > 0");
    return v;
  };
  s.area_m2 = property("section_area_mm2", b * h, 1e-6);
  s.in_plane_second_moment_m4 = property("in_plane_second_moment_mm4", b * h * h * h / 12.0, 1e-12);
  s.out_of_plane_second_moment_m4 = property("out_of_plane_second_moment_mm4", h * b * b * b / 12.0, 1e-12);
  s.torsion_constant_m4 = property("torsion_constant_mm4", b > 0.0 ? rectangle_torsion_constant(b, h) : 0.0, 1e-12);

  // Default centroid: half the section height inside the outer ring's outer diameter (outside
  // the inner ring's bore), i.e. a ring whose section fills the envelope's edge.
  const bool outer = c->rotating_ring == RotatingRing::Outer;
  const double envelope_edge = outer ? c->outer_diameter_m / 2.0 : c->inner_diameter_m / 2.0;
  const double default_radius = outer ? envelope_edge - h / 2.0 : envelope_edge + h / 2.0;
  s.centroid_radius_m = r.number("centroid_radius_mm", default_radius * 1e3, !(h > 0.0)) * 1e-3;
  r.require(s.centroid_radius_m > 0.0 && s.centroid_radius_m < 100.0 * c->pitch_diameter_m, "centroid_radius_mm",
            "must be > 0 and within 100 pitch diameters");
  // Thin ring: the section small against the radius (Soedel's curved-beam theory).
  const double depth =
      std::sqrt(12.0 * std::max(s.in_plane_second_moment_m4, s.out_of_plane_second_moment_m4) / s.area_m2);
  r.require(depth < 0.5 * s.centroid_radius_m, "centroid_radius_mm",
            "the section is too deep for a thin ring (its depth must be below half the radius)");

  s.youngs_modulus_Pa = r.number("youngs_modulus_GPa", c->material.youngs_modulus_Pa * 1e-9) * 1e9;
  r.require(s.youngs_modulus_Pa > 0.0, "youngs_modulus_GPa", "must be > 0");
  s.shear_modulus_Pa = s.youngs_modulus_Pa / (2.0 * (1.0 + c->material.poisson_ratio));
  s.density_kg_m3 = r.number("density_kg_m3", c->material.density_kg_m3);
  r.require(s.density_kg_m3 > 0.0, "density_kg_m3", "must be > 0");

  s.in_plane_max_order = read_order(r, "in_plane_max_order", 0, false);
  s.out_of_plane_max_order = read_order(r, "out_of_plane_max_order", 0, true);
  s.modal_damping_ratio = r.number("modal_damping_ratio", 0.01);
  r.require(s.modal_damping_ratio >= 0.0 && s.modal_damping_ratio <= 0.3, "modal_damping_ratio",
            "must be in [0, 0.3] (a fraction of critical damping of each ring mode)");
  s.mounting_radial_stiffness_N_per_m2 = r.number("mounting_radial_stiffness_N_per_m2", 0.0);
  r.require(s.mounting_radial_stiffness_N_per_m2 >= 0.0, "mounting_radial_stiffness_N_per_m2", "must be >= 0");
  s.mounting_axial_stiffness_N_per_m2 = r.number("mounting_axial_stiffness_N_per_m2", 0.0);
  r.require(s.mounting_axial_stiffness_N_per_m2 >= 0.0, "mounting_axial_stiffness_N_per_m2", "must be >= 0");
}

}  // namespace bearing_sim::detail
