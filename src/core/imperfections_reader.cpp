// Reading of the `imperfections:` and `defects:` sections (imperfections_reader.hpp).
#include "imperfections_reader.hpp"

#include <cmath>
#include <cstdint>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/errors.hpp"
#include "yaml_reader.hpp"

namespace bearing_sim {

namespace {

// The surface named under `key` (default outer_race).
Surface surface_of(const detail::Reader& r, const std::string& key) {
  try {
    return parse_surface(r.text(key, "outer_race"));
  } catch (const InvalidInputError& e) {
    r.fail(key, e.what());
  }
}

// A row index of a bearing of `rows` rows, or `fallback` when the key is absent.
int row_of(const detail::Reader& r, const std::string& key, int fallback, int rows) {
  const int row = r.integer(key, fallback);
  if (r.has(key))
    r.require(row >= 0 && row < rows, key,
              rows == 1 ? "must be 0 (the bearing has one row)" : "must be 0 or 1 (the bearing has two rows)");
  return row;
}

// The scalar keys of `imperfections:` (all but the waviness list).
void read_imperfection_keys(const detail::Reader& r, int rows, ImperfectionSpec* out) {
  ImperfectionSpec& spec = *out;
  const int seed = r.integer("seed", 1);
  r.require(seed >= 0, "seed", "must be >= 0");
  spec.seed = static_cast<std::uint64_t>(seed);
  spec.ball_diameter_variation_m = r.number("ball_diameter_variation_um", 0.0) * 1e-6;
  r.require(spec.ball_diameter_variation_m >= 0.0, "ball_diameter_variation_um", "must be >= 0");
  spec.roughness_rms_m = r.number("roughness_rms_um", 0.0) * 1e-6;
  r.require(spec.roughness_rms_m >= 0.0, "roughness_rms_um", "must be >= 0");
  spec.roughness_row = row_of(r, "roughness_row", -1, rows);
  spec.ball_spacing_jitter_m = r.number("ball_spacing_jitter_mm", 0.0) * 1e-3;
  r.require(spec.ball_spacing_jitter_m >= 0.0, "ball_spacing_jitter_mm", "must be >= 0");
  spec.cage_slip = r.number("cage_slip_percent", 0.0) / 100.0;
  r.require(spec.cage_slip >= 0.0 && spec.cage_slip < 0.2, "cage_slip_percent", "must be in [0, 20)");
  spec.cage_slip_variation = r.number("cage_slip_variation_percent", 0.0) / 100.0;
  r.require(spec.cage_slip_variation >= 0.0 && spec.cage_slip_variation < 0.05, "cage_slip_variation_percent",
            "must be in [0, 5)");
  spec.cage_slip_correlation_s = r.number("cage_slip_correlation_s", 0.05);
  r.require(spec.cage_slip_correlation_s > 0.0, "cage_slip_correlation_s", "must be > 0");
  // A pocket clearance is a fraction of a millimetre; 2 mm is past any cage.
  spec.ball_place_wander_m = r.number("ball_place_wander_mm", 0.0) * 1e-3;
  r.require(spec.ball_place_wander_m >= 0.0 && spec.ball_place_wander_m < 2e-3, "ball_place_wander_mm",
            "must be in [0, 2) mm");
  spec.ball_place_wander_correlation_s = r.number("ball_place_wander_correlation_s", 0.05);
  r.require(spec.ball_place_wander_correlation_s >= 1e-4 && spec.ball_place_wander_correlation_s <= 1e3,
            "ball_place_wander_correlation_s", "must be in [1e-4, 1e3] s");
  spec.ball_spin_axis_wander_rad = r.number("ball_spin_axis_wander_deg", 0.0) * kPi / 180.0;
  r.require(spec.ball_spin_axis_wander_rad >= 0.0 && spec.ball_spin_axis_wander_rad < 0.5 * kPi,
            "ball_spin_axis_wander_deg", "must be in [0, 90) deg");
  spec.ball_spall_latitude_rad = r.number("ball_spall_latitude_deg", 0.0) * kPi / 180.0;
  r.require(spec.ball_spall_latitude_rad >= 0.0 && spec.ball_spall_latitude_rad <= 0.5 * kPi, "ball_spall_latitude_deg",
            "must be in [0, 90] deg");
  spec.ball_spin_axis_wander_correlation_s = r.number("ball_spin_axis_wander_correlation_s", 0.1);
  r.require(spec.ball_spin_axis_wander_correlation_s >= 1e-4 && spec.ball_spin_axis_wander_correlation_s <= 1e3,
            "ball_spin_axis_wander_correlation_s", "must be in [1e-4, 1e3] s");
  // The spin angle gained or lost per passage through the unloaded arc; past a half turn a
  // ball spall's phase (it meets a race every half turn) is lost at every passage anyway.
  spec.ball_spin_slip_rad = r.number("ball_spin_slip_deg", 0.0) * kPi / 180.0;
  r.require(spec.ball_spin_slip_rad >= 0.0 && spec.ball_spin_slip_rad <= kPi, "ball_spin_slip_deg",
            "must be in [0, 180] deg");
  spec.ball_spin_slip_azimuth_rad = r.number("ball_spin_slip_azimuth_deg", 180.0) * kPi / 180.0;
  r.require(std::abs(spec.ball_spin_slip_azimuth_rad) <= kTwoPi, "ball_spin_slip_azimuth_deg",
            "must be in [-360, 360] deg");
  const std::string edges = r.text("spall_edges", "rounded");
  r.require(edges == "rounded" || edges == "sharp", "spall_edges", "must be 'rounded' or 'sharp'");
  spec.spall_sharp_edges = edges == "sharp";
  const std::string pits = r.text("spall_pits", "trench");
  r.require(pits == "trench" || pits == "round", "spall_pits", "must be 'trench' or 'round'");
  spec.spall_round_pits = pits == "round";
  // A rim stands a few micrometres proud (an EDM recast lip); past 20 um it is no rim but a
  // bump the ball could not roll over. Its width is that of the contact's length, < 10 mm
  // on any bearing the package takes.
  spec.spall_rim_height_m = r.number("spall_rim_height_um", 0.0) * 1e-6;
  r.require(spec.spall_rim_height_m >= 0.0 && spec.spall_rim_height_m <= 20e-6, "spall_rim_height_um",
            "must be in [0, 20] um");
  r.require(spec.spall_rim_height_m == 0.0 || spec.spall_sharp_edges, "spall_rim_height_um",
            "needs spall_edges: sharp (a worn, rounded edge has no rim)");
  spec.spall_rim_width_m = r.number("spall_rim_width_um", 0.0, spec.spall_rim_height_m > 0.0) * 1e-6;
  r.require(spec.spall_rim_width_m >= 0.0 && spec.spall_rim_width_m < 10e-3, "spall_rim_width_um",
            "must be in [0, 10000) um (given with spall_rim_height_um)");
  r.require(spec.spall_rim_height_m == 0.0 || spec.spall_rim_width_m > 0.0, "spall_rim_width_um",
            "must be > 0 when spall_rim_height_um is");
}

// `imperfections.waviness`: a list of {surface, order, amplitude_um, phase_deg, row}.
void read_waviness(const detail::Reader& r, const YAML::Node& list, const std::string& source, int rows,
                   ImperfectionSpec* out) {
  if (!list.IsSequence()) r.fail("waviness", "expected a list of {surface, order, amplitude_um, phase_deg}");
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!list[i].IsMap()) r.fail("waviness[" + std::to_string(i) + "]", "expected a mapping");
    detail::Reader w(list[i], source, "imperfections.waviness[" + std::to_string(i) + "].");
    w.check_keys({"surface", "order", "amplitude_um", "phase_deg", "row"});
    Waviness wv;
    wv.surface = surface_of(w, "surface");
    wv.order = w.integer("order", 0, true);
    w.require(wv.order >= 1 && wv.order <= 2000, "order", "must be between 1 and 2000");
    wv.amplitude_m = w.number("amplitude_um", 0.0, true) * 1e-6;
    w.require(wv.amplitude_m >= 0.0 && wv.amplitude_m < 50e-6, "amplitude_um", "must be in [0, 50) um");
    wv.phase_rad = w.number("phase_deg", 0.0) * kPi / 180.0;
    wv.row = row_of(w, "row", -1, rows);
    out->waviness.push_back(wv);
  }
}

// `defects:`: a list of spalls {surface, position_deg, ball, row, width_mm, depth_um, growth}.
void read_defects(const YAML::Node& defects, const std::string& source, int rows, ImperfectionSpec* out) {
  if (!defects.IsSequence())
    throw ConfigError(source + ": key 'defects': expected a list of {surface, position_deg, width_mm, depth_um, ...}");
  for (std::size_t i = 0; i < defects.size(); ++i) {
    const std::string prefix = "defects[" + std::to_string(i) + "].";
    if (!defects[i].IsMap()) throw ConfigError(source + ": key '" + prefix + "': expected a mapping");
    detail::Reader d(defects[i], source, prefix);
    d.check_keys({"surface", "position_deg", "ball", "row", "width_mm", "depth_um", "width_growth_mm_per_hour",
                  "depth_growth_um_per_hour"});
    Spall s;
    s.surface = surface_of(d, "surface");
    if (s.surface == Surface::Ball && d.has("row"))
      d.fail("row", "not for a ball spall: the ball index (row-major) gives the row");
    s.row = row_of(d, "row", 0, rows);
    s.position_rad = d.number("position_deg", 0.0) * kPi / 180.0;
    s.ball = d.integer("ball", 0);
    s.width_m = d.number("width_mm", 0.0, true) * 1e-3;
    s.depth_m = d.number("depth_um", 0.0, true) * 1e-6;
    s.width_growth_m_per_s = d.number("width_growth_mm_per_hour", 0.0) * 1e-3 / 3600.0;
    s.depth_growth_m_per_s = d.number("depth_growth_um_per_hour", 0.0) * 1e-6 / 3600.0;
    d.require(s.width_m > 0.0, "width_mm", "must be > 0");
    d.require(s.depth_m > 0.0, "depth_um", "must be > 0");
    d.require(s.width_growth_m_per_s >= 0.0 && std::isfinite(s.width_growth_m_per_s), "width_growth_mm_per_hour",
              "must be finite and >= 0");
    d.require(s.depth_growth_m_per_s >= 0.0 && std::isfinite(s.depth_growth_m_per_s), "depth_growth_um_per_hour",
              "must be finite and >= 0");
    out->spalls.push_back(s);
  }
}

}  // namespace

ImperfectionSpec parse_imperfections(const YAML::Node& imperfections, const YAML::Node& defects,
                                     const std::string& source, int rows) {
  ImperfectionSpec spec;
  if (imperfections) {
    if (!imperfections.IsMap()) throw ConfigError(source + ": key 'imperfections': expected a mapping");
    detail::Reader r(imperfections, source, "imperfections.");
    r.check_keys({"seed",
                  "waviness",
                  "ball_diameter_variation_um",
                  "roughness_rms_um",
                  "roughness_row",
                  "ball_spacing_jitter_mm",
                  "cage_slip_percent",
                  "cage_slip_variation_percent",
                  "cage_slip_correlation_s",
                  "ball_place_wander_mm",
                  "ball_place_wander_correlation_s",
                  "ball_spin_axis_wander_deg",
                  "ball_spin_axis_wander_correlation_s",
                  "ball_spall_latitude_deg",
                  "ball_spin_slip_deg",
                  "ball_spin_slip_azimuth_deg",
                  "spall_edges",
                  "spall_rim_height_um",
                  "spall_rim_width_um",
                  "spall_pits"});
    read_imperfection_keys(r, rows, &spec);
    const YAML::Node list = imperfections["waviness"];
    if (list) read_waviness(r, list, source, rows, &spec);
  }
  if (defects) read_defects(defects, source, rows, &spec);
  return spec;
}

ImperfectionSpec imperfections_from_string(const std::string& yaml_text, const std::string& source, int rows) {
  const YAML::Node root = detail::load_yaml(yaml_text, source);
  if (!root || !root.IsMap())
    throw ConfigError(source + ": expected a YAML mapping with the keys imperfections and defects");
  detail::Reader(root, source, "").check_keys({"imperfections", "defects"});
  return parse_imperfections(root["imperfections"], root["defects"], source, rows);
}

ImperfectionSpec load_imperfections(const std::string& path, int rows) {
  return imperfections_from_string(detail::read_config_file(path, "imperfections file"), path, rows);
}

}  // namespace bearing_sim
