#pragma once
// Spec -> anatomy: the watertight vessel surface and its ground-truth centerline graph.
#include <optional>
#include <string>

#include "base/graph/centerline_graph.hpp"
#include "anatomy_gen/tree_spec.hpp"
#include "base/mesh/triangle_mesh.hpp"

namespace gw {

struct AnatomyOptions {
  bool open_ends = false;               // remove the inlet/outlet caps
  std::optional<double> deform_phase;   // overrides spec.deformation.phase
};

struct GeneratedAnatomy {
  TreeSpec spec;            // as generated (the deformation phase actually used recorded)
  TriangleMesh mesh;        // millimetres, closed unless open_ends
  CenterlineGraph truth;    // same schema as `centerline` output
  double volume = 0.0;      // enclosed volume of the mesh (mm^3; capped mesh only)
  double seconds = 0.0;     // wall time of the generation
};

// Applies the deformation (if the spec has one), builds and checks the geometry, meshes
// the implicit surface and builds the truth. Throws SpecError for a bad spec (message
// names the problem) and MeshError if the mesh fails its own checks (closed, manifold,
// one component): a generator bug, never silently written.
GeneratedAnatomy generate_anatomy(const TreeSpec& spec, const AnatomyOptions& options = {});

// Writes DIR/<name>.stl and DIR/<name>.truth.json (write_centerline).
void write_anatomy(const GeneratedAnatomy& anatomy, const std::string& dir);

// One-line JSON summary: name, faces, vertices, volume, targets, bifurcations, seconds.
std::string anatomy_summary_json(const GeneratedAnatomy& anatomy);

}  // namespace gw
