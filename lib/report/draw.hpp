#pragma once
// Drawing primitives on an Image, in pixel coordinates (x right, y down; pixel (i, j)
// covers [i, i+1) x [j, j+1), its centre is (i + 0.5, j + 0.5)). No anti-aliasing: a
// pixel is painted when its centre is inside the shape. Everything clips at the border.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "lib/report/image.hpp"

namespace gw {

// Pixels whose centre lies within width/2 of segment a-b (round caps). width >= 1.
void draw_segment(Image& img, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width, Rgb color);

// draw_segment over consecutive points; non-finite points break the line.
void draw_polyline(Image& img, const std::vector<Eigen::Vector2d>& points, double width, Rgb color);

// Pixels whose centre is within `radius` of `centre`.
void fill_disc(Image& img, const Eigen::Vector2d& centre, double radius, Rgb color);

// Pixels whose centre is at a distance in [radius - width/2, radius + width/2] of `centre`.
void draw_ring(Image& img, const Eigen::Vector2d& centre, double radius, double width, Rgb color);

// Integer rectangle [x0, x1) x [y0, y1).
void fill_rect(Image& img, int x0, int y0, int x1, int y1, Rgb color);

// Coverage counts of triangles over a width x height grid: count[y * width + x] is the
// number of triangles whose interior contains pixel (x, y)'s centre. Vertices are snapped
// to 1/256 pixel and edges follow the top-left rule with exact integer arithmetic, so two
// triangles sharing an edge never both count a pixel on it: for a closed surface the count
// is twice the number of wall layers crossed (what an X-ray sees). Degenerate and
// non-finite triangles count nowhere.
struct CoverageRaster {
  int width = 0, height = 0;
  std::vector<std::uint16_t> count;
  CoverageRaster(int w, int h) : width(w), height(h), count(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0) {}
  void add_triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);
  std::uint16_t at(int x, int y) const { return count[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)]; }
};

}  // namespace gw
