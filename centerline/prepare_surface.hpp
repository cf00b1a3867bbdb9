#pragma once
// Make any vessel surface usable by mean-curvature-flow skeletonisation: one closed,
// outward-oriented triangle 2-manifold with a face size tied to the vessel radius.
#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "base/mesh/triangle_mesh.hpp"

namespace gw {

// An open boundary loop that was closed: an inlet/outlet of a clinical surface, so a
// terminal candidate.
struct SurfaceCap {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // centroid of the loop vertices
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // points out of the vessel
  double radius = 0.0;                                // mean distance of the loop to its centre
};

// What close_surface may do to a surface that is not already one closed piece.
struct SurfaceRepairOptions {
  // A piece whose area is below this share of the largest piece's is an island (segmentation
  // noise, a stray label) and is dropped; larger pieces are parts of the vessel and are kept.
  double island_area_fraction = 0.02;
  // Alpha wrapping (alpha_wrap_surface.hpp) when cheap repairs leave several pieces or holes
  // that only a makeshift fan could close. false: such a surface is refused instead.
  bool allow_wrap = true;
  bool force_wrap = false;      // wrap even a surface the cheap repairs closed (tests, comparisons)
  double wrap_alpha_factor = 0.5;    // ball radius = this x the thin vessels' radius (vessel_scale.hpp)
  double wrap_offset_factor = 0.04;  // offset = this x the same radius (the wall moves out by it)
  // A surface with more than this share of its area facing voxel-lattice directions is a voxel
  // staircase (smooth_staircase.hpp) and gets `staircase_passes` Taubin passes (0: never).
  double staircase_share = 0.5;
  int staircase_passes = 10;
};

struct ClosedSurface {
  TriangleMesh mesh;               // closed, single component, outward normals
  std::vector<SurfaceCap> caps;    // one per capped open end (round holes; slits are not ends)
  int dropped_components = 0;      // islands that were removed
  long dropped_faces = 0;          // their faces, in all
  double largest_dropped_area = 0; // of the biggest island (mesh units squared)
  int kept_pieces = 1;             // pieces big enough to be vessel (> 1 forces a wrap)
  bool soup_repaired = false;      // the faces did not form a consistent 2-manifold as given
  long split_vertices = 0;         // vertices duplicated to undo non-manifold joins
  long fan_caps = 0;               // non-round holes only a fan around their centroid could close (-> wrap)
  long fan_end_caps = 0;           // round vessel ends capped by a fan (non-planar loops): a fine cap
  bool flipped = false;            // normals pointed into the lumen and were reversed
  bool wrapped = false;            // the result is an alpha wrap of the repaired input
  double lattice_share = 0.0;      // area share facing voxel-lattice directions (smooth_staircase.hpp)
  bool smoothed = false;           // a voxel staircase was Taubin-smoothed
  double wrap_alpha = 0.0, wrap_offset = 0.0, wrap_scale_radius = 0.0;
  std::vector<std::string> repairs;  // every repair above, one human-readable line each
  std::vector<std::pair<std::string, double>> stage_seconds;  // wall time of each stage below
  double volume = 0.0, area = 0.0; // of `mesh`
  // Radius of a tube with the same volume/area ratio (V/A = r/2): the size remeshing
  // and every tolerance of the pipeline are tied to.
  double mean_radius() const { return area > 0 ? 2.0 * volume / area : 0.0; }
};

// Makes one closed, outward-oriented triangle 2-manifold of a vessel surface, in named stages:
//   build    halfedge mesh as given; if the faces are not a consistent 2-manifold: soup repair
//            (duplicate/degenerate faces), consistent orientation, non-manifold joins split
//   islands  pieces below `island_area_fraction` of the largest are dropped
//   cap      every open boundary is triangulated (a round one is an open vessel end: its centre,
//            normal and radius become a terminal candidate); a hole the triangulation cannot
//            close gets a fan around its centroid
//   wrap     several vessel-sized pieces or a fan cap: alpha wrap of everything (alpha and offset
//            from the thin vessels' radius), so a closed manifold always comes out
//   orient   normals outwards (positive volume)
//   smooth   a voxel staircase (marching cubes of a label map) is Taubin-smoothed
// Every repair is listed in `repairs`. Throws std::runtime_error "<problem>" for an unusable
// surface: no faces, non-finite coordinates, a sheet that encloses no volume.
ClosedSurface close_surface(const TriangleMesh& mesh, const SurfaceRepairOptions& options = {});

// Inputs with more faces than this many times the target count get their vertices clustered on a
// grid of half the target edge before the edge collapse (remesh_surface): a fine marching-cubes
// surface (1M faces) then takes seconds, not tens. The committed anatomies stay below it.
inline constexpr double kClusterDecimationRatio = 20.0;

// Isotropic remeshing of a closed surface to edges of about `edge_length`
// (`iterations` passes of split/collapse/flip/smooth). Keeps it closed.
TriangleMesh remesh_surface(const TriangleMesh& closed, double edge_length, int iterations = 3);

}  // namespace gw
