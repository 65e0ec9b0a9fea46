// rostest of bearing_viz_node against the fake BallLoads publisher (CT gantry bearing,
// static solution of the commanded load): TF chain and speeds, one sphere per ball,
// colour monotonic in load, load zone where the load puts it.
#include <cmath>
#include <deque>
#include <mutex>
#include <set>

#include <bearing_sim/BallLoads.h>
#include <geometry_msgs/WrenchStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_msgs/Float64.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/quasi_static.hpp"

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr int kBallsPerRow = 207;  // CT gantry bearing, two rows
constexpr double kHalfPitch = kPi / kBallsPerRow;

double wrap(double a) { return std::remainder(a, 2.0 * kPi); }
double yaw(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}
// Same luma as a reader would compute (Rec. 709), not the library's function.
double luma(const std_msgs::ColorRGBA& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }
bool grey(const std_msgs::ColorRGBA& c) { return std::abs(c.r - c.g) < 1e-6 && std::abs(c.g - c.b) < 1e-6; }

struct Listener {
  std::mutex mutex;
  visualization_msgs::MarkerArray markers;
  int marker_count = 0;
  std::deque<bearing_sim::BallLoads> loads;  // recent history, to pair with a marker array

  void on_markers(const visualization_msgs::MarkerArray::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    markers = *m;
    ++marker_count;
  }
  void on_loads(const bearing_sim::BallLoads::ConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex);
    loads.push_back(*m);
    if (loads.size() > 30) loads.pop_front();
  }
};

Listener* listener = nullptr;
tf2_ros::Buffer* tf_buffer = nullptr;
ros::Publisher* speed_pub = nullptr;
ros::Publisher* load_pub = nullptr;

// Waits for `count` new marker arrays and returns the last.
visualization_msgs::MarkerArray next_markers(int count = 1) {
  int start;
  {
    std::lock_guard<std::mutex> lock(listener->mutex);
    start = listener->marker_count;
  }
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(15.0);
  while (ros::ok() && ros::WallTime::now() < deadline) {
    {
      std::lock_guard<std::mutex> lock(listener->mutex);
      if (listener->marker_count >= start + count) return listener->markers;
    }
    ros::WallDuration(0.01).sleep();
  }
  ADD_FAILURE() << "no ball_markers";
  return {};
}

// Ball spheres of row `row` (id = row in namespace "balls").
const visualization_msgs::Marker* balls_marker(const visualization_msgs::MarkerArray& a, int row) {
  for (const auto& m : a.markers)
    if (m.ns == "balls" && m.id == row) return &m;
  return nullptr;
}

// Centre of the load zone of a row as a reader of the picture sees it: the circular mean
// of the azimuths of the coloured (not grey) balls.
double zone_centre_from_colours(const visualization_msgs::Marker& balls) {
  double s = 0.0, c = 0.0;
  for (std::size_t i = 0; i < balls.points.size(); ++i) {
    if (grey(balls.colors[i])) continue;
    const double phi = std::atan2(balls.points[i].y, balls.points[i].x);
    s += std::sin(phi);
    c += std::cos(phi);
  }
  return std::atan2(s, c);
}

void publish_radial_load(double fx, double fy) {
  geometry_msgs::WrenchStamped w;
  w.header.stamp = ros::Time::now();
  w.header.frame_id = "bearing";
  w.wrench.force.x = fx;
  w.wrench.force.y = fy;
  load_pub->publish(w);
}

// Waits until the zone of both rows is within `tolerance` of `expected`, for at most 10 s;
// returns the centres of the last marker array.
std::vector<double> wait_for_zone(double expected, double tolerance) {
  std::vector<double> centres(2, 0.0);
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(10.0);
  while (ros::ok() && ros::WallTime::now() < deadline) {
    const auto a = next_markers();
    for (int r = 0; r < 2; ++r) {
      const auto* m = balls_marker(a, r);
      if (!m) return centres;
      centres[r] = zone_centre_from_colours(*m);
    }
    if (std::abs(wrap(centres[0] - expected)) < tolerance && std::abs(wrap(centres[1] - expected)) < tolerance) break;
  }
  return centres;
}
}  // namespace

TEST(VizNode, TransformChainExists) {
  std::string error;
  for (const char* child : {"bearing", "rotating_ring", "cage"}) {
    EXPECT_TRUE(tf_buffer->canTransform("gantry", child, ros::Time(0), ros::Duration(10.0), &error))
        << child << ": " << error;
  }
  // Parent of each frame as the issue states: gantry -> bearing -> rotating_ring -> cage.
  const std::pair<const char*, const char*> chain[] = {
      {"bearing", "gantry"}, {"rotating_ring", "bearing"}, {"cage", "rotating_ring"}};
  for (const auto& link : chain) {
    std::string parent;
    EXPECT_TRUE(tf_buffer->_getParent(link.first, ros::Time(0), parent)) << link.first;
    EXPECT_EQ(parent, link.second) << link.first;
  }
}

TEST(VizNode, RingOffsetIsTheExaggeratedDisplacement) {
  // 6800 N along +x on the outer ring (the fake's initial load): the ring moves to +x by the
  // static deflection, shown 1000 times larger (launch file default).
  const bearing_sim::BearingModel model(
      bearing_sim::load_bearing_config(std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings/ct_gantry_lyc.yaml"));
  bearing_sim::Vector5 load = bearing_sim::Vector5::Zero();
  load[0] = 6800.0;
  const double expected_x = 1000.0 * bearing_sim::solve_static(model, load).displacement[0];
  ASSERT_GT(expected_x, 1e-3);  // a few micrometres, a few millimetres on screen
  next_markers(3);              // the node has had chunks by now
  const auto t = tf_buffer->lookupTransform("bearing", "rotating_ring", ros::Time(0));
  // The static deflection varies by well under 1 % with the cage angle; float transport.
  EXPECT_NEAR(t.transform.translation.x, expected_x, 0.02 * expected_x);
  EXPECT_NEAR(t.transform.translation.y, 0.0, 0.02 * expected_x);
}

TEST(VizNode, RingAndCageTurnAtTheCommandedSpeed) {
  const double speed = 2.0;  // rad/s of the rotating (outer) ring
  std_msgs::Float64 s;
  s.data = speed;
  speed_pub->publish(s);
  ros::WallDuration(1.0).sleep();  // let the speed arrive

  // Integrate the unwrapped yaw over ~2 s of TF, against the TF stamps.
  double ring_total = 0.0, cage_total = 0.0;
  auto ring0 = tf_buffer->lookupTransform("bearing", "rotating_ring", ros::Time(0));
  auto cage0 = tf_buffer->lookupTransform("bearing", "cage", ros::Time(0));
  const ros::Time t_start = ring0.header.stamp;
  double ring_prev = yaw(ring0.transform.rotation), cage_prev = yaw(cage0.transform.rotation);
  ros::Time t_end = t_start;
  for (int k = 0; k < 40; ++k) {
    ros::WallDuration(0.05).sleep();
    const auto ring = tf_buffer->lookupTransform("bearing", "rotating_ring", ros::Time(0));
    const ros::Time stamp = ring.header.stamp;
    const auto cage = tf_buffer->lookupTransform("bearing", "cage", stamp);  // same instant
    const double ry = yaw(ring.transform.rotation), cy = yaw(cage.transform.rotation);
    ring_total += wrap(ry - ring_prev);
    cage_total += wrap(cy - cage_prev);
    ring_prev = ry;
    cage_prev = cy;
    t_end = stamp;
  }
  const double dt = (t_end - t_start).toSec();
  ASSERT_GT(dt, 1.5);
  // The ring angle is integrated from the commanded speed against the same clock as the
  // stamps: only timer jitter at the ends remains (one 33 ms tick over 2 s is < 2 %).
  EXPECT_NEAR(ring_total / dt, speed, 0.03 * speed);
  // Cage speed, docs/model.md section 7.2, inner ring fixed: w_c = w_o (1 + gamma) / 2 with
  // gamma = d cos a0 / dm = 12 cos 35 deg / 1111. The cage follows the simulation's
  // 30 Hz cage angle, so allow a little more (5 %).
  const double gamma = 12.0 * std::cos(35.0 * kPi / 180.0) / 1111.0;
  const double cage_expected = speed * (1.0 + gamma) / 2.0;
  EXPECT_NEAR(cage_total / dt, cage_expected, 0.05 * cage_expected);

  s.data = 0.0;  // stop, so that the following tests see still balls
  speed_pub->publish(s);
  ros::WallDuration(0.3).sleep();
}

TEST(VizNode, OneSpherePerBallAndStableIds) {
  const auto a = next_markers();
  const auto b = next_markers(2);
  std::size_t spheres = 0;
  std::set<std::pair<std::string, int>> ids_a, ids_b;
  for (const auto& m : a.markers) {
    ids_a.insert({m.ns, m.id});
    if (m.ns == "balls") {
      EXPECT_EQ(m.type, visualization_msgs::Marker::SPHERE_LIST);
      EXPECT_EQ(m.colors.size(), m.points.size());
      spheres += m.points.size();
    }
  }
  for (const auto& m : b.markers) ids_b.insert({m.ns, m.id});
  EXPECT_EQ(spheres, 2u * kBallsPerRow);
  EXPECT_EQ(ids_a, ids_b);
  EXPECT_EQ(ids_a.size(), a.markers.size());  // no duplicate (ns, id)
}

TEST(VizNode, ColourIsMonotonicInLoad) {
  // Pair a marker array with the BallLoads it was drawn from (same azimuths), then order
  // the balls by the published load: grey exactly when unloaded, luma never decreasing.
  bool paired = false;
  for (int attempt = 0; attempt < 20 && !paired; ++attempt) {
    const auto a = next_markers();
    std::deque<bearing_sim::BallLoads> history;
    {
      std::lock_guard<std::mutex> lock(listener->mutex);
      history = listener->loads;
    }
    const visualization_msgs::Marker* rows[2] = {balls_marker(a, 0), balls_marker(a, 1)};
    ASSERT_TRUE(rows[0] && rows[1]);
    for (auto it = history.rbegin(); it != history.rend() && !paired; ++it) {
      bool match = true;
      for (int b = 0; b < 2 * kBallsPerRow && match; ++b) {
        const auto& p = rows[b / kBallsPerRow]->points[b % kBallsPerRow];
        match = std::abs(wrap(std::atan2(p.y, p.x) - it->azimuth[b])) < 1e-5;
      }
      if (!match) continue;
      paired = true;
      std::vector<std::pair<double, double>> load_luma;
      int loaded = 0;
      for (int b = 0; b < 2 * kBallsPerRow; ++b) {
        const auto& c = rows[b / kBallsPerRow]->colors[b % kBallsPerRow];
        const double q = it->load[b];
        EXPECT_EQ(grey(c), q <= 0.0) << "ball " << b << " load " << q;
        if (q > 0.0) {
          load_luma.emplace_back(q, luma(c));
          ++loaded;
        }
      }
      ASSERT_GT(loaded, 100);  // about half of 414 balls under a radial load
      std::sort(load_luma.begin(), load_luma.end());
      for (std::size_t k = 1; k < load_luma.size(); ++k)
        EXPECT_GE(load_luma[k].second, load_luma[k - 1].second - 1e-6)
            << "loads " << load_luma[k - 1].first << " -> " << load_luma[k].first;
      // A visible spread: the heaviest ball is clearly brighter than the lightest.
      EXPECT_GT(load_luma.back().second - load_luma.front().second, 0.3);
    }
  }
  EXPECT_TRUE(paired) << "no marker array matched a recent BallLoads message";
}

TEST(VizNode, PlusXForceOnOuterRingCentresTheZoneAt180Degrees) {
  publish_radial_load(6800.0, 0.0);
  const auto centres = wait_for_zone(kPi, kHalfPitch);
  for (int r = 0; r < 2; ++r) {
    // The loaded arc is contiguous and symmetric about 180 deg up to the ball grid:
    // its mid-point is within half a ball pitch of the true centre.
    EXPECT_LT(std::abs(wrap(centres[r] - kPi)), kHalfPitch) << "row " << r + 1 << ": " << centres[r] * 180 / kPi;
  }
  // The brightest ball sits within one pitch of 180 deg.
  const auto a = next_markers();
  const auto* m = balls_marker(a, 0);
  ASSERT_TRUE(m);
  std::size_t best = 0;
  for (std::size_t i = 1; i < m->points.size(); ++i)
    if (luma(m->colors[i]) > luma(m->colors[best])) best = i;
  EXPECT_LE(std::abs(wrap(std::atan2(m->points[best].y, m->points[best].x) - kPi)), 2 * kHalfPitch + 1e-6);
}

TEST(VizNode, ChangeOfLoadMovesTheZone) {
  // Force along -y: the outer ring's raceway presses on the balls at +y (azimuth +90 deg).
  publish_radial_load(0.0, -5000.0);
  const auto centres = wait_for_zone(kPi / 2, kHalfPitch);
  for (int r = 0; r < 2; ++r)
    EXPECT_LT(std::abs(wrap(centres[r] - kPi / 2)), kHalfPitch) << "row " << r + 1 << ": " << centres[r] * 180 / kPi;
  publish_radial_load(6800.0, 0.0);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_viz_node");
  ros::NodeHandle nh;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  Listener l;
  listener = &l;
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener tf_listener(buffer);
  tf_buffer = &buffer;
  ros::Publisher sp = nh.advertise<std_msgs::Float64>("speed", 1, true);
  ros::Publisher lp = nh.advertise<geometry_msgs::WrenchStamped>("load", 1, true);
  speed_pub = &sp;
  load_pub = &lp;
  ros::Subscriber ms = nh.subscribe("ball_markers", 5, &Listener::on_markers, &l);
  ros::Subscriber bs = nh.subscribe("ball_loads", 30, &Listener::on_loads, &l);
  // Wait for both nodes to connect before testing.
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::ok() && ros::WallTime::now() < deadline &&
         (ms.getNumPublishers() == 0 || bs.getNumPublishers() == 0 || sp.getNumSubscribers() < 2)) {
    ros::WallDuration(0.1).sleep();
  }
  const int result = RUN_ALL_TESTS();
  spinner.stop();
  return result;
}
