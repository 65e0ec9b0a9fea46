// Reading of the bearing file (bearing_config.hpp, bearing_config_reader.hpp).
#include "bearing_config_reader.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "bearing_sim/core/modal_damping.hpp"
#include "flexible_ring_config.hpp"
#include "imperfections_reader.hpp"
#include "yaml_reader.hpp"

namespace bearing_sim {
namespace {
using detail::Reader;

// A list of exactly n finite numbers under `key`, if present.
void read_numbers(const Reader& r, const YAML::Node& map, const std::string& key, std::size_t n, double* out) {
  const YAML::Node node = map[key];
  if (!node) return;
  if (!node.IsSequence() || node.size() != n) r.fail(key, "expected a list of " + std::to_string(n) + " numbers");
  for (std::size_t i = 0; i < n; ++i) {
    double v = 0.0;
    try {
      if (!node[i].IsScalar()) throw YAML::Exception(YAML::Mark(), "");
      v = node[i].as<double>();
    } catch (const YAML::Exception&) {
      r.fail(key, "expected a list of " + std::to_string(n) + " numbers");
    }
    if (!std::isfinite(v)) r.fail(key, "must be finite, got '" + node[i].Scalar() + "'");
    out[i] = v;
  }
}

// damping: either c_n per contact or the modal ratio of the radial mode (docs/model.md 7.3).
void read_damping(const Reader& dr, const YAML::Node& map, BearingConfig* c) {
  dr.check_keys({"contact_damping_Ns_per_m", "modal_damping_ratio", "reference_force_N", "reference_moment_Nm"});
  const bool per_contact = dr.has("contact_damping_Ns_per_m"), modal = dr.has("modal_damping_ratio");
  if (per_contact == modal)
    dr.fail(per_contact ? "modal_damping_ratio" : "contact_damping_Ns_per_m",
            "give exactly one of damping.contact_damping_Ns_per_m (per contact) and damping.modal_damping_ratio "
            "(of the radial mode)");
  if (per_contact) {
    dr.require(!dr.has("reference_force_N") && !dr.has("reference_moment_Nm"), "reference_force_N",
               "belongs to damping.modal_damping_ratio, not to a per-contact damping");
    c->contact_damping_Ns_per_m = dr.number("contact_damping_Ns_per_m", 0.0);
    dr.require(c->contact_damping_Ns_per_m >= 0.0, "contact_damping_Ns_per_m", "must be >= 0");
    return;
  }
  c->modal_damping_ratio = dr.number("modal_damping_ratio", 0.0);
  // 0.3 is far above any bearing's (lubricated steel contacts: 0.01-0.05); 0 means no damping.
  dr.require(c->modal_damping_ratio >= 0.0 && c->modal_damping_ratio <= 0.3, "modal_damping_ratio",
             "must be in [0, 0.3] (a fraction of critical damping; bearings have 0.01-0.05)");
  read_numbers(dr, map, "reference_force_N", 3, c->damping_reference_load.data());
  read_numbers(dr, map, "reference_moment_Nm", 2, c->damping_reference_load.data() + 3);
  dr.require(c->has_dynamics(), "modal_damping_ratio", "needs rotating_mass_kg (the ratio is of a mode of the ring)");
}

// carried_body: {mass_kg, centre_of_gravity_axial_mm, transverse_inertia_kg_m2, polar_inertia_kg_m2}.
void read_carried_body(const Reader& br, BearingConfig* c) {
  br.check_keys({"mass_kg", "centre_of_gravity_axial_mm", "transverse_inertia_kg_m2", "polar_inertia_kg_m2"});
  CarriedBody& b = c->carried_body;
  b.mass_kg = br.number("mass_kg", 0.0);
  br.require(br.has("mass_kg") && b.mass_kg > 0.0, "mass_kg", "must be given and > 0");
  br.require(c->has_dynamics(), "mass_kg", "needs rotating_mass_kg (the body moves with the rotating ring)");
  b.centre_of_gravity_axial_m = br.number("centre_of_gravity_axial_mm", 0.0) * 1e-3;
  br.require(std::abs(b.centre_of_gravity_axial_m) <= 100.0 * c->pitch_diameter_m, "centre_of_gravity_axial_mm",
             "must be within 100 pitch diameters of the bearing centre");
  b.transverse_inertia_kg_m2 = br.number("transverse_inertia_kg_m2", 0.0);
  br.require(br.has("transverse_inertia_kg_m2") && b.transverse_inertia_kg_m2 > 0.0, "transverse_inertia_kg_m2",
             "must be given and > 0 (about the centre of gravity)");
  b.polar_inertia_kg_m2 = br.number("polar_inertia_kg_m2", 0.0);
  br.require(b.polar_inertia_kg_m2 >= 0.0, "polar_inertia_kg_m2", "must be >= 0");
}

// c_n from the ratio at the reference load, once, when the file is read: c_n is then a fixed
// property of the contacts, and the ratio follows the load as a real bearing's does.
void resolve_modal_damping(const Reader& dr, BearingConfig* c) {
  Vector5 load;
  for (int i = 0; i < 5; ++i) load[i] = c->damping_reference_load[i];
  try {
    const BearingModel model(*c);
    c->contact_damping_Ns_per_m = contact_damping_for_ratio(model, load, c->modal_damping_ratio);
  } catch (const std::exception& e) {  // LoadNotCarriedError, InvalidInputError, ConfigError
    dr.fail("modal_damping_ratio", std::string("cannot be met at the reference load (damping.reference_force_N, "
                                               "damping.reference_moment_Nm; zero if absent): ") +
                                       e.what());
  }
}

// The ball and pitch diameters and the row spacing as the file gives them, mm: the envelope's
// defaults are made of them.
struct SizesMm {
  double d = 0.0, dm = 0.0, s = 0.0;
};

// Rows, arrangement, balls, pitch circle, row spacing and phase, contact angle, grooves, clearance.
SizesMm read_geometry(const Reader& r, BearingConfig* out) {
  BearingConfig& c = *out;
  c.rows = r.integer("rows", 1);
  r.require(c.rows == 1 || c.rows == 2, "rows", "must be 1 or 2, got " + std::to_string(c.rows));

  const std::string arrangement = r.text("arrangement", "back_to_back");
  if (arrangement == "back_to_back") c.arrangement = Arrangement::BackToBack;
  else if (arrangement == "face_to_face") c.arrangement = Arrangement::FaceToFace;
  else r.fail("arrangement", "must be back_to_back or face_to_face, got '" + arrangement + "'");

  c.balls_per_row = r.integer("balls_per_row", 0, true);
  r.require(c.balls_per_row >= 3 && c.balls_per_row <= 5000, "balls_per_row",
            "must be between 3 and 5000, got " + std::to_string(c.balls_per_row));

  const double d_mm = r.number("ball_diameter_mm", 0.0, true);
  r.require(d_mm > 0.0, "ball_diameter_mm", "must be > 0");
  const double dm_mm = r.number("pitch_diameter_mm", 0.0, true);
  r.require(dm_mm > d_mm, "pitch_diameter_mm", "must be larger than ball_diameter_mm");
  r.require(dm_mm <= kMaxPitchDiameterM * 1e3, "pitch_diameter_mm",
            "must be at most " + std::to_string(static_cast<int>(kMaxPitchDiameterM * 1e3)) +
                " mm (the largest slewing bearings are about 10 m)");
  r.require(c.balls_per_row * d_mm < kPi * dm_mm, "balls_per_row",
            "the balls do not fit on the pitch circle (Z d >= pi dm)");
  c.ball_diameter_m = d_mm * 1e-3;
  c.pitch_diameter_m = dm_mm * 1e-3;

  const double s_mm = r.number("row_spacing_mm", 0.0, c.rows == 2);
  if (c.rows == 2) r.require(s_mm > 0.0, "row_spacing_mm", "must be > 0 for two rows");
  else r.require(s_mm >= 0.0, "row_spacing_mm", "must be >= 0");
  c.row_spacing_m = s_mm * 1e-3;
  const double row_phase_deg = r.number("row_phase_deg", 0.0);
  // Beyond a turn the phase means nothing more, and huge values lose every digit of it.
  r.require(std::abs(row_phase_deg) <= 360.0, "row_phase_deg", "must be in [-360, 360] deg");
  c.row_phase_rad = row_phase_deg * kPi / 180.0;

  const double a0_deg = r.number("contact_angle_deg", 0.0);
  r.require(a0_deg >= 0.0 && a0_deg < 60.0, "contact_angle_deg", "must be in [0, 60) deg");
  c.contact_angle_rad = a0_deg * kPi / 180.0;

  c.inner_groove_curvature = r.number("inner_groove_curvature", 0.0, true);
  r.require(c.inner_groove_curvature > 0.5 && c.inner_groove_curvature < 1.0, "inner_groove_curvature",
            "must be in (0.5, 1.0) (groove radius / ball diameter)");
  c.outer_groove_curvature = r.number("outer_groove_curvature", 0.0, true);
  r.require(c.outer_groove_curvature > 0.5 && c.outer_groove_curvature < 1.0, "outer_groove_curvature",
            "must be in (0.5, 1.0) (groove radius / ball diameter)");

  const double g0_um = r.number("clearance_um", 0.0);
  r.require(std::abs(g0_um * 1e-6) < 0.05 * c.ball_diameter_m, "clearance_um",
            "magnitude must be below 5% of the ball diameter");
  c.clearance_m = g0_um * 1e-6;
  return {d_mm, dm_mm, s_mm};
}

// Outer and inner diameter and width; by default a ring section two ball diameters deep and
// 1.5 wide.
void read_envelope(const Reader& r, const SizesMm& mm, BearingConfig* out) {
  BearingConfig& c = *out;
  const double d_mm = mm.d, dm_mm = mm.dm, s_mm = mm.s;
  c.outer_diameter_m = r.number("outer_diameter_mm", dm_mm + 2.0 * d_mm) * 1e-3;
  c.inner_diameter_m = r.number("inner_diameter_mm", dm_mm - 2.0 * d_mm) * 1e-3;
  c.width_m = r.number("width_mm", std::max(1.5 * d_mm, 1.5 * d_mm + s_mm)) * 1e-3;
  r.require(c.outer_diameter_m > c.pitch_diameter_m, "outer_diameter_mm", "must exceed pitch_diameter_mm");
  r.require(c.inner_diameter_m > 0.0 && c.inner_diameter_m < c.pitch_diameter_m, "inner_diameter_mm",
            "must be > 0 and below pitch_diameter_mm");
  r.require(c.width_m > 0.0, "width_mm", "must be > 0");
}

// The rotating ring: which one, its material, mass and tilt inertia (given, or derived from
// the envelope).
void read_rotating_ring(const Reader& r, BearingConfig* out) {
  BearingConfig& c = *out;
  const std::string ring = r.text("rotating_ring", "outer");
  if (ring == "outer") c.rotating_ring = RotatingRing::Outer;
  else if (ring == "inner") c.rotating_ring = RotatingRing::Inner;
  else r.fail("rotating_ring", "must be outer or inner, got '" + ring + "'");

  if (const YAML::Node m = r.map("material")) {
    Reader mr(m, r.source(), "material.");
    mr.check_keys({"youngs_modulus_GPa", "poisson_ratio", "density_kg_m3"});
    c.material.youngs_modulus_Pa = mr.number("youngs_modulus_GPa", 208.0) * 1e9;
    mr.require(c.material.youngs_modulus_Pa > 0.0, "youngs_modulus_GPa", "must be > 0");
    c.material.poisson_ratio = mr.number("poisson_ratio", 0.3);
    mr.require(c.material.poisson_ratio > 0.0 && c.material.poisson_ratio < 0.5, "poisson_ratio",
               "must be in (0, 0.5)");
    c.material.density_kg_m3 = mr.number("density_kg_m3", 7850.0);
    mr.require(c.material.density_kg_m3 > 0.0, "density_kg_m3", "must be > 0");
  }

  c.rotating_mass_kg = r.number("rotating_mass_kg", 0.0);
  r.require(c.rotating_mass_kg >= 0.0 && (c.rotating_mass_kg > 0.0 || !r.has("rotating_mass_kg")), "rotating_mass_kg",
            "must be > 0");

  c.tilt_inertia_given = r.has("tilt_inertia_kg_m2");
  c.tilt_inertia_kg_m2 = r.number("tilt_inertia_kg_m2", 0.0);
  if (c.tilt_inertia_given) r.require(c.tilt_inertia_kg_m2 > 0.0, "tilt_inertia_kg_m2", "must be > 0");
  else {
    // Thick ring about a diameter, over the moving ring's side of the pitch circle.
    const double ro = c.rotating_ring == RotatingRing::Outer ? c.outer_diameter_m / 2 : c.pitch_diameter_m / 2;
    const double ri = c.rotating_ring == RotatingRing::Outer ? c.pitch_diameter_m / 2 : c.inner_diameter_m / 2;
    c.tilt_inertia_kg_m2 = c.rotating_mass_kg * (3.0 * (ro * ro + ri * ri) + c.width_m * c.width_m) / 12.0;
  }
}

}  // namespace

BearingConfig parse_bearing_config(const YAML::Node& root, const std::string& source) {
  if (!root || !root.IsMap()) throw ConfigError(source + ": expected a YAML mapping of bearing keys");
  Reader r(root, source, "");
  r.check_keys({"name",
                "rows",
                "arrangement",
                "balls_per_row",
                "ball_diameter_mm",
                "pitch_diameter_mm",
                "row_spacing_mm",
                "row_phase_deg",
                "contact_angle_deg",
                "inner_groove_curvature",
                "outer_groove_curvature",
                "clearance_um",
                "outer_diameter_mm",
                "inner_diameter_mm",
                "width_mm",
                "rotating_ring",
                "material",
                "rotating_mass_kg",
                "tilt_inertia_kg_m2",
                "carried_body",
                "damping",
                "imperfections",
                "defects",
                "flexible_ring"});

  BearingConfig c;
  c.name = r.text("name", "unnamed bearing");

  const SizesMm mm = read_geometry(r, &c);
  read_envelope(r, mm, &c);
  read_rotating_ring(r, &c);

  if (const YAML::Node body = r.map("carried_body")) read_carried_body(Reader(body, source, "carried_body."), &c);
  if (const YAML::Node flexible = r.map("flexible_ring"))
    detail::read_flexible_ring(Reader(flexible, source, "flexible_ring."), &c);
  const YAML::Node dmp = r.map("damping");
  if (dmp) read_damping(Reader(dmp, source, "damping."), dmp, &c);
  c.imperfections = parse_imperfections(root["imperfections"], root["defects"], source, c.rows);
  if (c.imperfections.ball_spacing_jitter_m > 0.1 * kPi * c.pitch_diameter_m / c.balls_per_row)
    throw ConfigError(source +
                      ": key 'imperfections.ball_spacing_jitter_mm': must be below a tenth of the ball "
                      "pitch, or balls would overlap");
  if (c.modal_damping_ratio > 0.0) resolve_modal_damping(Reader(dmp, source, "damping."), &c);
  return c;
}

BearingConfig bearing_config_from_string(const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = detail::load_yaml(yaml_text, source);
  return parse_bearing_config(root, source);
}

BearingConfig load_bearing_config(const std::string& path) {
  return bearing_config_from_string(detail::read_config_file(path, "bearing file"), path);
}

}  // namespace bearing_sim
