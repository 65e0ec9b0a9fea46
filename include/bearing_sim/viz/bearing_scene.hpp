#pragma once
// What the ball-load display draws, in the bearing frame, computed from the core
// BearingModel (geometry) and the arrays of one BallLoads message (state). ROS-free, so
// the geometry is unit-tested without a ROS master.
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/viz/colour_map.hpp"

namespace bearing_sim {
namespace viz {

// The arrays of a BallLoads message (row-major, row 0 first).
struct BallLoadArrays {
  int rows = 0;
  int balls_per_row = 0;
  double cage_angle_rad = 0.0;
  std::vector<float> azimuth_rad;        // in the bearing frame
  std::vector<float> load_N;             // normal contact force
  std::vector<float> contact_angle_rad;  // loaded contact angle
};

// Empty if `loads` fits `model` (same rows, balls per row, array lengths, finite values),
// else why not.
std::string check_ball_loads(const BearingModel& model, const BallLoadArrays& loads);

struct DisplayOptions {
  // Display diameter / true ball diameter. Balls of 12 mm on a 1.1 m bearing are a few
  // pixels wide; the ball pitch (pi dm / Z = 16.9 mm for the CT bearing) is the largest
  // diameter that keeps neighbours apart.
  double ball_scale = 1.3;
  // Length of the contact-force arrow at full-scale load.
  double force_arrow_length_m = 0.08;
  // Radial height of the polar load curve at full-scale load, drawn outward from a base
  // circle just outside the outer ring so it never hides the balls.
  double polar_curve_height_m = 0.15;
  double polar_curve_gap_m = 0.02;  // base circle = outer envelope radius + gap
};

struct BallGlyph {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // bearing frame, m
  double load_N = 0.0;
  Rgba colour;
};

// A line segment (LINE_LIST pair) with one colour.
struct Segment {
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  Rgba colour;
};

struct BearingScene {
  double ball_display_diameter_m = 0.0;
  std::vector<std::vector<BallGlyph>> balls;               // [row][index in row]
  std::vector<std::vector<Segment>> force_arrows;          // [row]: shaft and head segments
  std::vector<std::vector<Eigen::Vector3d>> polar_curves;  // [row]: closed line strip
  double full_scale_N = 0.0;                               // the colour and length scale used
  double max_load_N = 0.0;
  int max_load_ball = -1;                    // row-major index, -1 when no ball is loaded
  std::vector<double> load_zone_centre_rad;  // [row], NaN when the row carries no load
};

// Builds the scene. `full_scale_N` <= 0 scales to this message's maximum load.
// Precondition: check_ball_loads(model, loads) is empty.
BearingScene build_scene(const BearingModel& model, const BallLoadArrays& loads, double full_scale_N,
                         const DisplayOptions& options = {});

// Centre of the load zone: the load-weighted circular mean of the azimuths of balls
// [begin, end), in (-pi, pi]; NaN when they carry no load.
double load_zone_centre_rad(const std::vector<float>& azimuth_rad, const std::vector<float>& load_N, std::size_t begin,
                            std::size_t end);

// Radial extent and width of the rings, from the configured envelope: the outer ring from
// just outside the ball centres to the outer diameter, the inner ring from the bore to
// just inside them (a quarter ball diameter each side of the pitch circle: the grooves).
struct RingSection {
  double inner_radius_m = 0.0, outer_radius_m = 0.0, width_m = 0.0;
};
RingSection outer_ring_section(const BearingModel& model);
RingSection inner_ring_section(const BearingModel& model);

// Outline of a ring as LINE_LIST segments in its own frame: the inner and outer edge
// circles on both faces, `tick_count` radial ticks on the top face (so that the rotation
// of the rotating ring can be seen) and a long marker tick at azimuth 0.
std::vector<Segment> ring_outline(const RingSection& section, int circle_segments, int tick_count, const Rgba& colour);

// The flexible ring's deformed centre line (a RingDeformation message), magnified: at each
// azimuth phi the point (R + m w) (cos phi, sin phi) and m u along the axis, R the ring's
// centroid radius, w and u the radial and axial displacements, m the magnification. Closed
// (the first point again at the end); empty when the arrays differ in length or are empty.
std::vector<Eigen::Vector3d> deformation_curve(double centroid_radius_m, const std::vector<float>& azimuth_rad,
                                               const std::vector<float>& radial_m, const std::vector<float>& axial_m,
                                               double magnification);
// Pose of the rotating ring in the bearing frame: turned by ring_angle_rad about z and
// shifted by the (exaggerated) displacement of the moving ring.
Eigen::Isometry3d rotating_ring_pose(double ring_angle_rad, const Eigen::Vector3d& displacement_m, double exaggeration);
// Pose of the cage in the rotating-ring frame, for a cage centred on the bearing axis
// (it rides on the balls, which sit on the pitch circle of the bearing frame) turned by
// cage_angle_rad in the bearing frame.
Eigen::Isometry3d cage_pose_in_ring(const Eigen::Isometry3d& ring_in_bearing, double cage_angle_rad);

// Yaw (rotation about z) of a pose, in (-pi, pi].
double yaw_rad(const Eigen::Isometry3d& pose);

}  // namespace viz
}  // namespace bearing_sim
