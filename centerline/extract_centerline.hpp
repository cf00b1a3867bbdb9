#pragma once
// Centerline extraction: vessel surface -> CGAL mean-curvature-flow skeleton -> CenterlineGraph.
#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "centerline/prepare_surface.hpp"
#include "base/graph/centerline_graph.hpp"
#include "base/mesh/triangle_mesh.hpp"

namespace gw {

struct CenterlineOptions {
  std::optional<Eigen::Vector3d> inlet;  // the terminal nearest this point is the inlet; else the widest
  double spacing = 0.5;                  // output point spacing along branches (mm)
  double edges_per_radius = 2.0;         // remeshing before MCF: edge length = mean radius / this,
  int max_skeleton_faces = 10000;        //   or longer so that MCF gets at most about this many faces
  double edges_around_thinnest = 8.0;    // remeshed again finer (down to that cap) when the first skeleton's
                                         //   thinnest branch gets fewer edges round its circumference
  double spur_factor = 2.0;              // terminal chains shorter than this * radius are spurs
  double merge_factor = 1.0;             // junctions closer than this * radius become one bifurcation
  int smoothing_iterations = 4;          // Laplacian passes on each branch after re-centring
};

struct CenterlineStats {
  long input_faces = 0;     // faces of the given mesh
  long skeleton_faces = 0;  // faces after remeshing, what MCF ran on
  int skeleton_passes = 1;  // 2: remeshed finer for a thin branch (options.edges_around_thinnest) or a missed end
  int missed_ends = 0;      // known vessel ends (caps, flat ends) the first skeleton had no terminal near
  int capped_holes = 0, dropped_components = 0;
  double mean_radius = 0.0;  // 2 * volume / area of the closed surface (mm)
  double seconds_prepare = 0, seconds_skeleton = 0, seconds_graph = 0;
  std::vector<std::pair<std::string, double>> intake_seconds;  // per intake stage, when it ran (cache miss)
  std::vector<std::string> repairs;   // what the intake / close_surface changed, one line each
  std::vector<std::string> warnings;  // suspicions that changed nothing
  double wall_noise = 0.0;  // estimate_wall_noise: the wall's roughness (rms share of the radius; 0: smooth)
};

// Extracts the centerline graph of `mesh` (mm):
//  1. close_surface: repair, drop islands, cap holes (their centres are terminal
//     candidates), alpha-wrap what cheap repairs cannot close, orient outwards;
//  2. remesh_surface to edges of mean radius / edges_per_radius, so MCF cost depends on
//     the vessel size rather than on the input tessellation; once more, finer, when the first
//     skeleton (3-4) has a branch with fewer than edges_around_thinnest edges round it (an aortic
//     arch: the mean radius is the aorta's, the great vessels are 2.5 times thinner), or
//     when a known vessel end (a capped open end, or one cut flat: flat_ends.hpp) has no terminal of
//     the first skeleton within 6 of its radii (a great vessel cut to a stub on an arch's roof); an
//     end still without a terminal then gets a grafted chain, and the arms ending at known ends are
//     never dropped as stubs (SkeletonTree::known_ends);
//  3. mcf_skeleton (its node positions; correspondence centroids scatter when few
//     surface vertices collapse onto a node, so they are not used);
//  4. clean_skeleton: prune spurs, merge junction clusters into single bifurcations;
//  5. the inlet: terminal nearest options.inlet, else the one with the widest branch;
//     branches are directed distally by walking the tree from it;
//  6. refine_branch: re-centre on cross-sections, extend terminal ends to the wall,
//     smooth, resample at `spacing`, radius per point;
//  7. number_targets (the documented rule in centerline_graph.hpp).
// Throws std::runtime_error with a clear message when the surface cannot be repaired
// into a closed 2-manifold or yields no usable skeleton.
CenterlineGraph extract_centerline(const TriangleMesh& mesh, const CenterlineOptions& options = {},
                                   CenterlineStats* stats = nullptr);

// Steps 2-7 on a surface close_surface already made (intake_surface.hpp): its caps are the
// terminal candidates, its repairs are reported as warnings.
CenterlineGraph extract_centerline(const ClosedSurface& closed, const CenterlineOptions& options = {},
                                   CenterlineStats* stats = nullptr);

}  // namespace gw
