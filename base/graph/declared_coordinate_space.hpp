#pragma once
// The coordinate frame a mesh file says it is in, as 3D Slicer writes it ("SPACE=LPS" or
// "SPACE=RAS" in the STL header, an OBJ/PLY comment or the legacy VTK header; Slicer >= 4.11
// writes LPS by default). For the mesh intake: the project works in RAS (see
// read_slicer_markups.hpp), so a mesh declaring LPS has x and y negated on reading (a rotation
// by 180 degrees about z: triangle orientation is kept), which puts it in the frame of the
// Slicer curves and fiducials read with read_centerline / read_slicer_points.
// In:  a path. Out: "LPS", "RAS", or "" (nothing declared, or the file cannot be read: the
// mesh reader reports that). Only the first 4 KiB are looked at.
#include <string>

namespace gw {

std::string declared_coordinate_space(const std::string& path);

}  // namespace gw
