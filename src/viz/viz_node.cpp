#include "bearing_sim/viz/viz_node.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <geometry_msgs/TransformStamped.h>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/constants.hpp"
#include "bearing_sim/ros/private_parameters.hpp"
#include "bearing_sim/viz/viz_parameters.hpp"

namespace bearing_sim {
namespace viz {
namespace {
// The cage angle of the last BallLoads is carried forward at the cage speed between
// messages, but not further than this: a stalled simulation shows a stopped cage.
constexpr double kMaxCageExtrapolation_s = 0.5;

geometry_msgs::TransformStamped to_msg(const Eigen::Isometry3d& pose, const std::string& parent,
                                       const std::string& child, const ros::Time& stamp) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform.translation.x = pose.translation().x();
  t.transform.translation.y = pose.translation().y();
  t.transform.translation.z = pose.translation().z();
  const Eigen::Quaterniond q(pose.linear());
  t.transform.rotation.x = q.x();
  t.transform.rotation.y = q.y();
  t.transform.rotation.z = q.z();
  t.transform.rotation.w = q.w();
  return t;
}

}  // namespace

VizNode::VizNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), pnh_(private_nh), level_db_(std::numeric_limits<double>::quiet_NaN()) {
  // Every parameter checked before anything starts: a bad one stops the display, naming it.
  const VizParameters params = read_viz_parameters(ros_node::private_parameters(pnh_), pnh_.getNamespace());
  model_ = std::make_unique<BearingModel>(load_bearing_config(params.bearing_file));
  fixed_frame_ = params.fixed_frame;
  bearing_frame_ = params.bearing_frame;
  ring_frame_ = params.rotating_ring_frame;
  cage_frame_ = params.cage_frame;
  const double rate_hz = params.update_rate_hz;
  speed_rad_s_ = params.initial_speed_rad_s;
  exaggeration_ = params.displacement_exaggeration;
  deformation_magnification_ = params.deformation_magnification;
  colour_full_scale_N_ = params.colour_full_scale_N;
  display_.ball_scale = params.ball_scale;
  display_.force_arrow_length_m = params.force_arrow_length_m;
  display_.polar_curve_height_m = params.polar_curve_height_m;

  const bool outer_rotates = model_->config().rotating_ring == RotatingRing::Outer;
  const RingSection rotating = outer_rotates ? outer_ring_section(*model_) : inner_ring_section(*model_);
  const RingSection fixed = outer_rotates ? inner_ring_section(*model_) : outer_ring_section(*model_);
  extras_.rotating_ring_outline = ring_outline(rotating, 180, 24, Rgba{0.85f, 0.85f, 0.85f, 1.0f});
  extras_.fixed_ring_outline = ring_outline(fixed, 180, 0, Rgba{0.55f, 0.55f, 0.6f, 1.0f});
  extras_.bearing_outer_radius_m = 0.5 * model_->config().outer_diameter_m;

  markers_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("ball_markers", 1);
  ball_loads_sub_ = nh_.subscribe("ball_loads", 1, &VizNode::on_ball_loads, this);
  // Only a flexible ring deforms: no subscription (and nothing computed by the simulation) otherwise.
  if (model_->config().flexible_ring.present)
    deformation_sub_ = nh_.subscribe("ring_deformation", 1, &VizNode::on_ring_deformation, this);
  vibration_sub_ = nh_.subscribe("vibration", 10, &VizNode::on_vibration, this);
  level_sub_ = nh_.subscribe("vibration_level", 1, &VizNode::on_level, this);
  speed_sub_ = nh_.subscribe("speed", 1, &VizNode::on_speed, this);
  load_sub_ = nh_.subscribe("load", 1, &VizNode::on_load, this);

  // The bearing sits at the origin of the fixed frame, axes aligned: a fixed relation.
  static_tf_.sendTransform(to_msg(Eigen::Isometry3d::Identity(), fixed_frame_, bearing_frame_, ros::Time::now()));
  last_tick_ = ros::Time::now();
  timer_ = nh_.createTimer(ros::Duration(1.0 / rate_hz), &VizNode::on_timer, this);
  ROS_INFO("bearing_viz_node: %s, %d x %d balls, TF %s -> %s -> %s -> %s at %.0f Hz", model_->config().name.c_str(),
           model_->rows(), model_->balls_per_row(), fixed_frame_.c_str(), bearing_frame_.c_str(), ring_frame_.c_str(),
           cage_frame_.c_str(), rate_hz);
}

double VizNode::cage_speed_rad_s() const {
  double wi = 0.0, wo = 0.0;
  model_->ring_speeds(speed_rad_s_, &wi, &wo);
  return model_->cage_speed_rad_s(wi, wo);
}

void VizNode::on_ball_loads(const bearing_sim::BallLoads::ConstPtr& msg) {
  BallLoadArrays loads;
  loads.rows = msg->rows;
  loads.balls_per_row = msg->balls_per_row;
  loads.cage_angle_rad = msg->cage_angle;
  loads.azimuth_rad = msg->azimuth;
  loads.load_N = msg->load;
  loads.contact_angle_rad = msg->contact_angle;
  const std::string why = check_ball_loads(*model_, loads);
  if (!why.empty()) {
    ROS_WARN_THROTTLE(5.0, "bearing_viz_node: ignoring BallLoads: %s", why.c_str());
    return;
  }
  loads_ = std::move(loads);
  have_loads_ = true;
  loads_received_ = ros::Time::now();
  if (std::isfinite(msg->cage_angle)) cage_angle_rad_ = msg->cage_angle;
  for (float q : loads_.load_N) running_max_load_N_ = std::max(running_max_load_N_, static_cast<double>(q));
}

void VizNode::on_ring_deformation(const bearing_sim::RingDeformation::ConstPtr& msg) {
  extras_.ring_deformation = deformation_curve(model_->config().flexible_ring.centroid_radius_m, msg->azimuth,
                                               msg->radial, msg->axial, deformation_magnification_);
  if (extras_.ring_deformation.empty()) {
    ROS_WARN_THROTTLE(5.0, "bearing_viz_node: ignoring RingDeformation: azimuth, radial and axial differ in length");
    return;
  }
  float peak = 0.0f;
  for (float w : msg->radial) peak = std::max(peak, std::abs(w));
  // rviz's text font has no underscore or micro sign: plain symbols.
  char text[96];
  std::snprintf(text, sizeof text, "ring deformation x %.0f (peak radial %.1f um)", deformation_magnification_,
                1e6 * peak);
  extras_.ring_deformation_label = text;
}

void VizNode::on_vibration(const bearing_sim::VibrationChunk::ConstPtr& msg) {
  // The last sample is the newest position of the moving ring.
  if (msg->displacement_x.empty() || msg->displacement_y.size() != msg->displacement_x.size() ||
      msg->displacement_z.size() != msg->displacement_x.size()) {
    return;
  }
  const Eigen::Vector3d d(msg->displacement_x.back(), msg->displacement_y.back(), msg->displacement_z.back());
  if (d.allFinite()) displacement_m_ = d;
}

void VizNode::on_level(const bearing_sim::VibrationLevel::ConstPtr& msg) { level_db_ = msg->level_db; }

void VizNode::on_speed(const std_msgs::Float64::ConstPtr& msg) {
  if (!std::isfinite(msg->data)) {
    ROS_WARN_THROTTLE(5.0, "bearing_viz_node: ignoring non-finite speed");
    return;
  }
  speed_rad_s_ = msg->data;
}

void VizNode::on_load(const geometry_msgs::WrenchStamped::ConstPtr& msg) {
  const Eigen::Vector3d f(msg->wrench.force.x, msg->wrench.force.y, msg->wrench.force.z);
  const Eigen::Vector3d m(msg->wrench.torque.x, msg->wrench.torque.y, msg->wrench.torque.z);
  if (f.allFinite() && m.allFinite()) {
    extras_.applied_force_N = f;
    extras_.applied_moment_Nm = m;
  }
}

void VizNode::on_timer(const ros::TimerEvent&) {
  const ros::Time now = ros::Time::now();
  double dt = (now - last_tick_).toSec();
  if (dt < 0.0) dt = 0.0;  // time jumped back (bag or sim-time restart): hold
  last_tick_ = now;
  ring_angle_rad_ = std::remainder(ring_angle_rad_ + speed_rad_s_ * dt, 2.0 * kPi);

  double cage = cage_angle_rad_;
  if (have_loads_) {
    // The simulation's own cage angle, carried forward from the message's arrival.
    const double age = std::min(std::max((now - loads_received_).toSec(), 0.0), kMaxCageExtrapolation_s);
    cage = std::remainder(cage_angle_rad_ + cage_speed_rad_s() * age, 2.0 * kPi);
  } else {
    cage_angle_rad_ = std::remainder(cage_angle_rad_ + cage_speed_rad_s() * dt, 2.0 * kPi);
    cage = cage_angle_rad_;
  }

  const Eigen::Isometry3d ring = rotating_ring_pose(ring_angle_rad_, displacement_m_, exaggeration_);
  std::vector<geometry_msgs::TransformStamped> transforms{
      to_msg(ring, bearing_frame_, ring_frame_, now),
      to_msg(cage_pose_in_ring(ring, cage), ring_frame_, cage_frame_, now)};
  tf_.sendTransform(transforms);

  if (!have_loads_) return;  // nothing to colour yet
  const double scale = colour_full_scale_N_ > 0.0 ? colour_full_scale_N_ : running_max_load_N_;
  const BearingScene scene = build_scene(*model_, loads_, scale, display_);
  extras_.status_text = status_text(scene, *model_, loads_, level_db_, speed_rad_s_);
  MarkerFrames frames;
  frames.bearing = bearing_frame_;
  frames.rotating_ring = ring_frame_;
  markers_pub_.publish(build_markers(scene, extras_, frames, now));
}

}  // namespace viz
}  // namespace bearing_sim
