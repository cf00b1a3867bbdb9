#pragma once
// Stage "detect": which parts of the wire are within reach of the vessel wall.
// Contact points are the free nodes and the midpoints of elements longer than 1 mm (so a 2 mm chord
// cannot cut through a bend of the wall between two nodes); each becomes a unilateral constraint along the wall's inward
// direction at the start of the step, with two friction directions. The constraint keeps the linearised
// clearance gap + dt n.(v - v_wall) >= 0 at the end of the step (v_wall = 0 for a static wall). Broad phase: FCL sphere-vs-BVH queries, cached per point
// (WireState::wall_cache) and redone only when the point has moved more than the cache slack.
#include <Eigen/Core>
#include <limits>
#include <vector>

#include "engine/scene/vessel_scene.hpp"
#include "engine/wire/wire_state.hpp"

namespace gw {

struct ContactPoint {
  int point = 0;                // contact point id: node i -> i, midpoint of element e -> nodes + e
  int side = 0;                 // 0: the nearest wall; 1: a second side of a crease (see detect_contacts)
  int node_a = 0, node_b = -1;  // nodes carrying it (node_b = -1 for a node point)
  double wa = 1, wb = 0;        // interpolation weights
  Eigen::Vector3d n, t1, t2;    // n: into the lumen; t1, t2: tangent plane
  double gap = 0;               // wall clearance of the wire surface at the start of the step [mm]
  Eigen::Vector3d v_free;       // velocity of the point after the free (contact-less) motion [mm/s]
  // A moving wall: the wall's mean velocity over the sub-step at the contact [mm/s]; the constraint and
  // the friction act on the relative velocity v - v_wall (zero for a static wall).
  Eigen::Vector3d v_wall = Eigen::Vector3d::Zero();
  // Angular velocity of the point after the free motion [rad/s] (interpolated like v_free); only read
  // with friction at the wire surface (ContactWorkspace::lever), filled by the caller then.
  Eigen::Vector3d w_free = Eigen::Vector3d::Zero();
};

// Number of contact points (nodes + element midpoints) a model has.
int contact_point_count(const WireModel& model);

// Position of contact point `point` given node positions.
Eigen::Vector3d contact_point_position(const WireModel& model, const std::vector<Eigen::Vector3d>& x, int point);

// True when `point` is inserted far enough to be tested against the wall (past inlet_clearance_mm).
bool contact_point_active(const WireModel& model, const WireState& state, int point);

// Signed distance (> 0 inside) from `p` (contact point `point`) to the wall, using and refreshing the
// state's cache. Exact whenever the distance is below `need` (with `exact_to_cutoff`: below
// max(need, divergence margin + radius)); otherwise a lower bound >= need, reported as inside
// (triangle = -1): a point cannot get farther outside than that without first being seen within it.
// Points known (by the last query's distance and how far they moved since) to be deeper than that are
// answered without a scan.
// A moving wall (scene.motion) is taken at `time` (NaN: state.time).
WallDistance cached_wall_distance(const WireModel& model, const VesselScene& scene, WireState& state, int point,
                                  const Eigen::Vector3d& p, double need, bool exact_to_cutoff = false,
                                  double time = std::numeric_limits<double>::quiet_NaN());

// Whether a wall normal measured at the middle of a contact point's motion may replace the one from the
// start of the step (re-linearisation): only when both belong to the same side of the wall, i.e. turn by
// less than 60 degrees. In a vessel not much wider than the wire, the middle of a fast motion can be
// nearer the OPPOSITE wall; taking that wall's normal drops the constraint that holds the point, which
// then passes through the wall (seen as "wire point ... outside the vessel wall" divergences in the
// coronary tree when a folded tip snapped across a 0.8 mm branch).
bool same_wall_side(const Eigen::Vector3d& start_normal, const Eigen::Vector3d& mid_normal);

// A point deeper than this into its nearest wall [mm] also gets a contact on a second side of the wall
// where there is one within reach (detect_contacts). A held contact leaves under 0.007 mm (the bench
// insertions' deepest penetration); 0.01 was chosen on the jam of docs/physics.md among 0.005-0.02.
constexpr double kCreaseDepthMm = 0.01;

// Where a contact point's warm-start impulse is kept in WireState::contact_impulse (2 per point: a side each).
inline int contact_slot(int point_count, const ContactPoint& c) { return c.point + c.side * point_count; }

// Contacts of the wire at the start of the step (state.x), linearised there (SOFA-style): every active
// point whose wall clearance is below the margin plus its free-motion travel h |v_free| this sub-step
// (length h [s]). A point found more than kCreaseDepthMm inside its nearest wall (static or moving) is in a
// crease narrower than the wire (a tip wedged where two walls meet at a dead end or a taper): it also gets
// a contact (side 1) with the nearest wall of the other side, the nearest triangle within its reach that
// faces away from the first by more than 60 degrees (same_wall_side), where there is one. With the nearest
// wall's constraint alone such a point is pushed out of one wall into the other, and the nearest wall
// swaps every sub-step: a tip chattering at ~1 m/s that halves every sub-step. `v_free`: per node velocity
// after the free motion. Clears and fills `out`; `deepest` = largest distance of an active point outside the
// wall (0 if none).
void detect_contacts(const WireModel& model, const VesselScene& scene, WireState& state,
                     const std::vector<Eigen::Vector3d>& v_free, double h, std::vector<ContactPoint>& out,
                     double& deepest);

}  // namespace gw
