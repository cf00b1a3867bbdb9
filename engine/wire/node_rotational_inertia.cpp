#include "engine/wire/node_rotational_inertia.hpp"

namespace gw {

Eigen::Matrix3d node_rotational_inertia(const WireModel& model, int i, const Eigen::Matrix3d& r) {
  const double j = model.rot_inertia[i];
  if (!model.params.per_axis_rotational_inertia) return j * Eigen::Matrix3d::Identity();
  const Eigen::Vector3d t = r.col(0);
  return 0.5 * j * (Eigen::Matrix3d::Identity() + t * t.transpose());
}

}  // namespace gw
