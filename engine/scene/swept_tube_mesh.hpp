#pragma once
// A closed tube around a centreline: a circle of `radius` swept along `centreline` (frames by parallel
// transport, so the tube does not twist), capped flat at both ends; faces counter-clockwise seen from
// outside, as make_vessel_scene wants. For validation scenes (a rigid bend, a tube with three bends).
// Inputs: centreline, one row per point (at least 2, consecutive points distinct), in mm; radius > 0;
// segments >= 3, vertices per ring. Output: the mesh (rings of `segments` vertices, one per centreline
// point, plus a centre vertex per cap). Throws std::invalid_argument for bad inputs.
#include <Eigen/Core>

#include "base/mesh/triangle_mesh.hpp"

namespace gw {

TriangleMesh swept_tube_mesh(const Eigen::MatrixX3d& centreline, double radius, int segments = 24);

}  // namespace gw
