#pragma once
// Turns a BearingScene into the visualization_msgs::MarkerArray of the display
// (ROS-light: message types only, no node handle, so it is unit-tested without a master).
//
// Namespaces and ids are stable, so rviz updates the markers in place:
//   balls          id = row  SPHERE_LIST, one sphere per ball (index in row), bearing frame
//   contact_forces id = row  LINE_LIST arrows on the loaded balls (DELETE when none)
//   load_polar     id = row  LINE_STRIP polar curve of the row's load distribution
//   fixed_ring     id 0      LINE_LIST outline of the fixed ring, bearing frame
//   rotating_ring  id 0      LINE_LIST outline of the rotating ring, rotating-ring frame
//   applied_load   id 0, 1   ARROW along the applied radial force and its label (DELETE when none)
//   ring_deformation id 0, 1 LINE_STRIP the flexible ring's magnified centre line and its label
//                            (only with a flexible ring: nothing is sent otherwise)
//   status_text    id 0      TEXT_VIEW_FACING: max ball load, L, speed, colour scale
//   colour_bar     id 0      CUBE_LIST legend of the colour map; colour_bar_text id 0, 1
#include <string>

#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>

#include "bearing_sim/viz/bearing_scene.hpp"

namespace bearing_sim {
namespace viz {

struct MarkerFrames {
  std::string bearing = "bearing";              // balls, curves, fixed ring, text
  std::string rotating_ring = "rotating_ring";  // rotating-ring outline
};

struct SceneExtras {
  std::vector<Segment> fixed_ring_outline;                    // in the bearing frame
  std::vector<Segment> rotating_ring_outline;                 // in the rotating-ring frame
  Eigen::Vector3d applied_force_N = Eigen::Vector3d::Zero();  // on the moving ring, bearing frame
  Eigen::Vector3d applied_moment_Nm = Eigen::Vector3d::Zero();
  double bearing_outer_radius_m = 0.5;  // places the text, legend and load arrow
  std::string status_text;
  // The flexible ring's magnified centre line (deformation_curve) and its label; empty: none.
  std::vector<Eigen::Vector3d> ring_deformation;
  std::string ring_deformation_label;
};

// Status line shown above the bearing. level_db NaN: no VibrationLevel received yet.
std::string status_text(const BearingScene& scene, const BearingModel& model, const BallLoadArrays& loads,
                        double level_db, double ring_speed_rad_s);

visualization_msgs::MarkerArray build_markers(const BearingScene& scene, const SceneExtras& extras,
                                              const MarkerFrames& frames, const ros::Time& stamp);

// Polar curve colours of rows 1 and 2 (row 1 orange, row 2 light blue).
Rgba polar_curve_colour(int row);

}  // namespace viz
}  // namespace bearing_sim
