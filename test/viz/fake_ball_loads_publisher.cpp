// Test helper standing in for bearing_sim_node: publishes BallLoads (30 Hz), VibrationChunk
// (displacement) and VibrationLevel computed from the core's static solution for the
// current `load` (WrenchStamped, on the moving ring) at the cage angle of the current
// `speed` (rad/s of the rotating ring). Only for tests and screenshots of the display.
#include <cmath>
#include <memory>

#include <bearing_sim/BallLoads.h>
#include <bearing_sim/VibrationChunk.h>
#include <bearing_sim/VibrationLevel.h>
#include <geometry_msgs/WrenchStamped.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/bearing_model.hpp"
#include "bearing_sim/core/quasi_static.hpp"

namespace {
using bearing_sim::Vector5;

struct Fake {
  std::unique_ptr<bearing_sim::BearingModel> model;
  Vector5 load = Vector5::Zero();
  Vector5 guess = Vector5::Zero();
  double speed = 0.0, cage = 0.0;
  ros::Time last;
  std::uint64_t sample = 0;
  ros::Publisher loads_pub, chunk_pub, level_pub;

  void tick(const ros::TimerEvent&) {
    const ros::Time now = ros::Time::now();
    double wi = 0.0, wo = 0.0;
    model->ring_speeds(speed, &wi, &wo);
    cage = std::remainder(cage + model->cage_speed_rad_s(wi, wo) * std::max(0.0, (now - last).toSec()), 2.0 * M_PI);
    last = now;
    bearing_sim::StaticSolution s;
    try {
      s = bearing_sim::solve_static(*model, load, cage, {}, &guess);
    } catch (const std::exception& e) {
      ROS_WARN_THROTTLE(2.0, "fake publisher: %s", e.what());
      return;
    }
    guess = s.displacement;
    bearing_sim::BallLoads msg;
    msg.header.stamp = now;
    msg.header.frame_id = "bearing";
    msg.rows = model->rows();
    msg.balls_per_row = model->balls_per_row();
    msg.cage_angle = cage;
    for (const auto& b : s.balls) {
      msg.azimuth.push_back(b.azimuth_rad);
      msg.load.push_back(b.load_N);
      msg.contact_angle.push_back(b.contact_angle_rad);
      msg.deflection.push_back(b.deflection_m);
    }
    loads_pub.publish(msg);

    bearing_sim::VibrationChunk chunk;
    chunk.header = msg.header;
    chunk.first_sample = sample;
    chunk.sample_rate = 3000.0;
    const std::size_t n = 100;
    sample += n;
    chunk.accel_x.assign(n, 0.0f);
    chunk.accel_y.assign(n, 0.0f);
    chunk.accel_z.assign(n, 0.0f);
    chunk.displacement_x.assign(n, static_cast<float>(s.displacement[0]));
    chunk.displacement_y.assign(n, static_cast<float>(s.displacement[1]));
    chunk.displacement_z.assign(n, static_cast<float>(s.displacement[2]));
    chunk_pub.publish(chunk);

    bearing_sim::VibrationLevel level;
    level.header = msg.header;
    level.level_db = -40.0;  // a smooth bearing (docs/model.md section 11.2); fixed in this fake
    level.accel_rms = 9.81e-3 * std::pow(10.0, -40.0 / 20.0);
    level.window_s = 1.0;
    level_pub.publish(level);
  }
};
}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "fake_ball_loads_publisher");
  ros::NodeHandle nh, pnh("~");
  Fake fake;
  std::string file;
  if (!pnh.getParam("bearing_file", file)) {
    ROS_FATAL("~bearing_file required");
    return 1;
  }
  fake.model = std::make_unique<bearing_sim::BearingModel>(bearing_sim::load_bearing_config(file));
  pnh.param("initial_speed_rad_s", fake.speed, 0.0);
  pnh.param("force_x_N", fake.load[0], 0.0);
  pnh.param("force_y_N", fake.load[1], 0.0);
  pnh.param("force_z_N", fake.load[2], 0.0);
  pnh.param("moment_x_Nm", fake.load[3], 0.0);
  pnh.param("moment_y_Nm", fake.load[4], 0.0);
  double rate = 30.0;
  pnh.param("rate_hz", rate, 30.0);
  fake.loads_pub = nh.advertise<bearing_sim::BallLoads>("ball_loads", 1);
  fake.chunk_pub = nh.advertise<bearing_sim::VibrationChunk>("vibration", 10);
  fake.level_pub = nh.advertise<bearing_sim::VibrationLevel>("vibration_level", 1);
  auto speed_sub =
      nh.subscribe<std_msgs::Float64>("speed", 1, [&](const std_msgs::Float64::ConstPtr& m) { fake.speed = m->data; });
  auto load_sub =
      nh.subscribe<geometry_msgs::WrenchStamped>("load", 1, [&](const geometry_msgs::WrenchStamped::ConstPtr& m) {
        fake.load << m->wrench.force.x, m->wrench.force.y, m->wrench.force.z, m->wrench.torque.x, m->wrench.torque.y;
      });
  fake.last = ros::Time::now();
  ros::Timer timer = nh.createTimer(ros::Duration(1.0 / rate), &Fake::tick, &fake);
  ros::spin();
  return 0;
}
