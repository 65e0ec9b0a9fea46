// Unit tests of the ball-load display's pure parts: colour map, scene geometry from the
// core model, load-zone centre, ring/cage poses and the marker layout (no ROS master).
#include <cmath>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "bearing_sim/core/bearing_config.hpp"
#include "bearing_sim/core/quasi_static.hpp"
#include "bearing_sim/viz/bearing_scene.hpp"
#include "bearing_sim/viz/colour_map.hpp"
#include "bearing_sim/viz/marker_builder.hpp"

using namespace bearing_sim;
using namespace bearing_sim::viz;

namespace {
constexpr double kPi = 3.14159265358979323846;
const std::string kCtFile = std::string(BEARING_SIM_SOURCE_DIR) + "/config/bearings/ct_gantry_lyc.yaml";

BearingModel ct_model() { return BearingModel(load_bearing_config(kCtFile)); }

// BallLoads arrays of the static solution, as the simulation node publishes them.
BallLoadArrays static_loads(const BearingModel& model, const Vector5& load, double cage_angle) {
  const StaticSolution s = solve_static(model, load, cage_angle);
  BallLoadArrays a;
  a.rows = model.rows();
  a.balls_per_row = model.balls_per_row();
  a.cage_angle_rad = cage_angle;
  for (const BallState& b : s.balls) {
    a.azimuth_rad.push_back(static_cast<float>(b.azimuth_rad));
    a.load_N.push_back(static_cast<float>(b.load_N));
    a.contact_angle_rad.push_back(static_cast<float>(b.contact_angle_rad));
  }
  return a;
}

Vector5 radial(double fx, double fy) {
  Vector5 v = Vector5::Zero();
  v[0] = fx;
  v[1] = fy;
  return v;
}

double angle_difference(double a, double b) { return std::remainder(a - b, 2.0 * kPi); }
}  // namespace

TEST(ColourMap, ViridisEndpointsAreMatplotlibs) {
  // matplotlib viridis(0) = #440154, viridis(1) = #fde725.
  const Rgba lo = viridis(0.0), hi = viridis(1.0);
  EXPECT_NEAR(lo.r * 255, 0x44, 0.6);
  EXPECT_NEAR(lo.g * 255, 0x01, 0.6);
  EXPECT_NEAR(lo.b * 255, 0x54, 0.6);
  EXPECT_NEAR(hi.r * 255, 0xfd, 0.6);
  EXPECT_NEAR(hi.g * 255, 0xe7, 0.6);
  EXPECT_NEAR(hi.b * 255, 0x25, 0.6);
  // viridis(0.5) = #21918c.
  const Rgba mid = viridis(0.5);
  EXPECT_NEAR(mid.r * 255, 0x21, 1.5);
  EXPECT_NEAR(mid.g * 255, 0x91, 1.5);
  EXPECT_NEAR(mid.b * 255, 0x8c, 1.5);
}

TEST(ColourMap, LumaStrictlyIncreasesWithLoad) {
  double previous = -1.0;
  for (int k = 0; k <= 1000; ++k) {
    const double l = luma(load_colour(1e-3 + k * 1.0, 1000.0));
    if (k > 0 && k < 1000) {
      EXPECT_GT(l, previous) << "at " << k << " N";
    }
    previous = l;
  }
  // Above full scale it saturates at the top colour.
  EXPECT_DOUBLE_EQ(luma(load_colour(5000.0, 1000.0)), luma(viridis(1.0)));
}

TEST(ColourMap, UnloadedBallsAreGreyAndLoadedOnesAreNot) {
  EXPECT_TRUE(is_grey(load_colour(0.0, 100.0)));
  EXPECT_TRUE(is_grey(load_colour(-3.0, 100.0)));
  EXPECT_TRUE(is_grey(load_colour(std::nan(""), 100.0)));
  for (double q : {1e-6, 1.0, 50.0, 100.0, 300.0}) EXPECT_FALSE(is_grey(load_colour(q, 100.0))) << q;
  EXPECT_FALSE(is_grey(load_colour(10.0, 0.0)));  // no scale yet: still shown as loaded
}

TEST(BearingScene, BallsSitOnThePitchCircleAtTheirRowAndAzimuth) {
  const BearingModel model = ct_model();
  const BallLoadArrays loads = static_loads(model, radial(6800.0, 0.0), 0.3);
  ASSERT_EQ(check_ball_loads(model, loads), "");
  const BearingScene scene = build_scene(model, loads, 0.0);
  ASSERT_EQ(scene.balls.size(), 2u);
  std::set<double> row_z;
  for (int r = 0; r < 2; ++r) {
    ASSERT_EQ(scene.balls[r].size(), 207u);
    for (int j = 0; j < 207; ++j) {
      const Eigen::Vector3d& c = scene.balls[r][j].centre;
      // Bearing file: pitch diameter 1111 mm, row spacing 40 mm.
      EXPECT_NEAR(std::hypot(c.x(), c.y()), 0.5555, 1e-9);
      EXPECT_NEAR(std::abs(c.z()), 0.020, 1e-12);
      row_z.insert(c.z());
      EXPECT_NEAR(angle_difference(std::atan2(c.y(), c.x()), loads.azimuth_rad[r * 207 + j]), 0.0, 1e-6);
    }
  }
  EXPECT_EQ(row_z.size(), 2u);  // the rows are on opposite sides of the bearing centre
  EXPECT_NEAR(scene.ball_display_diameter_m, 0.012 * DisplayOptions().ball_scale, 1e-12);
}

TEST(BearingScene, RadialForceAlongPlusXOnOuterRingLoadsTheMinusXSide) {
  // Outer ring pulled to +x: its raceway at azimuth 180 deg presses onto the balls.
  const BearingModel model = ct_model();
  const double half_pitch = kPi / 207;
  for (double cage : {0.0, 0.01, 1.234}) {
    const BearingScene scene = build_scene(model, static_loads(model, radial(6800.0, 0.0), cage), 0.0);
    for (int r = 0; r < 2; ++r) {
      EXPECT_NEAR(angle_difference(scene.load_zone_centre_rad[r], kPi), 0.0, half_pitch) << "cage " << cage;
    }
    // The most loaded ball is one of the two nearest to 180 deg.
    const double az = std::atan2(scene.balls[scene.max_load_ball / 207][scene.max_load_ball % 207].centre.y(),
                                 scene.balls[scene.max_load_ball / 207][scene.max_load_ball % 207].centre.x());
    EXPECT_LE(std::abs(angle_difference(az, kPi)), 2 * half_pitch + 1e-9);
  }
  // A force along +y moves the zone to -90 deg.
  const BearingScene y = build_scene(model, static_loads(model, radial(0.0, 6800.0), 0.0), 0.0);
  EXPECT_NEAR(angle_difference(y.load_zone_centre_rad[0], -kPi / 2), 0.0, half_pitch);
}

TEST(BearingScene, LoadZoneCentreOfASyntheticDistribution) {
  // Loads Qmax cos(phi - 60 deg) inside +-70 deg of 60 deg on 360 balls 1 deg apart
  // (symmetric on the grid): the centre is 60 deg.
  const double centre = kPi / 3;
  std::vector<float> az, q;
  for (int j = 0; j < 360; ++j) {
    const double phi = 2 * kPi * j / 360 - kPi;
    az.push_back(phi);
    const double c = std::cos(phi - centre);
    q.push_back(c > std::cos(70.5 * kPi / 180) ? 100.0 * c : 0.0);  // no ball on the edge
  }
  EXPECT_NEAR(load_zone_centre_rad(az, q, 0, az.size()), centre, 1e-5);
  std::vector<float> none(360, 0.0f);
  EXPECT_TRUE(std::isnan(load_zone_centre_rad(az, none, 0, az.size())));
}

TEST(BearingScene, ColoursFollowLoadsAndArrowsPointAlongTheContactLine) {
  const BearingModel model = ct_model();
  const BallLoadArrays loads = static_loads(model, radial(6800.0, 0.0), 0.0);
  DisplayOptions opt;
  const BearingScene scene = build_scene(model, loads, 0.0, opt);
  int loaded = 0;
  std::vector<std::pair<double, double>> load_luma;
  for (int r = 0; r < 2; ++r) {
    for (const BallGlyph& g : scene.balls[r]) {
      EXPECT_EQ(is_grey(g.colour), g.load_N <= 0.0);
      if (g.load_N > 0.0) {
        ++loaded;
        load_luma.emplace_back(g.load_N, luma(g.colour));
      }
    }
  }
  // Zero clearance, pure radial load: about half of each row is in contact.
  EXPECT_GT(loaded, 2 * 90);
  EXPECT_LT(loaded, 2 * 120);
  std::sort(load_luma.begin(), load_luma.end());
  for (std::size_t k = 1; k < load_luma.size(); ++k) EXPECT_GE(load_luma[k].second, load_luma[k - 1].second);
  // Full scale is this message's maximum: the most loaded ball is at the top of the map.
  EXPECT_DOUBLE_EQ(scene.full_scale_N, scene.max_load_N);
  EXPECT_NEAR(load_luma.back().second, luma(viridis(1.0)), 1e-6);

  // Three segments per loaded ball; the shaft points inward (force of the outer raceway on
  // the ball) with its head on the displayed ball surface.
  std::size_t segments = scene.force_arrows[0].size() + scene.force_arrows[1].size();
  EXPECT_EQ(segments, 3u * loaded);
  const Segment& shaft = scene.force_arrows[0][0];
  EXPECT_LT(std::hypot(shaft.b.x(), shaft.b.y()), std::hypot(shaft.a.x(), shaft.a.y()));
  double nearest = 1e9;
  for (const BallGlyph& g : scene.balls[0]) nearest = std::min(nearest, (g.centre - shaft.b).norm());
  EXPECT_NEAR(nearest, 0.5 * scene.ball_display_diameter_m, 1e-9);
  // The longest arrow has the full-scale length.
  double longest = 0.0;
  for (int r = 0; r < 2; ++r)
    for (std::size_t k = 0; k < scene.force_arrows[r].size(); k += 3)
      longest = std::max(longest, (scene.force_arrows[r][k].a - scene.force_arrows[r][k].b).norm());
  EXPECT_NEAR(longest, opt.force_arrow_length_m, 1e-9);
}

TEST(BearingScene, RejectsBallLoadsOfAnotherBearing) {
  const BearingModel model = ct_model();
  BallLoadArrays loads = static_loads(model, radial(1000.0, 0.0), 0.0);
  loads.load_N.pop_back();
  EXPECT_NE(check_ball_loads(model, loads), "");
  loads = static_loads(model, radial(1000.0, 0.0), 0.0);
  loads.balls_per_row = 206;
  EXPECT_NE(check_ball_loads(model, loads), "");
  loads = static_loads(model, radial(1000.0, 0.0), 0.0);
  loads.azimuth_rad[5] = std::nanf("");
  EXPECT_NE(check_ball_loads(model, loads), "");
}

TEST(RingPoses, RingTurnsAndShiftsAndCageKeepsItsBearingFrameAngle) {
  const Eigen::Vector3d d(5e-6, -2e-6, 1e-6);
  const Eigen::Isometry3d ring = rotating_ring_pose(0.7, d, 1000.0);
  EXPECT_NEAR(yaw_rad(ring), 0.7, 1e-12);
  EXPECT_NEAR((ring.translation() - Eigen::Vector3d(5e-3, -2e-3, 1e-3)).norm(), 0.0, 1e-15);
  const Eigen::Isometry3d cage_in_ring = cage_pose_in_ring(ring, -2.5);
  const Eigen::Isometry3d cage = ring * cage_in_ring;  // composed as TF does
  EXPECT_NEAR(angle_difference(yaw_rad(cage), -2.5), 0.0, 1e-12);
  EXPECT_NEAR(cage.translation().norm(), 0.0, 1e-15);
}

TEST(RingPoses, RingSectionsComeFromTheEnvelope) {
  const BearingModel model = ct_model();
  const RingSection outer = outer_ring_section(model), inner = inner_ring_section(model);
  EXPECT_NEAR(outer.outer_radius_m, 0.610, 1e-12);  // outer diameter 1220 mm
  EXPECT_NEAR(inner.inner_radius_m, 0.501, 1e-12);  // bore 1002 mm
  EXPECT_NEAR(outer.width_m, 0.096, 1e-12);
  EXPECT_GT(outer.inner_radius_m, model.pitch_radius_m());
  EXPECT_LT(inner.outer_radius_m, model.pitch_radius_m());
  const auto outline = ring_outline(outer, 100, 12, Rgba{});
  EXPECT_EQ(outline.size(), 4u * 100 + 12 + 2);
}

TEST(RingPoses, DeformationCurveIsTheCentroidCircleMovedByTheMagnifiedDisplacement) {
  // An n = 2 ovality of 10 um and 3 um axial at four azimuths, magnified 5000: 50 mm out at 0
  // and pi, in at pi/2 and 3 pi/2, 15 mm up; closed by the first point again.
  const std::vector<float> azimuth = {0.0f, static_cast<float>(kPi / 2), static_cast<float>(kPi),
                                      static_cast<float>(3 * kPi / 2)};
  const std::vector<float> radial = {10e-6f, -10e-6f, 10e-6f, -10e-6f}, axial(4, 3e-6f);
  const auto curve = deformation_curve(0.6, azimuth, radial, axial, 5000.0);
  ASSERT_EQ(curve.size(), 5u);
  for (std::size_t i = 0; i < 4; ++i) {
    const double r = 0.6 + 5000.0 * radial[i];
    EXPECT_NEAR(curve[i].x(), r * std::cos(azimuth[i]), 1e-6) << i;
    EXPECT_NEAR(curve[i].y(), r * std::sin(azimuth[i]), 1e-6) << i;
    EXPECT_NEAR(curve[i].z(), 0.015, 1e-6) << i;
  }
  EXPECT_EQ(curve[4], curve[0]);
  EXPECT_NEAR(curve[0].head<2>().norm(), 0.65, 1e-6);
  EXPECT_NEAR(curve[1].head<2>().norm(), 0.55, 1e-6);
  EXPECT_TRUE(deformation_curve(0.6, azimuth, radial, {0.0f}, 5000.0).empty());  // lengths differ
}

TEST(MarkerBuilder, StableIdsOneSpherePerBallConsistentArrays) {
  const BearingModel model = ct_model();
  SceneExtras extras;
  extras.fixed_ring_outline = ring_outline(inner_ring_section(model), 90, 0, Rgba{});
  extras.rotating_ring_outline = ring_outline(outer_ring_section(model), 90, 24, Rgba{});
  extras.applied_force_N = Eigen::Vector3d(6800.0, 0.0, 0.0);
  extras.bearing_outer_radius_m = 0.61;
  std::vector<std::set<std::pair<std::string, int>>> keys;
  for (const Vector5& load : {radial(6800.0, 0.0), radial(0.0, -3000.0)}) {
    const BallLoadArrays loads = static_loads(model, load, 0.2);
    const BearingScene scene = build_scene(model, loads, 0.0);
    extras.status_text = status_text(scene, model, loads, -40.0, 18.85);
    const auto array = build_markers(scene, extras, MarkerFrames{}, ros::Time(12.5));
    std::set<std::pair<std::string, int>> k;
    std::size_t spheres = 0;
    for (const auto& m : array.markers) {
      EXPECT_TRUE(k.insert({m.ns, m.id}).second) << "duplicate " << m.ns << "/" << m.id;
      EXPECT_DOUBLE_EQ(m.pose.orientation.w, 1.0);
      if (!m.colors.empty()) {
        EXPECT_EQ(m.colors.size(), m.points.size()) << m.ns;
      }
      if (m.type == visualization_msgs::Marker::LINE_LIST) {
        EXPECT_EQ(m.points.size() % 2, 0u) << m.ns;
      }
      if (m.ns == "balls") {
        EXPECT_EQ(m.type, visualization_msgs::Marker::SPHERE_LIST);
        EXPECT_EQ(m.header.frame_id, "bearing");
        spheres += m.points.size();
      }
      if (m.ns == "rotating_ring") {
        EXPECT_EQ(m.header.frame_id, "rotating_ring");
        EXPECT_TRUE(m.frame_locked);
      }
      if (m.ns == "status_text") {
        EXPECT_NE(m.text.find("Q_max = "), std::string::npos);
        EXPECT_NE(m.text.find("L = -40.0 dB"), std::string::npos);
        EXPECT_NE(m.text.find("180.0 rpm"), std::string::npos);  // 18.85 rad/s
      }
    }
    EXPECT_EQ(spheres, 2u * 207);
    keys.push_back(k);
  }
  EXPECT_EQ(keys[0], keys[1]);  // same ids whatever the load: rviz updates in place
}

TEST(MarkerBuilder, StatusTextNamesTheMostLoadedBall) {
  const BearingModel model = ct_model();
  const BallLoadArrays loads = static_loads(model, radial(6800.0, 0.0), 0.0);
  const BearingScene scene = build_scene(model, loads, 0.0);
  const std::string text = status_text(scene, model, loads, std::nan(""), 0.0);
  char expected[64];
  std::snprintf(expected, sizeof expected, "Q_max = %.0f N", scene.max_load_N);
  EXPECT_NE(text.find(expected), std::string::npos) << text;
  EXPECT_NE(text.find("L = -- dB"), std::string::npos) << text;
  // Stribeck (docs/model.md section 6.4): Qmax ~ 4.37 Fr / (Z cos a) for one row; two rows share Fr.
  EXPECT_NEAR(scene.max_load_N, 4.37 * 3400.0 / (207 * std::cos(35 * kPi / 180)), 0.15 * scene.max_load_N);
}
