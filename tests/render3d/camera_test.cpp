// The orbit camera: the centre and every point on the view axis project to the frame's centre,
// azimuth 0 looks from `front` with `up` up, a positive azimuth moves the eye right and a positive
// elevation up, the fitted distance puts the bounding sphere just inside the narrower side, the
// focal length follows the vertical field of view, rays pass back through the points they came
// from, "AZ,EL" views parse, and bad frames, spheres and axes are refused.

#include "geolens/render3d/camera.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "geolens/core/errors.h"
#include "support/refusal.h"

namespace geolens {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The frame point model point `p` projects to.
Eigen::Vector2d frame_point(const Projection& p, const Eigen::Vector3d& point) {
  return p.project(p.to_camera(point));
}

TEST(Camera, TheCentreAndEveryPointOnTheViewAxisProjectToTheFrameCentre) {
  const Eigen::Vector3d centre(3, -2, 7);
  for (const double azimuth : {0.0, 30.0, -135.0, 400.0})
    for (const double elevation : {0.0, 20.0, -89.0})
      for (const auto [width, height] : {std::pair{64, 64}, {200, 100}, {31, 97}}) {
        OrbitCamera camera;
        camera.azimuth_degrees = azimuth;
        camera.elevation_degrees = elevation;
        const Projection p = place_camera(camera, centre, 2.5, width, height);
        const Eigen::Vector2d middle(width / 2.0, height / 2.0);
        EXPECT_LT((frame_point(p, centre) - middle).norm(), 1e-9);
        for (const double t : {-2.0, 0.3, 0.9})  // behind the centre, between it and the eye
          EXPECT_LT((frame_point(p, centre + t * (p.eye - centre)) - middle).norm(), 1e-9);
        // The rotation is a proper rotation: orthonormal rows, determinant 1.
        EXPECT_TRUE((p.rotation * p.rotation.transpose()).isIdentity(1e-12));
        EXPECT_NEAR(p.rotation.determinant(), 1, 1e-12);
      }
}

TEST(Camera, AtAzimuthZeroItLooksFromFrontWithUpUpwardsAndRightToTheRight) {
  OrbitCamera camera;
  camera.azimuth_degrees = 0;
  camera.elevation_degrees = 0;
  camera.up = {0, 0, 2};      // model z up
  camera.front = {0, -1, 0};  // model -y towards the camera
  const Eigen::Vector3d centre(1, 1, 1);
  const Projection p = place_camera(camera, centre, 1, 100, 100);
  const Eigen::Vector3d away = (p.eye - centre).normalized();
  EXPECT_TRUE(away.isApprox(Eigen::Vector3d(0, -1, 0), 1e-12)) << away;
  // up x front = (0,0,1) x (0,-1,0) = (1,0,0): model +x is the screen's right.
  const Eigen::Vector2d above = frame_point(p, centre + Eigen::Vector3d(0, 0, 0.5));
  const Eigen::Vector2d right = frame_point(p, centre + Eigen::Vector3d(0.5, 0, 0));
  EXPECT_NEAR(above.x(), 50, 1e-9);
  EXPECT_LT(above.y(), 50 - 1);  // y grows downwards
  EXPECT_GT(right.x(), 50 + 1);
  EXPECT_NEAR(right.y(), 50, 1e-9);
}

TEST(Camera, PositiveAzimuthMovesTheEyeRightAndPositiveElevationUp) {
  const Eigen::Vector3d centre(0, 0, 0);
  OrbitCamera camera;  // up +y, front +z: the screen's right at azimuth 0 is +x
  camera.distance = 10;
  camera.azimuth_degrees = 90;
  camera.elevation_degrees = 0;
  EXPECT_TRUE(place_camera(camera, centre, 1, 50, 50).eye.isApprox(Eigen::Vector3d(10, 0, 0)));
  camera.azimuth_degrees = -90;
  EXPECT_TRUE(place_camera(camera, centre, 1, 50, 50).eye.isApprox(Eigen::Vector3d(-10, 0, 0)));
  camera.azimuth_degrees = 0;
  camera.elevation_degrees = 30;
  const Eigen::Vector3d eye = place_camera(camera, centre, 1, 50, 50).eye;
  EXPECT_TRUE(eye.isApprox(Eigen::Vector3d(0, 5, 10 * std::cos(kPi / 6)), 1e-12)) << eye;
  // From above, the centre's up stays up on the screen.
  const Projection p = place_camera(camera, centre, 1, 50, 50);
  EXPECT_LT(frame_point(p, Eigen::Vector3d(0, 0.5, 0)).y(), 25);
  // A given distance is kept whatever the frame.
  EXPECT_NEAR((place_camera(camera, centre, 1, 500, 20).eye - centre).norm(), 10, 1e-12);
}

// Fitted, the sphere's silhouette (a circle of radius focal tan(asin(r / d)) around the centre)
// touches the frame's narrower side: the top and bottom of a wide frame, the sides of a tall one.
TEST(Camera, FittingPutsTheSphereJustInsideTheNarrowerSide) {
  const Eigen::Vector3d centre(0, 0, 0);
  const double radius = 3;
  for (const auto [width, height] : {std::pair{300, 100}, {100, 300}, {128, 128}}) {
    OrbitCamera camera;
    camera.field_of_view_degrees = 40;
    const Projection p = place_camera(camera, centre, radius, width, height);
    const double d = (p.eye - centre).norm();
    EXPECT_GT(d, radius);
    const double silhouette = p.focal * std::tan(std::asin(radius / d));
    EXPECT_NEAR(silhouette, std::min(width, height) / 2.0, 1e-9) << width << " x " << height;
  }
}

// Square pixels: a point at half the vertical field of view above the axis projects to the top
// edge, and the horizontal scale is the same.
TEST(Camera, TheFocalLengthFollowsTheVerticalFieldOfView) {
  OrbitCamera camera;
  camera.azimuth_degrees = 0;
  camera.elevation_degrees = 0;
  camera.field_of_view_degrees = 60;
  camera.distance = 10;
  const Projection p = place_camera(camera, Eigen::Vector3d::Zero(), 1, 400, 200);
  EXPECT_NEAR(p.focal, 100 / std::tan(kPi / 6), 1e-9);
  const double half = 10 * std::tan(kPi / 6);  // at the centre's depth
  EXPECT_NEAR(frame_point(p, Eigen::Vector3d(0, half, 0)).y(), 0, 1e-9);
  EXPECT_NEAR(frame_point(p, Eigen::Vector3d(-half, 0, 0)).x(), 200 - 100, 1e-9);
}

TEST(Camera, TheRayThroughAPointsProjectionPassesThroughThePoint) {
  OrbitCamera camera;
  camera.azimuth_degrees = 47;
  camera.elevation_degrees = -12;
  const Projection p = place_camera(camera, Eigen::Vector3d(1, 2, 3), 4, 320, 240);
  for (const Eigen::Vector3d point :
       {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(3, -1, 4), Eigen::Vector3d(-2, 4, 1)}) {
    const Eigen::Vector2d f = frame_point(p, point);
    const Eigen::Vector3d ray = p.ray(f.x(), f.y());
    EXPECT_NEAR(ray.norm(), 1, 1e-12);
    EXPECT_TRUE(ray.isApprox((point - p.eye).normalized(), 1e-9)) << point.transpose();
  }
}

TEST(Camera, ParseViewReadsAzimuthAndElevationAndRefusesTheRest) {
  OrbitCamera camera;
  parse_view("-45.5, 10", camera);
  EXPECT_EQ(camera.azimuth_degrees, -45.5);
  EXPECT_EQ(camera.elevation_degrees, 10);
  parse_view("", camera);  // leaves them
  EXPECT_EQ(camera.azimuth_degrees, -45.5);
  for (const char* bad : {"30", "30;20", "a,b", "30,20,1", "nan,0"}) {
    const std::string message = test::refusal([&] { parse_view(bad, camera); });
    EXPECT_NE(message.find(std::string("parse_view: view '") + bad + "' is not AZ,EL"),
              std::string::npos)
        << message;
  }
  EXPECT_NE(test::refusal([&] { parse_view("0,90", camera); }).find("(-90, 90)"),
            std::string::npos);
  EXPECT_EQ(camera.azimuth_degrees, -45.5);  // refused: left as it was
}

TEST(Camera, PlaceCameraRefusesBadFramesSpheresAndAxes) {
  const Eigen::Vector3d centre(0, 0, 0);
  auto refused = [&](const OrbitCamera& camera, double radius, int width, int height) {
    return test::refusal([&] { place_camera(camera, centre, radius, width, height); });
  };
  const OrbitCamera good;
  EXPECT_EQ(refused(good, 1, 10, 10), "");
  OrbitCamera parallel, inside, wide, flat;
  parallel.front = {0, 3, 0};  // along up
  inside.distance = 0.5;
  wide.field_of_view_degrees = 170;
  flat.elevation_degrees = -90;
  const std::pair<std::string, std::string> cases[] = {
      {refused(good, 1, 0, 10), "the frame 0 x 10 is empty"},
      {refused(good, 0, 10, 10), "bounding sphere"},
      {refused(good, NAN, 10, 10), "bounding sphere"},
      {refused(parallel, 1, 10, 10), "the up and front axes are zero or parallel"},
      {refused(inside, 1, 10, 10), "puts the camera inside the scene"},
      {refused(wide, 1, 10, 10), "field of view"},
      {refused(flat, 1, 10, 10), "elevation"},
  };
  for (const auto& [message, what] : cases) {
    EXPECT_EQ(message.rfind("place_camera: ", 0), 0u) << message;
    EXPECT_NE(message.find(what), std::string::npos) << what << "\n" << message;
  }
  EXPECT_NE(test::refusal([] {
              check_region({1, 0, 0, 0, 5}, "render");
            }).find("render: region"),
            std::string::npos);
  EXPECT_NE(test::refusal([] {
              check_region({0, 0, 0, 5, 5}, "render");
            }).find("pixel size"),
            std::string::npos);
}

}  // namespace
}  // namespace geolens
