#include "centerline/flat_ends.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

namespace gw {
namespace {

constexpr double kPlanarCos = 0.99939;  // cos 2 degrees: a face of the patch against its first face
constexpr int kMinFaces = 12;

// Per face, its three neighbours across its edges (-1: none; an edge shared by more than two faces has none).
std::vector<std::array<int, 3>> face_neighbours(const Eigen::MatrixX3i& F) {
  struct Half {
    std::uint64_t edge;  // the two vertex ids, smaller first
    int face, slot;
    bool operator<(const Half& o) const { return edge != o.edge ? edge < o.edge : face < o.face; }
  };
  std::vector<Half> halves;
  halves.reserve(static_cast<size_t>(3 * F.rows()));
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::uint64_t>(F(f, k)), b = static_cast<std::uint64_t>(F(f, (k + 1) % 3));
      halves.push_back({std::min(a, b) << 32 | std::max(a, b), f, k});
    }
  std::sort(halves.begin(), halves.end());
  std::vector<std::array<int, 3>> nb(static_cast<size_t>(F.rows()), {-1, -1, -1});
  for (size_t i = 0; i < halves.size();) {
    size_t j = i;
    while (j < halves.size() && halves[j].edge == halves[i].edge) ++j;
    if (j - i == 2) {
      nb[static_cast<size_t>(halves[i].face)][static_cast<size_t>(halves[i].slot)] = halves[i + 1].face;
      nb[static_cast<size_t>(halves[i + 1].face)][static_cast<size_t>(halves[i + 1].slot)] = halves[i].face;
    }
    i = j;
  }
  return nb;
}

// Whether the disk closes a tube of about its radius: from R inside it, the median of 12 rays in its plane meets the
// wall within 1.5 R.
bool closes_a_tube(const VesselWall& wall, const SurfaceCap& cap) {
  const Eigen::Vector3d inside = cap.centre - cap.radius * cap.normal;
  const Eigen::Vector3d u = cap.normal.unitOrthogonal(), v = cap.normal.cross(u);
  std::vector<double> hits;
  for (int k = 0; k < 12; ++k) {
    const double a = 2 * M_PI * k / 12;
    hits.push_back(wall.ray_hit(inside, std::cos(a) * u + std::sin(a) * v, 3.0 * cap.radius));
  }
  std::nth_element(hits.begin(), hits.begin() + 6, hits.end());
  return hits[6] <= 1.5 * cap.radius;
}

// The patch's end disk, when it is one.
bool as_end_disk(const TriangleMesh& m, const VesselWall& wall, const std::vector<int>& patch,
                 const std::vector<char>& in_patch,
                 const std::vector<std::array<int, 3>>& nb, const Eigen::MatrixX3d& normal,
                 const Eigen::VectorXd& area, SurfaceCap& cap) {
  if (static_cast<int>(patch.size()) < kMinFaces) return false;
  double total = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), n = Eigen::Vector3d::Zero();
  for (const int f : patch) {
    const Eigen::Vector3d c = (m.V.row(m.F(f, 0)) + m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2))).transpose() / 3.0;
    centre += area(f) * c;
    n += area(f) * normal.row(f).transpose();
    total += area(f);
  }
  centre /= total;
  const double R = std::sqrt(total / M_PI);
  int rim = 0;
  double rim_distance = 0.0;
  for (const int f : patch)
    for (int k = 0; k < 3; ++k) {
      if ((m.V.row(m.F(f, k)).transpose() - centre).norm() > 1.25 * R) return false;
      const int g = nb[static_cast<size_t>(f)][static_cast<size_t>(k)];
      if (g >= 0 && in_patch[static_cast<size_t>(g)]) continue;
      ++rim;
      rim_distance += (m.V.row(m.F(f, k)).transpose() - centre).norm();
    }
  if (rim == 0) return false;
  rim_distance /= rim;
  if (rim_distance < 0.8 * R || rim_distance > 1.2 * R) return false;
  cap.centre = centre;
  cap.normal = n.normalized();
  cap.radius = rim_distance;
  return closes_a_tube(wall, cap);
}

}  // namespace

std::vector<SurfaceCap> flat_ends(const TriangleMesh& m, const VesselWall& wall) {
  const int nf = static_cast<int>(m.F.rows());
  Eigen::MatrixX3d normal(nf, 3);
  Eigen::VectorXd area(nf);
  for (int f = 0; f < nf; ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    const Eigen::Vector3d x = (b - a).cross(c - a);
    area(f) = 0.5 * x.norm();
    const Eigen::Vector3d unit = x.norm() > 0 ? Eigen::Vector3d(x / x.norm()) : Eigen::Vector3d::Zero();
    normal.row(f) = unit.transpose();
  }
  const auto nb = face_neighbours(m.F);
  std::vector<char> seen(static_cast<size_t>(nf), 0), in_patch(static_cast<size_t>(nf), 0);
  std::vector<SurfaceCap> ends;
  for (int seed = 0; seed < nf; ++seed) {
    if (seen[static_cast<size_t>(seed)]) continue;
    std::vector<int> patch{seed};  // faces coplanar with the seed, reached across edges
    seen[static_cast<size_t>(seed)] = in_patch[static_cast<size_t>(seed)] = 1;
    for (size_t i = 0; i < patch.size(); ++i)
      for (const int g : nb[static_cast<size_t>(patch[i])])
        if (g >= 0 && !seen[static_cast<size_t>(g)] && normal.row(g).dot(normal.row(seed)) > kPlanarCos) {
          seen[static_cast<size_t>(g)] = in_patch[static_cast<size_t>(g)] = 1;
          patch.push_back(g);
        }
    SurfaceCap cap;
    if (as_end_disk(m, wall, patch, in_patch, nb, normal, area, cap)) ends.push_back(cap);
    for (const int f : patch) in_patch[static_cast<size_t>(f)] = 0;
  }
  return ends;
}

}  // namespace gw
