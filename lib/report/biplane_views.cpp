#include "lib/report/biplane_views.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace gw {

std::array<ViewAxes, 2> choose_biplane_axes(const std::vector<Eigen::Vector3d>& points,
                                            const Eigen::Vector3d& inlet, BiplaneAxes mode) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::size_t n = 0;
  for (const auto& p : points)
    if (p.allFinite()) {
      mean += p;
      ++n;
    }
  if (n == 0) throw std::invalid_argument("biplane: the scene has no finite point to frame");
  mean /= static_cast<double>(n);

  if (mode == BiplaneAxes::FixedXY_ZY)
    return {ViewAxes{"FRONTAL", Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()},
            ViewAxes{"LATERAL", Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY()}};

  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : points)
    if (p.allFinite()) cov += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);  // eigenvalues ascending
  Eigen::Vector3d down = eig.eigenvectors().col(2);
  Eigen::Vector3d right = eig.eigenvectors().col(1);
  // Inlet at the top: going from the inlet to the scene's centre goes down the screen.
  // (With the inlet at the centre the sign is arbitrary but still deterministic.)
  if ((mean - inlet).allFinite() && (mean - inlet).dot(down) < 0.0) down = -down;
  Eigen::Index k;
  right.cwiseAbs().maxCoeff(&k);
  if (right[k] < 0.0) right = -right;
  const Eigen::Vector3d up = -down;
  const Eigen::Vector3d lateral_right = right.cross(up).normalized();
  return {ViewAxes{"FRONTAL", right.normalized(), up.normalized()}, ViewAxes{"LATERAL", lateral_right, up.normalized()}};
}

}  // namespace gw
