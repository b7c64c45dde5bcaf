#pragma once
// The camera of a 3D scene (a mesh or a volume): an orbit around the scene's bounding sphere,
// fitted to the frame, and the grid of pixels one render covers.

#include <Eigen/Core>
#include <string>

namespace geolens {

/// Where the camera looks from. It orbits the centre of the scene's bounding sphere: at azimuth
/// 0 and elevation 0 it looks from `front` towards the centre, with `up` pointing up on the
/// screen; a positive azimuth moves it towards the screen's right (about `up`), a positive
/// elevation moves it up (towards `up`).
struct OrbitCamera {
  double azimuth_degrees = 30;    ///< any value
  double elevation_degrees = 20;  ///< in (-90, 90)
  /// Vertical field of view, degrees, in (0, 170).
  double field_of_view_degrees = 30;
  /// Distance from the centre, model units; 0 = fit to view: the nearest distance at which the
  /// whole bounding sphere is inside the frame (so the camera is always outside the scene).
  double distance = 0;
  Eigen::Vector3d up{0, 1, 0};     ///< model axis shown upwards; non-zero
  Eigen::Vector3d front{0, 0, 1};  ///< model axis facing the camera at azimuth 0; not along `up`
};

/// Reads a --view value "AZ,EL" (degrees, e.g. "30,20") into `camera`'s azimuth and elevation;
/// an empty `view` leaves them. Throws InvalidInput naming "parse_view" and the value when it
/// is not two numbers separated by a comma or the elevation is not in (-90, 90).
void parse_view(const std::string& view, OrbitCamera& camera);

/// A camera placed for a frame: model points to frame pixels by a perspective projection.
/// Frame pixel (x, y) covers [x, x + 1) x [y, y + 1), y downwards; the centre of the bounding
/// sphere projects to the frame's centre. Camera coordinates: x right, y up, z towards the
/// viewer (the camera looks along -z).
struct Projection {
  Eigen::Matrix3d rotation;  ///< rows: the camera's x, y, z axes in model coordinates
  Eigen::Vector3d eye;       ///< the camera's position, model units
  double focal = 1;          ///< frame pixels per unit of x / depth
  ///@{
  double centre_x = 0, centre_y = 0;  ///< frame pixel coordinates of the optical axis
  ///@}

  /// A model point in camera coordinates.
  Eigen::Vector3d to_camera(const Eigen::Vector3d& p) const { return rotation * (p - eye); }
  /// The frame point a camera-space point with depth -q.z() > 0 projects to.
  Eigen::Vector2d project(const Eigen::Vector3d& q) const {
    return {centre_x + focal * q.x() / -q.z(), centre_y - focal * q.y() / -q.z()};
  }
  /// The unit direction, in model coordinates, of the ray from the eye through frame point
  /// (x, y).
  Eigen::Vector3d ray(double x, double y) const;
};

/// Places `camera` for a frame_width x frame_height frame around the sphere (`centre`, `radius`
/// > 0, model units). Throws InvalidInput naming "place_camera" for a frame smaller than 1 x 1,
/// a non-finite or non-positive radius, an elevation outside (-90, 90), a field of view outside
/// (0, 170), a negative distance, a distance that puts the eye inside the sphere, or degenerate
/// `up` / `front` axes.
Projection place_camera(const OrbitCamera& camera, const Eigen::Vector3d& centre, double radius,
                        int frame_width, int frame_height);

/// The pixels one render covers: pixel (x + i, y + j), i in [0, width), j in [0, height), of
/// the grid of square pixels `pixel_size` frame pixels wide whose pixel (0, 0) starts at the
/// frame's corner; so it covers frame [(x + i) s, (x + i + 1) s) x [(y + j) s, ...), s =
/// pixel_size. Level l of a source whose level 0 has 2^k texels per frame pixel is the grid of
/// pixel_size 2^(l - k), and a tile of it is a region of that grid. Renderers evaluate every
/// sample from its absolute position in the grid, never from the region's corner, so two
/// regions of one grid agree exactly where they overlap and adjacent ones join without a seam.
struct PixelRegion {
  double pixel_size = 1;  ///< frame pixels per pixel, > 0
  ///@{
  int x = 0, y = 0;           ///< grid index of the region's first pixel
  int width = 0, height = 0;  ///< pixels of the grid, >= 1
  ///@}
};

/// Throws InvalidInput naming `function` unless the region has a finite positive pixel size
/// and a size of at least 1 x 1 and at most 2^28 pixels.
void check_region(const PixelRegion& region, const char* function);

}  // namespace geolens
