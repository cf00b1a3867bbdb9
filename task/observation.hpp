#pragma once
// The observation of paper 2.2.3, Omega = {theta_t, theta_{t-n dt}, lambda_t, lambda_{t-n dt}, a_t, omega, s},
// as a fixed-size vector. Layout "guidewire-nav/obs/1" (the paper's omega) is the first 11 entries;
// "guidewire-nav/obs/3" is the first 12, omega in the approach plane and its sine; "guidewire-nav/obs/4" and
// "/obs/6" are obs/3 with junctions combined or read as k-way (docs/junctions.md); "/obs/5" the first 14, "/obs/8" all 15. The layout is TaskConfig::observation (observation_layout.hpp):
//   [0..2]  theta_t      t_i . c_i, i = 1..3: unit wire tangent at 0, 2, 4 mm from the tip (t_i) against
//                        the unit centerline tangent h = 4 mm ahead of that point's projection (c_i)
//   [3..5]  theta_{t-n dt}  the same one env step earlier (n dt = frame_skip * dt)
//   [6]     lambda_t / lambda_0      tip-to-goal distance along the centerline, over its value when the
//                                    goal became current (1 at reset), clipped to [0, max_lambda_ratio]
//   [7]     lambda_{t-n dt} / lambda_0
//   [8]     a_t          the rotation action applied during the last env step, in [-1, 1] (0 when the
//                        policy was not in control)
//   [9]     omega = k_p . w_p in [-1, 1]: tip curvature vector and wrong-branch direction, both projected on
//                        the plane normal to the correct branch (obs/1); in obs/3 the curvature and the
//                        direction from the correct to the wrong branch (w - c), projected on the plane normal
//                        to the approach direction p (course.hpp). w_p is unit, k_p is divided by
//                        max(|k_p|, kappa_rest/2) so omega is the cosine of the angle between them while the
//                        tip is curved and fades to 0 when the wall straightens it. With several wrong
//                        children, the largest (most dangerous) value; obs/4: against their mean direction.
//   [10]    s = v . c / push speed: tip velocity over the last env step along the centerline tangent at the
//                        tip, 1 = advancing at the push speed; clipped to +-max_abs_speed_ratio
//   [11]    omega_side = (n x w_p) . k_p, scaled like omega (obs/3 only): the sine to omega's cosine, i.e.
//                        on which side of w_p the tip bends, measured about omega's plane normal n. Why: omega
//                        alone is even in the roll angle, so an actor cannot tell whether its rotation carries
//                        the bend towards -1 or past it; the obs/2 actor shipped until 2026-11-30 rotates one
//                        way until omega is low, and when it starts a control zone already aimed (coronary T4,
//                        2nd bifurcation) a small residual rotation carries it past -1 and on round. With the
//                        sign the aim is a stable set point: rotate towards the side that lowers omega. The
//                        shipped actor is obs/3 (policy/trained/README.md).
//   [12]    insertion    the insertion action applied during the last env step, in [-1, 1] (obs/5 only; 1 when
//                        the task pushed: outside the control zone, or an act/1 task)
//   [13]    wrong_branch 1 while the tip is in a wrong child (the task's wrong-branch test,
//                        wrong_branch_entered.hpp), else 0 (obs/5 only). Why: an actor that may pull back must
//                        know it went the wrong way, as a clinician sees it on the fluoroscope; the paper's
//                        entries barely change once the tip is in a wrong child
//   [14]    tip_force    the largest wall force on the wire's distal 1 mm during the last env step, over 1.5 N (the
//                        rupture threshold the force figures use), clipped to [0, kTipForceCap] (obs/8 only; 0 at
//                        reset). Why: a clinician feels the wire push back and stops; the other entries show a jam
//                        only as a stalled speed, after the force has built up (issue 64: pushed into jams at 10-100 N)
// Why 3 products t_i . c_i and not the figure's 3x3 t_i . c_j: the text defines theta_i = t_i . c_i
// explicitly and calls theta an N-vector; the 6 off-diagonal products add mostly c_i . c_j-like terms,
// i.e. the local curvature of the centerline itself, which is the anatomy-specific information the
// shape-invariant observation is meant to leave out; and 11 inputs keep the actor small and fast.
#include <Eigen/Core>
#include <array>
#include <string>

#include "task/task_config.hpp"
#include "task/wall_force.hpp"  // kRuptureForceN

namespace gw {

// The entries an actor takes (its layout's size(), the first 11 or 12) and their names: ObservationLayout
// (observation_layout.hpp, included through task_config.hpp).
using Observation = std::array<double, kObservationSize>;

namespace obs_index {
inline constexpr int kTheta = 0, kThetaPrev = 3, kLambda = 6, kLambdaPrev = 7, kAction = 8, kOmega = 9, kSpeed = 10,
                     kOmegaSide = 11, kInsertion = 12, kWrongBranch = 13, kTipForce = 14;
}

inline constexpr double kTipForceScaleN = kRuptureForceN;  // tip_force = the tip's wall force / this (1.5 N)
inline constexpr double kTipForceCap = 4.0;     // ... clipped here (6 N)

// Names of the entries, e.g. "theta_t_1", "lambda_prev", "omega".
const std::array<const char*, kObservationSize>& observation_names();

// Box bounds of every entry (clipping limits from `config`).
void observation_bounds(const TaskConfig& config, Observation& low, Observation& high);

// omega for one wrong branch: `curvature` (1/mm, pointing where the tip bends), `plane_normal`
// (unit normal of omega's plane: CourseBifurcation::omega_normal), `wrong_in_plane` (unit w_p, or zero),
// `rest_curvature` (1/mm, the tip's). In [-1, 1].
double wrong_branch_alignment(const Eigen::Vector3d& curvature, const Eigen::Vector3d& plane_normal,
                              const Eigen::Vector3d& wrong_in_plane, double rest_curvature);
// omega_side for the same arguments: (n x w_p) . k_p with omega's scaling, in [-1, 1]. With omega it is
// (cos, sin) of the angle from w_p to k_p about n while the tip is curved.
double wrong_branch_side(const Eigen::Vector3d& curvature, const Eigen::Vector3d& plane_normal,
                         const Eigen::Vector3d& wrong_in_plane, double rest_curvature);

// Mean curvature vector between two unit tangents of the wire, `tip_tangent` distal and `back_tangent`
// `arc_between` mm proximal: dt/ds, pointing towards the side the tip bends to (a shape sensor gives this).
Eigen::Vector3d curvature_from_tangents(const Eigen::Vector3d& tip_tangent, const Eigen::Vector3d& back_tangent,
                                        double arc_between);

}  // namespace gw
