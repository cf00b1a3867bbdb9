#include "centerline/estimate_wall_noise.hpp"
#include "base/util/median.hpp"

#include <algorithm>

#include "centerline/cross_section.hpp"
#include "centerline/polyline_tools.hpp"

namespace gw {

double estimate_wall_noise(const std::vector<std::vector<Eigen::Vector3d>>& chains, const VesselWall& wall,
                           double spacing) {
  constexpr double kSmoothWall = 0.01;  // smooth generated surfaces: 0.002; 0.3-0.6 mm voxels: 0.03-0.05
  constexpr size_t kMinSections = 20;
  std::vector<double> noise;
  for (const auto& chain : chains) {
    if (chain.size() < 2) continue;
    const std::vector<Eigen::Vector3d> p = smooth_polyline(resample_polyline(chain, spacing), 2);
    const std::vector<Eigen::Vector3d> tangent = polyline_tangents(smooth_polyline(p, 4));
    for (size_t i = 0; i < p.size(); ++i) {
      const CrossSection cs = fit_cross_section(wall, p[i], tangent[i], 4.0 * wall.distance(p[i]) + 1e-9);
      if (cs.elongation < 1.4) noise.push_back(cs.roughness);
    }
  }
  if (noise.size() < kMinSections) return 0.0;
  const double m = median(noise);
  return m < kSmoothWall ? 0.0 : m;
}

}  // namespace gw
