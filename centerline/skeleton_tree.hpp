#pragma once
// Turn the raw MCF skeleton (hundreds of nodes, spurs, junction clusters) into a clean
// tree of chains between terminals and junctions.
#include <Eigen/Core>
#include <functional>
#include <vector>

#include "centerline/mcf_skeleton.hpp"
#include "centerline/prepare_surface.hpp"

namespace gw {

struct SkeletonChain {
  int a = -1, b = -1;                    // key nodes at either end
  std::vector<Eigen::Vector3d> points;   // a ... b, both ends included
};

struct SkeletonTree {
  std::vector<Eigen::Vector3d> nodes;  // key nodes: terminals (1 chain) and junctions (3+)
  std::vector<SkeletonChain> chains;   // no cycles, every node used
  // Vessel ends known from the surface (capped open ends, flat ends: flat_ends.hpp), set where the first skeleton
  // missed one (extract_centerline.cpp): an arm ending at one is a vessel, never a spur.
  std::vector<SurfaceCap> known_ends;
  std::vector<int> degree() const;
  // Whether p lies within two radii of a known end (the cap rule of SkeletonCleanup::cap_factor).
  bool at_known_end(const Eigen::Vector3d& p) const;
};

struct SkeletonCleanup {
  double spur_factor = 2.0;   // a terminal chain shorter than this * radius at its junction is a spur
  double merge_factor = 1.0;  // junctions closer than this * local radius become one bifurcation, if also
                              // closer than this * the sum of their thinnest other arms' radii (openings overlap)
  double cap_factor = 2.0;    // a terminal within this * radius of a cap is a real end, never a spur
};

// Chains between the skeleton's key nodes (at the MCF node positions),
// then repeatedly: prune the shortest spur, merge close junctions, join chains through
// nodes left with two chains. Cycles are cut (the chain closing a cycle is dropped).
// `radius_at(p)` is the vessel radius near p; `caps` the centres of capped holes.
SkeletonTree clean_skeleton(const RawSkeleton& raw, const std::function<double(const Eigen::Vector3d&)>& radius_at,
                            const std::vector<Eigen::Vector3d>& caps, const SkeletonCleanup& options = {});

}  // namespace gw
