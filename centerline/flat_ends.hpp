#pragma once
// flat_ends: the vessel ends of a closed surface that were cut flat (a generated tube's end disk, a scan cropped
// at its box): terminal candidates, as the caps of open ends are (prepare_surface.hpp, SurfaceCap).
//
// Inputs: a closed, outward surface (mm) and its wall. Output: one SurfaceCap per end disk: a planar patch (face
// normals within 2 degrees of its first face's) of at least 12 faces, round (every vertex within 1.25 R of its
// centroid, R = sqrt(area / pi), the boundary's mean distance within 0.8-1.2 R), closing a tube of about its
// radius: from R inside it, rays in its plane meet the wall within 1.5 R (median of 12). A straight tube's wall,
// whose faces share a normal along a generator, is a long strip and fails the roundness test; a terrace of a voxel
// staircase on a wide vessel's wall fails the tube test (rays along the wall go far). Deterministic (faces
// visited in order).
#include <vector>

#include "base/mesh/triangle_mesh.hpp"
#include "centerline/prepare_surface.hpp"
#include "centerline/vessel_wall.hpp"

namespace gw {

std::vector<SurfaceCap> flat_ends(const TriangleMesh& surface, const VesselWall& wall);

}  // namespace gw
