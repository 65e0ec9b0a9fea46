#pragma once
// bearing_viz_node: TF of the bearing's rings and cage, and the ball-load markers.
// A thin shell: the geometry comes from BearingModel (the same ~bearing_file as the
// simulation node), the drawing from bearing_scene / marker_builder.
#include <memory>
#include <string>

#include <bearing_sim/BallLoads.h>
#include <bearing_sim/RingDeformation.h>
#include <bearing_sim/VibrationChunk.h>
#include <bearing_sim/VibrationLevel.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/viz/marker_builder.hpp"

namespace bearing_sim {
namespace viz {

class VizNode {
 public:
  // Reads the parameters (see docs/visualization.md); throws std::runtime_error on a
  // missing or invalid ~bearing_file or parameter.
  VizNode(ros::NodeHandle nh, ros::NodeHandle private_nh);

 private:
  void on_ball_loads(const bearing_sim::BallLoads::ConstPtr& msg);
  void on_ring_deformation(const bearing_sim::RingDeformation::ConstPtr& msg);
  void on_vibration(const bearing_sim::VibrationChunk::ConstPtr& msg);
  void on_level(const bearing_sim::VibrationLevel::ConstPtr& msg);
  void on_speed(const std_msgs::Float64::ConstPtr& msg);
  void on_load(const geometry_msgs::WrenchStamped::ConstPtr& msg);
  void on_timer(const ros::TimerEvent& event);
  double cage_speed_rad_s() const;

  ros::NodeHandle nh_, pnh_;
  std::unique_ptr<BearingModel> model_;
  std::string fixed_frame_, bearing_frame_, ring_frame_, cage_frame_;
  double exaggeration_ = 1000.0;
  double deformation_magnification_ = 5000.0;
  double colour_full_scale_N_ = 0.0;  // <= 0: running maximum
  DisplayOptions display_;
  SceneExtras extras_;

  ros::Subscriber ball_loads_sub_, deformation_sub_, vibration_sub_, level_sub_, speed_sub_, load_sub_;
  ros::Publisher markers_pub_;
  tf2_ros::TransformBroadcaster tf_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  ros::Timer timer_;

  // State, all updated on the single callback thread.
  double speed_rad_s_ = 0.0;
  double ring_angle_rad_ = 0.0;
  double cage_angle_rad_ = 0.0;
  ros::Time last_tick_;
  Eigen::Vector3d displacement_m_ = Eigen::Vector3d::Zero();
  double level_db_;
  double running_max_load_N_ = 0.0;
  bool have_loads_ = false;
  BallLoadArrays loads_;
  ros::Time loads_received_;
};

}  // namespace viz
}  // namespace bearing_sim
