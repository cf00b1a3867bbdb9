#pragma once
// A smooth cardiac-like displacement field, scaled by a phase in [0,1].
// With heart centre c, unit long axis a, y = x - c, height h = y.a, radial part y_r = y - h a:
//   x'(x, phase) = c + R_a(theta) [(1 - phase*rc) y_r] + (1 - phase*as) h a,
//   theta = phase * twist_deg_per_cm * (h / 10 mm)   (degrees, about a)
// rc = radial_contraction, as = axial_shortening. Phase 0 is the identity and phase 1 the
// maximum amplitude; the map is smooth (C-infinity) and invertible for |rc|, |as| < 0.5.
// Radii are not changed: vessel calibre is assumed constant over the cycle.
#include <Eigen/Core>

#include "base/graph/centerline_graph.hpp"
#include "anatomy_gen/tree_spec.hpp"

namespace gw {

// x' for one point.
Eigen::Vector3d deform_point(const DeformationSpec& field, const Eigen::Vector3d& x, double phase);

// The spec with every control point displaced at `phase`; children stay on their parents
// (each child's first point follows the parent curve at the same spline parameter).
// The result has no deformation block (it is already applied).
TreeSpec deform_spec(const TreeSpec& spec, const DeformationSpec& field, double phase);

// Every point of a centreline graph displaced (inlet direction recomputed), e.g. to move a
// ground truth with the anatomy. Radii are kept.
void deform_centerline(CenterlineGraph& graph, const DeformationSpec& field, double phase);

}  // namespace gw
