#pragma once
// The mutable part of the simulation (like mjData): plain values, cheap and exact to copy.
// Copying a state and stepping both copies with the same controls gives bit-identical results.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "engine/wire/wire_model.hpp"

namespace gw {

// Per contact point (node or element midpoint), the wall triangles within `gathered` of `centre`, found
// by a grid range query (engine/scene/triangle_grid) and sorted by a lower bound of their distance to
// `centre`. Any triangle within (gathered - |p - centre|) of a point p is in the list, so queries stay
// exact while the point moves little; a pure accelerator: contacts, normals and penetrations are
// identical with an empty cache (only distances beyond what a query needs come back as lower bounds).
struct WallCandidates {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double gathered = -1;             // query radius used at `centre`; < 0: invalid
  std::vector<int> triangles;       // sorted by lower_bounds
  std::vector<double> lower_bounds; // lower bound of each triangle's distance to centre
  double clearance = 0;             // when `triangles` is empty: signed wall distance at centre (> 0 inside)
  int closest = -1;                 // position in `triangles` of the last query's closest triangle (-1: none)
  // Lower bound of the signed wall distance at `bound_point`, from the last query of this point. The
  // signed distance is 1-Lipschitz, so bound - |p - bound_point| bounds it at p: a point that is still
  // deeper inside than a query's cutoff needs no triangle scan (most of a wire in a wide lumen).
  Eigen::Vector3d bound_point = Eigen::Vector3d::Zero();
  double bound = -1e300;
  // Moving walls (VesselScene::motion): the wall times the list (lower bounds, clearance) and `bound`
  // were measured at; later queries take off the wall's largest travel since (wall_max_travel).
  double wall_time = 0, bound_time = 0;
  // Rigid and cardiac walls keep the list in the REST configuration instead (engine/contact/
  // detect_contacts.cpp): `centre`, `gathered`, `lower_bounds` and `clearance` are then rest-frame
  // values around the point's pre-image, valid whatever the heart does; `rest_point` is the point's
  // last pre-image (the next Newton start).
  bool rest = false;
  Eigen::Vector3d rest_point = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector4d> rest_spheres;  // rest bounding sphere per triangle, in list order (locality)
  // Static walls: per triangle in list order, its bounding sphere (centre, radius) and its plane (unit
  // normal, offset): the scene's face_spheres and face_planes, read in order by every scan of the list.
  std::vector<Eigen::Vector4d> face_bounds;
};

struct WireState {
  std::vector<Eigen::Vector3d> x;     // node positions [mm], proximal -> distal
  std::vector<Eigen::Quaterniond> q;  // node frames (local x = tangent, tip bends towards local +y)
  std::vector<Eigen::Vector3d> v;     // linear velocities [mm/s]
  std::vector<Eigen::Vector3d> w;     // angular velocities, world frame [rad/s]
  std::vector<Eigen::Vector3d> external_force;   // applied loads on free nodes [mN] (tests, user)
  std::vector<Eigen::Vector3d> external_torque;  // [mN mm]
  std::vector<Eigen::Vector3d> contact_force;    // last step's wall force per node [mN]
  Eigen::Vector3d inlet = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
  Eigen::Quaterniond base_frame = Eigen::Quaterniond::Identity();  // introducer frame at zero roll
  double inserted_length_mm = 0;
  double proximal_rotation_rad = 0;
  double time = 0;
  long steps = 0;
  // Whether the last sub-step found a contact (adaptive stepping, WireModel::free_span: only a sub-step
  // after a free one may be long). True in a new state: its first sub-step is a contact one.
  bool last_substep_in_contact = true;
  std::string diverged;                  // non-empty once a step failed: the problem; reset to go on
  std::vector<WallCandidates> wall_cache;  // contact broad-phase cache (nodes, then element midpoints)
  const void* wall_cache_scene = nullptr;  // scene the cache was built for
  std::vector<double> contact_impulse;     // last normal impulse per contact point (PGS warm start)
};

// Wire along `direction` with its tip `inserted_length_mm` past `inlet`, rolled by
// `proximal_rotation_rad` about the axis; the inserted part starts in its rest shape (curved tip, at
// rest). Throws std::runtime_error for a zero or non-finite direction/inlet or a negative length.
WireState make_initial_state(const WireModel& model, const Eigen::Vector3d& inlet, const Eigen::Vector3d& direction,
                             double proximal_rotation_rad, double inserted_length_mm = 2.0);

// First node that is out of the introducer (free); nodes before it are driven kinematically.
// Returns model.nodes when nothing is inserted yet. Node 0 is always held.
int first_free_node(const WireModel& model, const WireState& state);

// Places the introducer-held nodes on the inlet axis with the current roll; their velocities are the
// push along the axis and the roll rate about it.
void place_held_nodes(const WireModel& model, WireState& state, double push_mm_per_s, double rotate_rad_per_s);

// The frame of the held (introducer) part at the state's current roll.
Eigen::Quaterniond introducer_frame(const WireState& state);

}  // namespace gw
