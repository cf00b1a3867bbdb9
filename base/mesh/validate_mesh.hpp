#pragma once
// Inspect a triangle mesh for everything that breaks centerline extraction or contact:
// holes, non-manifold edges, several components, degenerate faces, NaN, wrong units.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "base/mesh/triangle_mesh.hpp"

namespace gw {

struct MeshReport {
  long vertices = 0;
  long faces = 0;
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero();
  Eigen::Vector3d bbox_max = Eigen::Vector3d::Zero();
  double max_extent = 0.0;         // largest bounding-box side
  long non_finite_vertices = 0;    // NaN or inf coordinates
  long degenerate_faces = 0;       // repeated index or (near) zero area
  long boundary_edges = 0;         // edges used by exactly one face
  long boundary_loops = 0;         // open holes (inlets/outlets of a clinical mesh)
  long non_manifold_edges = 0;     // edges used by more than two faces
  long components = 0;             // face-connected pieces
  double volume = 0.0;             // signed enclosed volume; meaningful when closed
  std::vector<std::string> errors;    // fatal: the mesh cannot be used
  std::vector<std::string> warnings;  // usable, but the user should know

  bool closed() const { return boundary_edges == 0; }
  bool manifold() const { return non_manifold_edges == 0; }
  bool ok() const { return errors.empty(); }
};

// Computes every field above. Error: non-finite coordinates. Warnings: open
// boundaries, non-manifold edges, several components, degenerate faces, unit
// suspicion (largest side < 1 -> metres, < 5 -> centimetres, > 5000 -> micrometres;
// vessel anatomies are expected in millimetres, tens to hundreds across).
MeshReport validate_mesh(const TriangleMesh& mesh);

// Human-readable multi-line summary, for `mesh-info` and logs.
std::string format_report(const MeshReport& report);

// The same as one JSON object (string), for `--json` and tests.
std::string report_to_json(const MeshReport& report);

}  // namespace gw
