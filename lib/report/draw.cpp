#include "lib/report/draw.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gw {
namespace {

// Pixel index range [lo, hi] whose centres may lie in [a, b], clipped to [0, n-1].
// Returns false when empty (also for non-finite bounds).
bool pixel_range(double a, double b, int n, int& lo, int& hi) {
  if (!std::isfinite(a) || !std::isfinite(b)) return false;
  const double l = std::max(std::floor(a - 0.5), 0.0);
  const double h = std::min(std::ceil(b - 0.5), static_cast<double>(n - 1));
  if (l > h) return false;
  lo = static_cast<int>(l);
  hi = static_cast<int>(h);
  return true;
}

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

}  // namespace

void draw_segment(Image& img, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width, Rgb color) {
  if (!a.allFinite() || !b.allFinite()) return;
  const double r = std::max(width, 1.0) / 2.0;
  int x0, x1, y0, y1;
  if (!pixel_range(std::min(a.x(), b.x()) - r, std::max(a.x(), b.x()) + r, img.width, x0, x1)) return;
  if (!pixel_range(std::min(a.y(), b.y()) - r, std::max(a.y(), b.y()) + r, img.height, y0, y1)) return;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x)
      if (distance_to_segment({x + 0.5, y + 0.5}, a, b) <= r) img.set(x, y, color);
}

void draw_polyline(Image& img, const std::vector<Eigen::Vector2d>& points, double width, Rgb color) {
  if (points.size() == 1) fill_disc(img, points[0], std::max(width, 1.0) / 2.0, color);
  for (std::size_t i = 1; i < points.size(); ++i) draw_segment(img, points[i - 1], points[i], width, color);
}

void fill_disc(Image& img, const Eigen::Vector2d& c, double radius, Rgb color) {
  draw_segment(img, c, c, 2.0 * radius, color);
}

void draw_ring(Image& img, const Eigen::Vector2d& c, double radius, double width, Rgb color) {
  if (!c.allFinite()) return;
  const double outer = radius + width / 2.0, inner = radius - width / 2.0;
  int x0, x1, y0, y1;
  if (!pixel_range(c.x() - outer, c.x() + outer, img.width, x0, x1)) return;
  if (!pixel_range(c.y() - outer, c.y() + outer, img.height, y0, y1)) return;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double d = (Eigen::Vector2d(x + 0.5, y + 0.5) - c).norm();
      if (d >= inner && d <= outer) img.set(x, y, color);
    }
}

void fill_rect(Image& img, int x0, int y0, int x1, int y1, Rgb color) {
  for (int y = std::max(y0, 0); y < std::min(y1, img.height); ++y)
    for (int x = std::max(x0, 0); x < std::min(x1, img.width); ++x) img.set(x, y, color);
}

void CoverageRaster::add_triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  constexpr double kSub = 256.0;    // sub-pixel grid
  constexpr double kLimit = 1.0e6;  // pixels; keeps every product below 2^63
  struct P { std::int64_t x, y; };
  P v[3];
  const Eigen::Vector2d* in[3] = {&a, &b, &c};
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d& q = *in[i];
    if (!q.allFinite() || std::abs(q.x()) > kLimit || std::abs(q.y()) > kLimit) return;
    v[i] = {std::llround(q.x() * kSub), std::llround(q.y() * kSub)};
  }
  auto cross = [](P o, P p, P q) { return (p.x - o.x) * (q.y - o.y) - (p.y - o.y) * (q.x - o.x); };
  const std::int64_t area2 = cross(v[0], v[1], v[2]);
  if (area2 == 0) return;
  if (area2 < 0) std::swap(v[1], v[2]);
  // Top-left rule: a pixel centre exactly on an edge belongs to the triangle for which
  // the edge runs in one fixed half of the directions; the neighbour across a shared
  // edge walks it the other way, so exactly one of the two counts the pixel.
  auto owns_edge = [](P p, P q) {
    const std::int64_t dx = q.x - p.x, dy = q.y - p.y;
    return dy < 0 || (dy == 0 && dx > 0);
  };
  const bool own[3] = {owns_edge(v[0], v[1]), owns_edge(v[1], v[2]), owns_edge(v[2], v[0])};
  const double minx = std::min({v[0].x, v[1].x, v[2].x}) / kSub, maxx = std::max({v[0].x, v[1].x, v[2].x}) / kSub;
  const double miny = std::min({v[0].y, v[1].y, v[2].y}) / kSub, maxy = std::max({v[0].y, v[1].y, v[2].y}) / kSub;
  int x0, x1, y0, y1;
  if (!pixel_range(minx, maxx, width, x0, x1) || !pixel_range(miny, maxy, height, y0, y1)) return;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const P p{static_cast<std::int64_t>(x) * 256 + 128, static_cast<std::int64_t>(y) * 256 + 128};
      const std::int64_t e[3] = {cross(v[0], v[1], p), cross(v[1], v[2], p), cross(v[2], v[0], p)};
      bool inside = true;
      for (int k = 0; k < 3 && inside; ++k) inside = e[k] > 0 || (e[k] == 0 && own[k]);
      if (inside) {
        std::uint16_t& n = count[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
        if (n < std::numeric_limits<std::uint16_t>::max()) ++n;
      }
    }
}

}  // namespace gw
