#pragma once
// The moving vessel wall (issue 36): a time-varying surface x_i(t) = X_i + D_i(t) over the scene's
// rest mesh (vertex X_i, same triangles), constant like the rest of the model (like mjModel); the time
// is the wire state's (WireState::time). Attached to a VesselScene (VesselScene::motion); a scene
// without motion is today's rigid static wall, stepped by exactly the same code.
//
// Sources of D (WallMotionKind):
//   rigid    D(t) = velocity t + amplitude sin(2 pi phase(t))              (tests: a carried/shaken tube)
//   cardiac  D(X, s) with s = cardiac_activation(phase(t)) in [0, 1], the map of the anatomy generator
//            (anatomy_gen/deformation.hpp) plus a rotation and a translation:
//              y = X - c, h = y.a, y_r = y - h a,  theta = s (twist h + rotation)
//              x = c + R_a(theta) (1 - s rc) y_r + (1 - s as) h a + s T
//            rc = contraction_mm / reference radius, as = shortening_mm / reference length; with a
//            fixed point F, D(X) - D(F) (the wall seen from a frame that moves with F)
//   phases   N surfaces of the same vertex order at phases j / N (4D CT), linearly interpolated in phase.
// phase(t) = frac(phase_offset + t * heart_rate_bpm / 60), so 0 bpm freezes the wall at phase_offset.
// Cardiac waveform (cardiac_activation), with systole fraction S (default 1/3 of the cycle):
//   s = (1 - cos(pi phase / S)) / 2                     for phase < S   (systole: 0 -> 1)
//   s = (1 + cos(pi (phase - S) / (1 - S))) / 2         for phase >= S  (diastole: 1 -> 0)
// C1 at both joins (zero rate at end-diastole and end-systole); s = 1 is end-systole.
#include <Eigen/Core>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "base/mesh/triangle_mesh.hpp"

namespace gw {

enum class WallMotionKind { rigid, cardiac, phases };

// The parametric cardiac motion as written in a motion JSON file (load_cardiac_motion), amplitudes in mm
// at end-systole (s = 1).
struct CardiacMotion {
  double heart_rate_bpm = 60;
  double systole_fraction = 1.0 / 3.0;
  double phase_offset = 0;                                    // phase at t = 0 (0 = end-diastole)
  Eigen::Vector3d axis_origin = Eigen::Vector3d::Zero();      // heart centre c [mm]
  Eigen::Vector3d axis_direction = Eigen::Vector3d::UnitZ();  // long axis a (normalised)
  double contraction_mm = 0;       // radial displacement towards the axis at reference_radius_mm
  double reference_radius_mm = 0;  // 0: the mesh's largest distance from the axis
  double shortening_mm = 0;        // axial displacement towards the plane h = 0 at reference_length_mm
  double reference_length_mm = 0;  // 0: the mesh's largest |h|
  double twist_deg_per_cm = 0;     // torsion: rotation about a growing with h
  double rotation_deg = 0;         // rotation about the axis, uniform
  Eigen::Vector3d translation_mm = Eigen::Vector3d::Zero();
  // Optional point held still (the displacement there subtracted everywhere; phase surfaces: each phase
  // moved back by its nearest vertices' mean displacement): e.g. the guide catheter's tip engaged in the
  // ostium, so the simulation runs in the catheter's frame and the introducer stays put.
  bool has_fixed_point = false;
  Eigen::Vector3d fixed_point = Eigen::Vector3d::Zero();
  // Hold the anatomy's inlet still (a motion file's default, "fixed_point": "inlet"): set by whoever knows
  // the inlet (resolve_heart_motion), which then fills has_fixed_point and fixed_point. heart_wall_motion
  // refuses a motion that still asks for it.
  bool hold_inlet = false;
  // 4D CT instead of the parametric map: N >= 2 surface files (paths), the wall at phases j / N, with the
  // rest mesh's vertex count, order and triangles (heart_wall_motion). Only the timing keys go with them.
  std::vector<std::string> phase_surfaces;
};

struct WallMotion {
  WallMotionKind kind = WallMotionKind::rigid;
  double heart_rate_bpm = 0;
  double systole_fraction = 1.0 / 3.0;
  double phase_offset = 0;
  // rigid
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();   // [mm/s]
  Eigen::Vector3d amplitude = Eigen::Vector3d::Zero();  // [mm]
  // cardiac (see the header comment)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero(), axis = Eigen::Vector3d::UnitZ();
  double contraction = 0, shortening = 0, twist_rad_per_mm = 0, rotation_rad = 0;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  bool has_fixed_point = false;
  Eigen::Vector3d fixed_point = Eigen::Vector3d::Zero();  // D(fixed_point) is subtracted from every D
  double travel_per_activation = 0;  // max over vertices of the bound B_i: |x_i(s1) - x_i(s0)| <= |s1 - s0| B_i
  double radius_limit = 0, height_limit = 0;  // cylinder around the axis holding every vertex
  // phases: per frame, the displacement of every vertex from the rest mesh
  std::vector<Eigen::MatrixX3d> frames;
  std::vector<double> frame_reach;  // max |D| per frame
  std::vector<double> frame_step;   // max vertex travel from frame j to frame j + 1 (cyclic)
  // Rest mesh data for the lazily evaluated current geometry (finish_wall_motion).
  int vertices = 0;
  std::vector<int> vertex_face_begin;  // CSR: faces around each vertex, ascending, with the corner
  std::vector<int> vertex_face, vertex_corner;
  std::vector<std::array<int, 3>> face_vertices;  // rest.F row by row: a face's corners in one cache line
  double max_edge_mm = 0;              // longest rest edge
  long id = 0;                         // unique per constructed motion (keys the per-thread vertex cache)
};

// Cycle phase in [0, 1) at time t.
double cardiac_phase(const WallMotion& m, double t);

// The waveform above: activation s in [0, 1] at `phase` with the given systole fraction (0, 1).
double cardiac_activation(double phase, double systole_fraction);

// Motion constructors; each checks its inputs (std::invalid_argument) and fills the rest mesh data.
WallMotion rigid_wall_motion(const TriangleMesh& rest, const Eigen::Vector3d& velocity_mm_per_s,
                             const Eigen::Vector3d& amplitude_mm, double heart_rate_bpm, double phase_offset = 0);
WallMotion cardiac_wall_motion(const TriangleMesh& rest, const CardiacMotion& params);
// `surfaces`: N >= 2 vertex matrices, the same vertex count and order as `rest`, at phases j / N.
WallMotion phase_wall_motion(const TriangleMesh& rest, const std::vector<Eigen::MatrixX3d>& surfaces,
                             double heart_rate_bpm, double phase_offset = 0);

// A motion JSON file: {"heart_rate_bpm": 72, "systole_fraction": 0.33, "axis_origin": [x, y, z],
// "axis_direction": [..], "contraction_mm": 2, "shortening_mm": 1, "twist_deg_per_cm": 3,
// "rotation_deg": 4, "translation_mm": [..], "fixed_point": [..] | "inlet" | "none", ...} (the
// CardiacMotion fields; missing ones keep their defaults; "fixed_point" missing = "inlet": the anatomy's
// inlet held still, hold_inlet), or 4D CT: {"heart_rate_bpm": 72, "phase_offset": 0, "phase_surfaces":
// ["ed.obj", "p1.obj", ...]} (paths relative to the file; no parametric key beside them but "fixed_point").
// Throws std::runtime_error "<file>: <problem>" for an unreadable file, an unknown key or a bad value.
CardiacMotion load_cardiac_motion(const std::string& path);

// The wall motion a CardiacMotion describes on `rest`: phase_wall_motion of its phase surfaces (each loaded
// with load_mesh, millimetres as written; refused, naming the file, unless its triangles are the rest
// mesh's: same vertex count, order and faces), else cardiac_wall_motion. Throws std::runtime_error for a
// file, std::invalid_argument for bad timing or an inlet to hold that nobody gave (hold_inlet).
WallMotion heart_wall_motion(const TriangleMesh& rest, const CardiacMotion& params);

// Current position of rest vertex `vertex` at time t (computed as X + D, so exactly X when D = 0).
Eigen::Vector3d wall_vertex_position(const WallMotion& m, const TriangleMesh& rest, int vertex, double t);

// The per-time part of D (activation, the fixed point's or rigid displacement, the frame pair), so
// that many vertices at one time cost one evaluation of it: wall_vertex_position(m, rest, i, t) ==
// wall_vertex_position(m, rest, i, wall_time(m, t)), bit for bit.
struct WallTime {
  double t = 0, s = 0, a = 0;  // time, activation (cardiac), weight of frame j + 1 (phases)
  int j = 0;                   // phases: the frame before t
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();  // rigid: D(t); cardiac: D of the fixed point
};
WallTime wall_time(const WallMotion& m, double t);
Eigen::Vector3d wall_vertex_position(const WallMotion& m, const TriangleMesh& rest, int vertex, const WallTime& at);

// The field at an arbitrary rest point X (rigid and cardiac; false for phases, which only know vertices).
bool wall_field_position(const WallMotion& m, const Eigen::Vector3d& X, double t, Eigen::Vector3d& x);
// The same at a prepared time (rigid and cardiac only): X + D(X, at).
Eigen::Vector3d wall_field_position(const WallMotion& m, const Eigen::Vector3d& X, const WallTime& at);

// A current point p at time t pulled back to the REST configuration, with what it takes to turn rest
// distances around it into current ones and back (the rest-frame candidate lists of
// engine/contact/detect_contacts.cpp). For a rest point Y and a current triangle point y whose rest point
// is Y (same barycentric weights): |x(Y) - y| <= K d^2 / 2 (d the longest rest edge), and
// |x(Y) - x(X)| >= sigma z - K z^2 / 2 with z = |Y - X| (Taylor at X: sigma bounds the smallest singular
// value of the Jacobian at X from below, K the second derivatives). With e = |x(X) - p| a current
// triangle point within r of p therefore has z <= z1 or z >= z2, the roots of K z^2 / 2 - sigma z + rho,
// rho = r + e + K d^2 / 2; and z <= |Y - x(Y)| + |x(Y) - p| + |p - X| <= max|D| + r + K d^2 / 2 + |p - X|
// rules out z >= z2 when z2 is beyond that (rest_reach).
struct RestPoint {
  Eigen::Vector3d X = Eigen::Vector3d::Zero();  // the pre-image of p (Newton), x(X, t) ~ p
  double sigma = 1;     // lower bound of the Jacobian's smallest singular value at X
  double curvature = 0; // K: bound of the map's second derivatives over the vertices' cylinder
  double slack = 0;     // e + K d^2 / 2
  double global = 0;    // max|D(t)| + K d^2 / 2 + |p - X|: no rest triangle point within r of p is farther than r + global
};
// Rigid and cardiac motions (false for phase surfaces: no field between the vertices). `guess`: a start
// for the Newton iteration (the point's pre-image at a nearby time), or null.
bool wall_rest_point(const WallMotion& m, const Eigen::Vector3d& p, const WallTime& at, const Eigen::Vector3d* guess,
                     RestPoint& out);
// Radius about rp.X holding the rest point of every current triangle point within r of p (z1 above, a
// little above for rounding); +infinity when the bound cannot say (z2 not beyond the global bound).
double rest_reach(const RestPoint& rp, double r);
// A lower bound of the current distance from p of every current triangle point whose rest point is at
// least z from rp.X (the inverse of rest_reach; 0 when it cannot say).
double current_reach(const RestPoint& rp, double z);

// Upper bounds over all vertices of |D_i(t)| and of |x_i(t1) - x_i(t0)| (a little above, for rounding).
double wall_max_displacement(const WallMotion& m, double t);
double wall_max_travel(const WallMotion& m, double t0, double t1);

// A ball of the REST configuration holding every rest triangle whose current (time t) triangle comes
// within r of p: through the field's inverse (rigid: exact; cardiac: p pulled back by fixed-point
// iteration, the radius r grown by the map's smallest stretch and curvature, see the .cpp), else centre
// p and radius r + max |D| (phase surfaces).
void rest_query_ball(const WallMotion& m, const Eigen::Vector3d& p, double r, double t, Eigen::Vector3d& centre,
                     double& radius);

}  // namespace gw
