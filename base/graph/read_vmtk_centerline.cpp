#include "base/graph/read_vmtk_centerline.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "base/graph/polyline_tree.hpp"
#include "base/graph/vtp_polylines.hpp"

namespace gw {
namespace {

struct Line {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> radii;
};

}  // namespace

CenterlineGraph read_vmtk_centerline(const std::string& path) {
  static const std::string kRadius = "MaximumInscribedSphereRadius";
  const VtpPolylines vtp = read_vtp_polylines(path, {kRadius});
  const std::vector<double>& radius = vtp.point_arrays.at(kRadius);
  const auto fail = [&](const std::string& what) { return std::runtime_error(path + ": " + what); };

  std::vector<Line> lines;
  double extent = 0.0;
  for (const Eigen::Vector3d& p : vtp.points) extent = std::max(extent, (p - vtp.points.front()).norm());
  const double same = 1e-9 * std::max(extent, 1.0);  // consecutive points closer than this are one
  for (size_t c = 0; c < vtp.lines.size(); ++c) {
    Line line;
    for (std::int64_t id : vtp.lines[c]) {
      const Eigen::Vector3d p = vtp.points[static_cast<size_t>(id)];
      const double r = radius[static_cast<size_t>(id)];
      if (!std::isfinite(r) || r < 0)
        throw fail("line " + std::to_string(c) + ": " + kRadius + " " + std::to_string(r) + " is not a radius");
      if (!line.points.empty() && (p - line.points.back()).norm() <= same) continue;
      if (vtp.space == "LPS") line.points.emplace_back(-p.x(), -p.y(), p.z());
      else line.points.push_back(p);
      line.radii.push_back(r);
    }
    if (line.points.size() >= 2) lines.push_back(std::move(line));
  }
  if (lines.empty()) throw fail("no line has two or more distinct points");

  // The inlet is the end every line shares: the first points (vmtkcenterlines' order) or the last.
  const auto tolerance = [&](double r) { return std::max(kVmtkSharedTrunkFraction * r, 1e-6 * std::max(extent, 1.0)); };
  auto shared = [&](bool front) {
    const Line& a = lines.front();
    const Eigen::Vector3d p = front ? a.points.front() : a.points.back();
    const double r = front ? a.radii.front() : a.radii.back();
    return std::all_of(lines.begin(), lines.end(), [&](const Line& l) {
      return ((front ? l.points.front() : l.points.back()) - p).norm() <= tolerance(r);
    });
  };
  if (lines.size() > 1 && !shared(true)) {
    if (!shared(false))
      throw fail("the " + std::to_string(lines.size()) +
                 " lines share neither their first nor their last point: they do not start from one inlet");
    for (Line& l : lines) {
      std::reverse(l.points.begin(), l.points.end());
      std::reverse(l.radii.begin(), l.radii.end());
    }
  }

  try {
    PolylineTree tree(lines.front().points, lines.front().radii);
    for (size_t c = 1; c < lines.size(); ++c) {
      const Line& l = lines[c];
      std::vector<double> d(l.points.size());
      size_t parted = l.points.size();
      for (size_t i = 0; i < l.points.size(); ++i) {
        d[i] = tree.nearest(l.points[i]).distance;
        if (d[i] > tolerance(l.radii[i])) {
          parted = i;
          break;
        }
      }
      if (parted == l.points.size()) continue;  // runs along the tree all the way: nothing new
      if (parted == 0) throw fail("line " + std::to_string(c) + " does not start at the inlet");
      size_t last = parted - 1;  // the last shared point: back to where the distance starts growing
      while (last > 0 && d[last - 1] < d[last]) --last;
      const std::vector<Eigen::Vector3d> points(l.points.begin() + static_cast<long>(last) + 1, l.points.end());
      const std::vector<double> radii(l.radii.begin() + static_cast<long>(last) + 1, l.radii.end());
      tree.attach(tree.nearest(l.points[last]), points, radii);
    }
    return tree.graph();
  } catch (const std::invalid_argument& e) {
    throw fail(e.what());
  }
}

}  // namespace gw
