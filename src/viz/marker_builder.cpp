#include "bearing_sim/viz/marker_builder.hpp"

#include <cmath>
#include <cstdio>

#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/core/frequencies.hpp"

namespace bearing_sim {
namespace viz {
namespace {
geometry_msgs::Point point(const Eigen::Vector3d& p) {
  geometry_msgs::Point out;
  out.x = p.x();
  out.y = p.y();
  out.z = p.z();
  return out;
}

std_msgs::ColorRGBA colour(const Rgba& c) {
  std_msgs::ColorRGBA out;
  out.r = c.r;
  out.g = c.g;
  out.b = c.b;
  out.a = c.a;
  return out;
}

visualization_msgs::Marker base_marker(const std::string& frame, const ros::Time& stamp, const std::string& ns, int id,
                                       int type) {
  visualization_msgs::Marker m;
  m.header.frame_id = frame;
  m.header.stamp = stamp;
  m.ns = ns;
  m.id = id;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;  // rviz rejects the all-zero quaternion
  m.scale.x = m.scale.y = m.scale.z = 1.0;
  m.color.r = m.color.g = m.color.b = m.color.a = 1.0f;
  return m;
}

visualization_msgs::Marker deleted(const std::string& frame, const ros::Time& stamp, const std::string& ns, int id) {
  visualization_msgs::Marker m = base_marker(frame, stamp, ns, id, visualization_msgs::Marker::ARROW);
  m.action = visualization_msgs::Marker::DELETE;
  return m;
}

void add_segments(visualization_msgs::Marker* m, const std::vector<Segment>& segments) {
  for (const Segment& s : segments) {
    m->points.push_back(point(s.a));
    m->points.push_back(point(s.b));
    m->colors.push_back(colour(s.colour));
    m->colors.push_back(colour(s.colour));
  }
}

std::string format(const char* fmt, double a) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, a);
  return buf;
}
}  // namespace

Rgba polar_curve_colour(int row) { return row == 0 ? Rgba{1.0f, 0.55f, 0.1f, 1.0f} : Rgba{0.35f, 0.75f, 1.0f, 1.0f}; }

std::string status_text(const BearingScene& scene, const BearingModel& model, const BallLoadArrays& loads,
                        double level_db, double ring_speed_rad_s) {
  std::string text;
  if (scene.max_load_ball >= 0) {
    const int row = scene.max_load_ball / model.balls_per_row();
    double az_deg = loads.azimuth_rad[scene.max_load_ball] * 180.0 / kPi;
    if (az_deg < 0.0) az_deg += 360.0;
    text += "Q_max = " + format("%.0f N", scene.max_load_N) + " (row " + std::to_string(row + 1) + ", " +
            format("%.1f deg)", az_deg);
  } else {
    text += "Q_max = 0 N (no ball in contact)";
  }
  text += "\nL = " + (std::isfinite(level_db) ? format("%.1f dB", level_db) : std::string("-- dB"));
  const double rpm = ring_speed_rad_s * 60.0 / (2.0 * kPi);
  const double cage_hz = bearing_frequencies(model, ring_speed_rad_s).cage_hz;
  text += "\n" + std::string(model.config().rotating_ring == RotatingRing::Outer ? "outer" : "inner") + " ring " +
          format("%.1f rpm", rpm) + format(" (%.2f rad/s)", ring_speed_rad_s) + format(", cage %.3f Hz", cage_hz);
  text += "\nball colour: load 0.." + format("%.0f N", scene.full_scale_N) + " (viridis), grey: no contact";
  return text;
}

visualization_msgs::MarkerArray build_markers(const BearingScene& scene, const SceneExtras& extras,
                                              const MarkerFrames& frames, const ros::Time& stamp) {
  using visualization_msgs::Marker;
  visualization_msgs::MarkerArray out;
  const double ro = extras.bearing_outer_radius_m;
  const double line_width = 0.002 * ro / 0.5;  // 2 mm lines on a 1 m bearing

  for (std::size_t r = 0; r < scene.balls.size(); ++r) {
    const int id = static_cast<int>(r);
    Marker balls = base_marker(frames.bearing, stamp, "balls", id, Marker::SPHERE_LIST);
    balls.scale.x = balls.scale.y = balls.scale.z = scene.ball_display_diameter_m;
    for (const BallGlyph& g : scene.balls[r]) {
      balls.points.push_back(point(g.centre));
      balls.colors.push_back(colour(g.colour));
    }
    out.markers.push_back(balls);

    if (scene.force_arrows[r].empty()) {
      out.markers.push_back(deleted(frames.bearing, stamp, "contact_forces", id));
    } else {
      Marker arrows = base_marker(frames.bearing, stamp, "contact_forces", id, Marker::LINE_LIST);
      arrows.scale.x = 1.5 * line_width;
      add_segments(&arrows, scene.force_arrows[r]);
      out.markers.push_back(arrows);
    }

    Marker curve = base_marker(frames.bearing, stamp, "load_polar", id, Marker::LINE_STRIP);
    curve.scale.x = 1.5 * line_width;
    curve.color = colour(polar_curve_colour(id));
    for (const auto& p : scene.polar_curves[r]) curve.points.push_back(point(p));
    out.markers.push_back(curve);
  }

  Marker fixed = base_marker(frames.bearing, stamp, "fixed_ring", 0, Marker::LINE_LIST);
  fixed.scale.x = line_width;
  add_segments(&fixed, extras.fixed_ring_outline);
  out.markers.push_back(fixed);

  // Drawn in the rotating ring's own frame and locked to it, so rviz turns and shifts it
  // with the TF between marker updates.
  Marker rotating = base_marker(frames.rotating_ring, stamp, "rotating_ring", 0, Marker::LINE_LIST);
  rotating.scale.x = line_width;
  rotating.frame_locked = true;
  add_segments(&rotating, extras.rotating_ring_outline);
  out.markers.push_back(rotating);

  const Eigen::Vector3d radial_force(extras.applied_force_N.x(), extras.applied_force_N.y(), 0.0);
  if (radial_force.norm() > 0.0) {
    // From the centre towards the side the force pulls the moving ring to.
    Marker arrow = base_marker(frames.bearing, stamp, "applied_load", 0, Marker::ARROW);
    arrow.points.push_back(point(Eigen::Vector3d::Zero()));
    arrow.points.push_back(point(0.45 * ro * radial_force.normalized()));
    arrow.scale.x = 0.02 * ro;  // shaft diameter
    arrow.scale.y = 0.05 * ro;  // head diameter
    arrow.scale.z = 0.08 * ro;  // head length
    arrow.color = colour(Rgba{0.9f, 0.15f, 0.15f, 1.0f});
    out.markers.push_back(arrow);
    Marker label = base_marker(frames.bearing, stamp, "applied_load", 1, Marker::TEXT_VIEW_FACING);
    const Eigen::Vector3d at = (0.45 * ro + 0.12 * ro) * radial_force.normalized();
    label.pose.position = point(at + Eigen::Vector3d(0.0, 0.06 * ro, 0.0));
    label.scale.z = 0.05 * ro;
    label.color = arrow.color;
    // rviz's text font has no underscore: plain symbols.
    label.text = format("Fr = %.0f N", radial_force.norm());
    const Eigen::Vector2d moment(extras.applied_moment_Nm.x(), extras.applied_moment_Nm.y());
    if (moment.norm() > 0.0) label.text += format(", M = %.0f N m", moment.norm());
    out.markers.push_back(label);
  } else {
    out.markers.push_back(deleted(frames.bearing, stamp, "applied_load", 0));
    out.markers.push_back(deleted(frames.bearing, stamp, "applied_load", 1));
  }

  if (!extras.ring_deformation.empty()) {
    // Above the balls (z) so that the line is not hidden by them.
    Marker ring = base_marker(frames.bearing, stamp, "ring_deformation", 0, Marker::LINE_STRIP);
    ring.scale.x = 2.0 * line_width;
    ring.color = colour(Rgba{1.0f, 0.2f, 0.8f, 1.0f});
    for (const auto& p : extras.ring_deformation) ring.points.push_back(point(p));
    out.markers.push_back(ring);
    Marker label = base_marker(frames.bearing, stamp, "ring_deformation", 1, Marker::TEXT_VIEW_FACING);
    label.pose.position.x = 0.0;
    label.pose.position.y = 1.65 * ro;  // beyond the status text (1.4 ro, four lines)
    label.scale.z = 0.05 * ro;
    label.color = ring.color;
    label.text = extras.ring_deformation_label;
    out.markers.push_back(label);
  }

  Marker text = base_marker(frames.bearing, stamp, "status_text", 0, Marker::TEXT_VIEW_FACING);
  // Beyond the far side of the bearing (+y), clear of the rings and the polar curves.
  text.pose.position.x = 0.0;
  text.pose.position.y = 1.4 * ro;
  text.pose.position.z = 0.0;
  text.scale.z = 0.07 * ro;  // capital letter height
  text.text = extras.status_text;
  out.markers.push_back(text);

  // Colour bar in front of the bearing (-y side), 0 .. full scale, labelled at its ends.
  Marker bar = base_marker(frames.bearing, stamp, "colour_bar", 0, Marker::CUBE_LIST);
  const int steps = 20;
  const double bar_length = 1.2 * ro, cell = bar_length / steps, y_bar = -1.2 * ro;
  bar.scale.x = cell;
  bar.scale.y = 0.05 * ro;
  bar.scale.z = 0.01 * ro;
  for (int k = 0; k < steps; ++k) {
    bar.points.push_back(point(Eigen::Vector3d(-0.5 * bar_length + (k + 0.5) * cell, y_bar, 0.0)));
    bar.colors.push_back(colour(viridis((k + 0.5) / steps)));
  }
  out.markers.push_back(bar);
  for (int k = 0; k < 2; ++k) {
    Marker label = base_marker(frames.bearing, stamp, "colour_bar_text", k, Marker::TEXT_VIEW_FACING);
    label.pose.position.x = (k == 0 ? -1.0 : 1.0) * (0.5 * bar_length + 0.15 * ro);
    label.pose.position.y = y_bar;
    label.scale.z = 0.06 * ro;
    label.text = k == 0 ? std::string("0 N") : format("%.0f N", scene.full_scale_N);
    out.markers.push_back(label);
  }
  return out;
}

}  // namespace viz
}  // namespace bearing_sim
