#pragma once
// The two orthogonal projections of the biplane figure, like a biplane C-arm: a frontal
// and a lateral view sharing the vertical axis (the lateral one is the frontal view
// turned 90 degrees about it), orthographic, same millimetre scale in both panels.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace gw {

enum class BiplaneAxes {
  // From the scene's principal axes (covariance of the mesh vertices): vertical = the
  // direction of largest spread, oriented so the inlet is at the top; frontal right =
  // second largest, its largest world component made positive; lateral right = frontal
  // right x up (the frontal viewer's direction). Shows a tree spread out whatever its pose.
  Principal,
  // Fixed world axes: frontal right = +x, up = +y (looking along -z); lateral right = +z,
  // up = +y (looking along -x). Use it to compare anatomies in one frame.
  FixedXY_ZY,
};

// Screen directions of one view, as unit world vectors.
struct ViewAxes {
  std::string name;       // "FRONTAL" or "LATERAL"
  Eigen::Vector3d right;  // world direction drawn towards +x on screen
  Eigen::Vector3d up;     // world direction drawn upwards on screen
};

// The frontal and lateral axes for `points` (the scene: mesh vertices, path...; the
// non-finite ones are ignored) and the inlet position. Throws std::invalid_argument
// when no point is finite.
std::array<ViewAxes, 2> choose_biplane_axes(const std::vector<Eigen::Vector3d>& points,
                                            const Eigen::Vector3d& inlet, BiplaneAxes mode);

// Where a view lands in the image: world -> pixel (x right, y down, pixel centres at +0.5).
struct ViewProjection {
  ViewAxes axes;
  double px_per_mm = 1.0;
  Eigen::Vector2d centre_uv = Eigen::Vector2d::Zero();  // (right, up) coordinates drawn at the panel centre
  Eigen::Vector2i panel_origin = Eigen::Vector2i::Zero();  // top-left pixel of the panel in the image
  Eigen::Vector2i panel_size = Eigen::Vector2i::Zero();

  Eigen::Vector2d uv(const Eigen::Vector3d& p) const { return {p.dot(axes.right), p.dot(axes.up)}; }
  // Pixel position in the whole image.
  Eigen::Vector2d to_pixel(const Eigen::Vector3d& p) const {
    const Eigen::Vector2d d = (uv(p) - centre_uv) * px_per_mm;
    return {panel_origin.x() + panel_size.x() / 2.0 + d.x(), panel_origin.y() + panel_size.y() / 2.0 - d.y()};
  }
};

}  // namespace gw
