#pragma once
// A triangle surface mesh: the one in-memory form every module takes (libigl style V/F).
#include <Eigen/Core>
#include <stdexcept>
#include <string>

namespace gw {

struct TriangleMesh {
  Eigen::MatrixX3d V;  // vertex positions, one row per vertex (millimetres after scaling)
  Eigen::MatrixX3i F;  // triangles as vertex indices, counter-clockwise seen from outside
};

// Every mesh problem the user must hear about: message is "<file>: <problem>".
class MeshError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace gw
