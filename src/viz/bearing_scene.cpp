#include "bearing_sim/viz/bearing_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "bearing_sim/core/constants.hpp"

namespace bearing_sim {
namespace viz {
namespace {
Eigen::Vector3d on_circle(double radius, double azimuth, double z) {
  return Eigen::Vector3d(radius * std::cos(azimuth), radius * std::sin(azimuth), z);
}
}  // namespace

std::string check_ball_loads(const BearingModel& model, const BallLoadArrays& loads) {
  std::ostringstream why;
  const std::size_t n = static_cast<std::size_t>(model.ball_count());
  if (loads.rows != model.rows() || loads.balls_per_row != model.balls_per_row()) {
    why << "BallLoads has " << loads.rows << " x " << loads.balls_per_row << " balls, the bearing file " << model.rows()
        << " x " << model.balls_per_row();
  } else if (loads.azimuth_rad.size() != n || loads.load_N.size() != n || loads.contact_angle_rad.size() != n) {
    why << "BallLoads arrays have " << loads.azimuth_rad.size() << "/" << loads.load_N.size() << "/"
        << loads.contact_angle_rad.size() << " entries (azimuth/load/contact_angle), expected " << n;
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      if (!std::isfinite(loads.azimuth_rad[i]) || !std::isfinite(loads.load_N[i]) ||
          !std::isfinite(loads.contact_angle_rad[i])) {
        why << "BallLoads entry " << i << " is not finite";
        break;
      }
    }
  }
  return why.str();
}

double load_zone_centre_rad(const std::vector<float>& azimuth_rad, const std::vector<float>& load_N, std::size_t begin,
                            std::size_t end) {
  double s = 0.0, c = 0.0, total = 0.0;
  for (std::size_t i = begin; i < end; ++i) {
    const double q = std::max(0.0f, load_N[i]);
    s += q * std::sin(azimuth_rad[i]);
    c += q * std::cos(azimuth_rad[i]);
    total += q;
  }
  if (!(total > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return std::atan2(s, c);
}

BearingScene build_scene(const BearingModel& model, const BallLoadArrays& loads, double full_scale_N,
                         const DisplayOptions& options) {
  const auto& cfg = model.config();
  const int rows = model.rows(), z = model.balls_per_row();
  const double rp = model.pitch_radius_m();
  BearingScene scene;
  scene.ball_display_diameter_m = cfg.ball_diameter_m * options.ball_scale;
  const double ball_radius_shown = 0.5 * scene.ball_display_diameter_m;

  for (int b = 0; b < model.ball_count(); ++b) {
    if (loads.load_N[b] > scene.max_load_N) {
      scene.max_load_N = loads.load_N[b];
      scene.max_load_ball = b;
    }
  }
  scene.full_scale_N = full_scale_N > 0.0 ? full_scale_N : scene.max_load_N;

  const double polar_base = 0.5 * cfg.outer_diameter_m + options.polar_curve_gap_m;
  scene.balls.resize(rows);
  scene.force_arrows.resize(rows);
  scene.polar_curves.resize(rows);
  for (int r = 0; r < rows; ++r) {
    const double zr = model.row_axial_position_m(r);
    const int cr = model.row_contact_sign(r);
    for (int j = 0; j < z; ++j) {
      const int b = r * z + j;
      const double phi = loads.azimuth_rad[b], q = std::max(0.0f, loads.load_N[b]);
      BallGlyph glyph;
      glyph.centre = on_circle(rp, phi, zr);
      glyph.load_N = q;
      glyph.colour = load_colour(q, scene.full_scale_N);
      scene.balls[r].push_back(glyph);

      const double fraction = scene.full_scale_N > 0.0 ? std::min(q / scene.full_scale_N, 1.0) : 0.0;
      scene.polar_curves[r].push_back(on_circle(polar_base + options.polar_curve_height_m * fraction, phi, zr));

      if (q > 0.0) {
        // Force of the outer raceway on the ball: along the loaded contact line (docs/model.md
        // section 5.2, e = (cos a cos phi, cos a sin phi, c_r sin a) from inner to outer
        // contact), pointing inward, its head on the ball's surface.
        const double a = loads.contact_angle_rad[b];
        const Eigen::Vector3d e(std::cos(a) * std::cos(phi), std::cos(a) * std::sin(phi), cr * std::sin(a));
        const double length = options.force_arrow_length_m * fraction;
        const Eigen::Vector3d head = glyph.centre + ball_radius_shown * e;
        const Eigen::Vector3d tail = head + length * e;
        // Arrow head: two barbs in the plane of the shaft and the tangent direction, which
        // faces a camera looking along the bearing axis.
        const Eigen::Vector3d tangent(-std::sin(phi), std::cos(phi), 0.0);
        const double barb = 0.3 * length;
        Segment shaft{tail, head, glyph.colour};
        Segment left{head, head + barb * (0.8 * e + 0.5 * tangent), glyph.colour};
        Segment right{head, head + barb * (0.8 * e - 0.5 * tangent), glyph.colour};
        scene.force_arrows[r].push_back(shaft);
        scene.force_arrows[r].push_back(left);
        scene.force_arrows[r].push_back(right);
      }
    }
    // Close the curve. Azimuths increase with the index within a row (base azimuth
    // 2 pi j / Z plus the common cage angle), so the strip goes once round.
    if (!scene.polar_curves[r].empty()) scene.polar_curves[r].push_back(scene.polar_curves[r].front());
    scene.load_zone_centre_rad.push_back(load_zone_centre_rad(
        loads.azimuth_rad, loads.load_N, static_cast<std::size_t>(r) * z, static_cast<std::size_t>(r + 1) * z));
  }
  return scene;
}

RingSection outer_ring_section(const BearingModel& model) {
  const auto& c = model.config();
  return RingSection{model.pitch_radius_m() + 0.25 * c.ball_diameter_m, 0.5 * c.outer_diameter_m, c.width_m};
}

RingSection inner_ring_section(const BearingModel& model) {
  const auto& c = model.config();
  return RingSection{0.5 * c.inner_diameter_m, model.pitch_radius_m() - 0.25 * c.ball_diameter_m, c.width_m};
}

std::vector<Segment> ring_outline(const RingSection& s, int circle_segments, int tick_count, const Rgba& colour) {
  std::vector<Segment> out;
  const double h = 0.5 * s.width_m;
  for (double radius : {s.inner_radius_m, s.outer_radius_m}) {
    for (double zf : {-h, h}) {
      for (int k = 0; k < circle_segments; ++k) {
        const double a0 = 2.0 * kPi * k / circle_segments, a1 = 2.0 * kPi * (k + 1) / circle_segments;
        out.push_back(Segment{on_circle(radius, a0, zf), on_circle(radius, a1, zf), colour});
      }
    }
  }
  for (int k = 0; k < tick_count; ++k) {
    const double a = 2.0 * kPi * k / tick_count;
    out.push_back(Segment{on_circle(s.inner_radius_m, a, h), on_circle(s.outer_radius_m, a, h), colour});
  }
  // Azimuth-0 mark: the tick continued across the face and down the outer surface.
  out.push_back(Segment{on_circle(s.outer_radius_m, 0.0, h), on_circle(s.outer_radius_m, 0.0, -h), colour});
  out.push_back(Segment{on_circle(s.inner_radius_m, 0.0, h), on_circle(s.inner_radius_m, 0.0, -h), colour});
  return out;
}

std::vector<Eigen::Vector3d> deformation_curve(double centroid_radius_m, const std::vector<float>& azimuth_rad,
                                               const std::vector<float>& radial_m, const std::vector<float>& axial_m,
                                               double magnification) {
  std::vector<Eigen::Vector3d> curve;
  const std::size_t n = azimuth_rad.size();
  if (n == 0 || radial_m.size() != n || axial_m.size() != n) return curve;
  curve.reserve(n + 1);
  for (std::size_t i = 0; i < n; ++i) {
    const double r = centroid_radius_m + magnification * radial_m[i];
    curve.emplace_back(r * std::cos(azimuth_rad[i]), r * std::sin(azimuth_rad[i]), magnification * axial_m[i]);
  }
  curve.push_back(curve.front());
  return curve;
}

Eigen::Isometry3d rotating_ring_pose(double ring_angle_rad, const Eigen::Vector3d& displacement_m,
                                     double exaggeration) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = exaggeration * displacement_m;
  pose.linear() = Eigen::AngleAxisd(ring_angle_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return pose;
}

Eigen::Isometry3d cage_pose_in_ring(const Eigen::Isometry3d& ring_in_bearing, double cage_angle_rad) {
  Eigen::Isometry3d cage_in_bearing = Eigen::Isometry3d::Identity();
  cage_in_bearing.linear() = Eigen::AngleAxisd(cage_angle_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return ring_in_bearing.inverse() * cage_in_bearing;
}

double yaw_rad(const Eigen::Isometry3d& pose) {
  const Eigen::Matrix3d r = pose.linear();
  return std::atan2(r(1, 0), r(0, 0));
}

}  // namespace viz
}  // namespace bearing_sim
