#include "engine/sim/step.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "engine/contact/detect_contacts.hpp"
#include "engine/contact/solve_contacts.hpp"
#include "engine/sim/assemble_system.hpp"
#include "engine/wire/node_rotational_inertia.hpp"
#include "engine/wire/so3.hpp"

namespace gw {

namespace {

// Per-thread scratch: sized on first use, reused by every later step (no allocation per step).
struct StepWorkspace {
  DynamicsSystem sys;
  BlockTridiagonalFactor factor;
  Eigen::VectorXd dv;
  std::vector<ContactPoint> contacts;
  std::vector<Eigen::Vector3d> v_contact;
  ContactWorkspace cws;
  ContactWorkspace reference;  // model.reference_contact_solve_every: the copy solved to convergence
};

double seconds_since(std::chrono::steady_clock::time_point& t) {
  const auto now = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(now - t).count();
  t = now;
  return s;
}

StepReport fail(WireState& state, StepReport rep, const std::string& problem) {
  rep.ok = false;
  rep.problem = problem;
  state.diverged = problem;
  return rep;
}

}  // namespace

namespace {

// A sub-step is split in two halves while its motion would carry some node further than this [mm]: the
// contacts are linearised at the start of the sub-step (tangent planes of the wall), which holds for
// travel that is small against the vessel's curvature (error ~ travel^2 / 2R: 0.003 mm at R = 1.75 mm).
// Pushing moves the wire 0.005 mm per 0.5 ms sub-step; a tip that snaps free after the wire has wound
// up torsion against the wall (a "whip") moved 1-3 mm in one sub-step and left the vessel.
constexpr double kMaxSubstepTravelMm = 0.05;
// At most this many halvings (model.h / 64 = 8 us at the default 0.5 ms).
constexpr int kMaxSubstepHalvings = 6;

// Stage: the linearised implicit Euler system of the free nodes (Eq. 1) assembled, factored and solved
// for the free-motion velocity change ws.dv.head(6 nf). False when the system is not positive definite.
bool free_motion(const WireModel& model, const WireState& state, double push, double rotate, double dt,
                 StepWorkspace& ws, StepReport& rep, std::chrono::steady_clock::time_point& clock) {
  const int n = model.nodes;
  assemble_system(model, state, push, rotate, dt, ws.sys);
  const int nf = n - ws.sys.first_free;
  rep.free_nodes = nf;
  rep.timings.assemble_s = seconds_since(clock);
  if (ws.dv.size() < 6 * n) ws.dv.resize(6 * n);
  auto dv = ws.dv.head(6 * nf);
  if (nf > 0) {
    if (!factor_block_tridiagonal(ws.sys.a, ws.factor)) return false;
    dv = ws.sys.rhs.head(6 * nf);
    solve_block_tridiagonal(ws.sys.a, ws.factor, dv);
  }
  rep.timings.solve_s = seconds_since(clock);
  return true;
}

// Diagnostic (model.reference_contact_solve_every): on every k-th sub-step, the contact problem as the capped
// solve starts it, kept for check_contact_solve; whether it was kept. Out of line, like check_contact_solve, so
// that the step's own code compiles as it does without them (an inlined copy changed the compiler's
// floating-point contractions elsewhere in the stage, and with them the trajectory's last bits).
[[gnu::noinline]] bool keep_contact_problem_if_due(const WireModel& model, const WireState& state, StepWorkspace& ws) {
  const int every = model.reference_contact_solve_every;
  if (every <= 0 || state.steps % every != 0) return false;
  ws.reference = ws.cws;
  return true;
}

// Diagnostic: ws.reference solved to convergence; how far the capped solve's forces (ws.cws) are from it
// goes into rep.contact_checks.
[[gnu::noinline]] void check_contact_solve(const WireModel& model, double dt, StepWorkspace& ws, StepReport& rep) {
  const ContactSolveResult ref = solve_contact_impulses(ws.contacts, dt, model.params.friction, kReferenceContactSweeps,
                                                        true, ws.reference);
  ContactForceError e = contact_force_error(ws.contacts, ws.cws.impulse, ws.reference.impulse, model.nodes);
  e.reference_converged = ref.residual < kContactSweepTolerance;
  rep.contact_checks.push_back(e);
}

// Each contact (ws.contacts, after the first solve: ws.cws.h_t_p) re-linearised at the middle of its constrained
// motion: the wall normal there makes g(x1) ~ g(x0) + n_mid . (x1 - x0) second-order accurate, so a wire pressed
// on a curved wall does not chatter sideways between the tangent planes at its start and end points. Returns the
// largest 1 - cos of a normal's turn (0: none turned; above 1e-5 the caller solves again).
double relinearise_at_mid_motion(const WireModel& model, const VesselScene& scene, WireState& state, double dt,
                                 StepWorkspace& ws) {
  const int k = ws.sys.first_free;
  double turned = 0;
  for (ContactPoint& c : ws.contacts) {
    if (c.side != 0) continue;  // a crease's second side keeps its normal (the query answers the nearest wall)
    Eigen::Vector3d v_end = c.v_free + c.wa * ws.cws.h_t_p.segment<3>(6 * (c.node_a - k));
    if (c.node_b >= 0) v_end += c.wb * ws.cws.h_t_p.segment<3>(6 * (c.node_b - k));
    const Eigen::Vector3d mid = contact_point_position(model, state.x, c.point) + 0.5 * dt * v_end;
    const double need = model.radius_mm + model.params.contact_margin_mm + dt * v_end.norm();
    // Exact to the cutoff: a wall a little beyond `need` at mid-motion still gives this contact its normal.
    // A moving wall is taken at mid-motion too, seen from its shape at the start of the step: the point
    // is carried back by the wall's mean velocity over the sub-step (half of its travel), which is the
    // same query for a translating wall and differs by second-order terms otherwise (the wall's
    // acceleration, h^2 a / 8, and its strain rate times h / 2: of order 1e-4 rad for the coronary field
    // at 100 bpm, against the 4e-3 rad that trigger a second solve). It saves evaluating the triangles,
    // normals and vertex normals at a third time per sub-step (t + h / 2, on top of t and t + h).
    const Eigen::Vector3d seen = scene.motion ? Eigen::Vector3d(mid - 0.5 * dt * c.v_wall) : mid;
    const WallDistance wd = cached_wall_distance(model, scene, state, c.point, seen, need, true, state.time);
    if (wd.triangle < 0 || !same_wall_side(c.n, wd.inward)) continue;
    turned = std::max(turned, 1.0 - wd.inward.dot(c.n));
    c.n = wd.inward;
    c.t1 = c.n.unitOrthogonal();
    c.t2 = c.n.cross(c.t1);
  }
  return turned;
}

// Stage: the contacts at the start of the step (ws.contacts), found by the swept test at the free-motion
// velocities (ws.v_contact). Returns a problem (the wire found outside the wall) or "".
std::string detect(const WireModel& model, const VesselScene& scene, WireState& state, double push, double dt,
                   StepWorkspace& ws, StepReport& rep, std::chrono::steady_clock::time_point& clock) {
  const int n = model.nodes, k = ws.sys.first_free, nf = n - k;
  const auto dv = ws.dv.head(6 * nf);
  ws.v_contact.resize(n);
  for (int i = 0; i < n; ++i)
    ws.v_contact[i] = i < k ? Eigen::Vector3d(push * state.direction)
                            : Eigen::Vector3d(state.v[i] + dv.segment<3>(6 * (i - k)));
  double outside = 0;
  detect_contacts(model, scene, state, ws.v_contact, dt, ws.contacts, outside);
  rep.contacts = static_cast<int>(ws.contacts.size());
  rep.timings.detect_s = seconds_since(clock);
  if (outside > model.params.divergence_margin_mm)
    return "the wire is " + std::to_string(outside) + " mm outside the vessel wall (t = " +
           std::to_string(state.time) + " s)";
  return "";
}

// Stage: the contacts found by detect, linearised at the start of the step (Eq. 2), with the free-motion
// velocities; their impulses (warm-started from the previous sub-step's), a second solve where a contact's
// normal at mid-motion turned, the velocity change added to ws.dv and the contact forces into the state.
void constrain_contacts(const WireModel& model, const VesselScene& scene, WireState& state, double dt,
                        StepWorkspace& ws, StepReport& rep, std::chrono::steady_clock::time_point& clock) {
  const int n = model.nodes, k = ws.sys.first_free, nf = n - k;
  auto dv = ws.dv.head(6 * nf);
  if (!ws.contacts.empty()) {
    const double mu = model.params.friction;
    const int iters = model.params.contact_iterations;
    ws.cws.lever = model.params.friction_torque ? model.radius_mm : 0.0;
    if (ws.cws.lever > 0)  // the surface point's slip needs the free angular velocity too
      for (ContactPoint& c : ws.contacts) {
        c.w_free = c.wa * (state.w[c.node_a] + dv.segment<3>(6 * (c.node_a - k) + 3));
        if (c.node_b >= 0) c.w_free += c.wb * (state.w[c.node_b] + dv.segment<3>(6 * (c.node_b - k) + 3));
      }
    prepare_contact_compliance(ws.sys.a, ws.factor, k, ws.contacts, ws.cws);
    // Warm start from the previous sub-step's normal impulses of the same points.
    const int m = static_cast<int>(ws.contacts.size());
    const int points = contact_point_count(model);
    if (static_cast<int>(state.contact_impulse.size()) != 2 * points) state.contact_impulse.assign(2 * points, 0.0);
    if (ws.cws.impulse.size() < 3 * m) ws.cws.impulse.conservativeResize(3 * m);
    for (int c = 0; c < m; ++c) ws.cws.impulse[3 * c] = state.contact_impulse[contact_slot(points, ws.contacts[c])];
    const bool check = keep_contact_problem_if_due(model, state, ws);
    ContactSolveResult cr = solve_contact_impulses(ws.contacts, dt, mu, iters, true, ws.cws);
    if (check) check_contact_solve(model, dt, ws, rep);
    contact_velocity_change(ws.sys.a, ws.factor, ws.contacts, ws.cws);
    const double turned = relinearise_at_mid_motion(model, scene, state, dt, ws);
    if (turned > 1e-5) {  // a normal turned by more than ~0.25 degrees: solve again with the new ones
      cr = solve_contact_impulses(ws.contacts, dt, mu, iters, true, ws.cws);
      contact_velocity_change(ws.sys.a, ws.factor, ws.contacts, ws.cws);
    }
    dv += ws.cws.h_t_p.head(6 * nf);
    std::fill(state.contact_impulse.begin(), state.contact_impulse.end(), 0.0);
    for (int c = 0; c < m; ++c) state.contact_impulse[contact_slot(points, ws.contacts[c])] = ws.cws.impulse[3 * c];
    rep.contact_iterations = cr.iterations;
    rep.contact_solves = 1;
    rep.capped_contact_solves = cr.residual >= kContactSweepTolerance ? 1 : 0;  // the last solve of the two
    for (std::size_t c = 0; c < ws.contacts.size(); ++c) {
      const ContactPoint& cp = ws.contacts[c];
      const Eigen::Vector3d f = (cp.n * ws.cws.impulse[3 * c] + cp.t1 * ws.cws.impulse[3 * c + 1] +
                                 cp.t2 * ws.cws.impulse[3 * c + 2]) /
                                dt;
      state.contact_force[cp.node_a] += cp.wa * f;
      if (cp.node_b >= 0) state.contact_force[cp.node_b] += cp.wb * f;
    }
  }
  rep.timings.constraints_s = seconds_since(clock);
}

// Stage: whether the step's motion would carry some free node further than kMaxSubstepTravelMm.
bool travels_too_far(const WireModel& model, const WireState& state, const StepWorkspace& ws, double dt) {
  const int n = model.nodes, k = ws.sys.first_free, nf = n - k;
  const auto dv = ws.dv.head(6 * nf);
  double travel = 0;
  for (int i = k; i < n; ++i) travel = std::max(travel, (state.v[i] + dv.segment<3>(6 * (i - k))).norm());
  return dt * travel > kMaxSubstepTravelMm;
}

// Stage: the free nodes integrated (semi-implicit: positions with the new velocities), the introducer
// driven, the clock advanced. Returns the kinetic energy.
double integrate(const WireModel& model, WireState& state, double push, double rotate, double dt,
                 const StepWorkspace& ws) {
  const int n = model.nodes, k = ws.sys.first_free, nf = n - k;
  const auto dv = ws.dv.head(6 * nf);
  double kinetic = 0;
  for (int i = k; i < n; ++i) {
    state.v[i] += dv.segment<3>(6 * (i - k));
    state.w[i] += dv.segment<3>(6 * (i - k) + 3);
    state.x[i] += dt * state.v[i];
    state.q[i] = (Eigen::Quaterniond(so3_exp(dt * state.w[i])) * state.q[i]).normalized();
    if (model.params.per_axis_rotational_inertia)
      kinetic += 0.5 * model.mass[i] * state.v[i].squaredNorm() +
                 0.5 * state.w[i].dot(node_rotational_inertia(model, i, state.q[i].toRotationMatrix()) * state.w[i]);
    else
      kinetic += 0.5 * model.mass[i] * state.v[i].squaredNorm() + 0.5 * model.rot_inertia[i] * state.w[i].squaredNorm();
  }
  state.inserted_length_mm = std::clamp(state.inserted_length_mm + dt * push, 0.0, model.params.length_mm);
  state.proximal_rotation_rad += dt * rotate;
  place_held_nodes(model, state, push, rotate);
  state.time += dt;
  ++state.steps;
  return kinetic;
}

// Stage: what diverged after the step, or "": NaN, an exploding speed or energy, or a constrained point
// beyond the wall. Exact wall distances after the step for every constrained point (rep's penetration);
// a point that was not constrained could only reach the wall by moving more than its swept margin,
// which the next step's detection reports (it measures every active point).
std::string divergence(const WireModel& model, const VesselScene* scene, WireState& state,
                       const StepWorkspace& ws, StepReport& rep) {
  const int n = model.nodes, k = ws.sys.first_free, nf = n - k;
  for (int i = k; i < n; ++i) {
    if (!state.x[i].allFinite() || !state.v[i].allFinite() || !state.w[i].allFinite() ||
        !state.q[i].coeffs().allFinite())
      return "NaN in the wire state at node " + std::to_string(i) + " (t = " + std::to_string(state.time) + " s)";
    if (state.v[i].norm() > model.params.max_speed_mm_per_s)
      return "exploding velocity: node " + std::to_string(i) + " moves at " + std::to_string(state.v[i].norm()) +
             " mm/s (t = " + std::to_string(state.time) + " s)";
  }
  if (!(rep.energy <= model.energy_limit))
    return "exploding energy: " + std::to_string(rep.energy) + " mN mm exceeds the limit " +
           std::to_string(model.energy_limit) + " (t = " + std::to_string(state.time) + " s)";
  if (scene && nf > 0) {
    double worst = 0;
    int worst_point = -1;
    for (const ContactPoint& c : ws.contacts) {
      const Eigen::Vector3d p = contact_point_position(model, state.x, c.point);
      const WallDistance wd = cached_wall_distance(model, *scene, state, c.point, p, model.radius_mm);
      rep.max_penetration_mm = std::max(rep.max_penetration_mm, model.radius_mm - wd.signed_distance);
      if (-wd.signed_distance > worst) {
        worst = -wd.signed_distance;
        worst_point = c.point;
      }
    }
    if (worst > model.params.divergence_margin_mm)
      return "wire point " + std::to_string(worst_point) + " is " + std::to_string(worst) +
             " mm outside the vessel wall (t = " + std::to_string(state.time) + " s)";
  }
  return "";
}

// One integration sub-step of length h, in the stages above. With `may_split`, returns before changing
// the wire's motion (with `split` = true) when a node would travel more than kMaxSubstepTravelMm, or when
// the sub-step is longer than the model's contact sub-step (adaptive stepping) and finds a contact.
StepReport substep(const WireModel& model, const VesselScene* scene, const Control& control, WireState& state,
                   double h, bool may_split, bool& split) {
  split = false;
  StepReport rep;
  const int n = model.nodes;
  if (static_cast<int>(state.x.size()) != n || static_cast<int>(state.q.size()) != n ||
      static_cast<int>(state.v.size()) != n || static_cast<int>(state.w.size()) != n ||
      static_cast<int>(state.external_force.size()) != n || static_cast<int>(state.external_torque.size()) != n ||
      static_cast<int>(state.contact_force.size()) != n)
    throw std::invalid_argument("step: the state does not belong to this model (node count differs)");
  if (!std::isfinite(control.push_mm_per_s) || !std::isfinite(control.rotate_rad_per_s))
    throw std::invalid_argument("step: control values must be finite");
  if (!state.diverged.empty())
    return fail(state, rep, "the state diverged earlier (" + state.diverged + "); reset it");

  thread_local StepWorkspace ws;
  const double dt = h, push = control.push_mm_per_s, rotate = control.rotate_rad_per_s;
  auto clock = std::chrono::steady_clock::now();
  if (!free_motion(model, state, push, rotate, dt, ws, rep, clock))
    return fail(state, rep, "the implicit system is not positive definite (degenerate wire geometry)");
  std::fill(state.contact_force.begin(), state.contact_force.end(), Eigen::Vector3d::Zero());
  const bool long_substep = dt > model.h * (1 + 1e-9);  // adaptive stepping: longer than the contact sub-step
  if (scene && rep.free_nodes > 0) {
    if (const std::string problem = detect(model, *scene, state, push, dt, ws, rep, clock); !problem.empty())
      return fail(state, rep, problem);
    if (may_split && !ws.contacts.empty() && long_substep) {  // contacts are solved at model.h
      split = true;
      return rep;
    }
    constrain_contacts(model, *scene, state, dt, ws, rep, clock);
  }
  if (may_split && scene && travels_too_far(model, state, ws, dt)) {  // free space has no contacts to linearise
    split = true;
    return rep;
  }
  state.last_substep_in_contact = rep.contacts > 0;
  rep.long_substeps = long_substep ? 1 : 0;
  const double kinetic = integrate(model, state, push, rotate, dt, ws);
  rep.energy = ws.sys.elastic_energy + kinetic;
  if (const std::string problem = divergence(model, scene, state, ws, rep); !problem.empty())
    return fail(state, rep, problem);
  return rep;
}

}  // namespace

namespace {

void accumulate(StepReport& total, const StepReport& rep) {
  total.ok = rep.ok;
  total.problem = rep.problem;
  total.contacts = rep.contacts;
  total.max_penetration_mm = std::max(total.max_penetration_mm, rep.max_penetration_mm);
  total.free_nodes = rep.free_nodes;
  total.contact_iterations = std::max(total.contact_iterations, rep.contact_iterations);
  total.contact_solves += rep.contact_solves;
  total.capped_contact_solves += rep.capped_contact_solves;
  total.contact_checks.insert(total.contact_checks.end(), rep.contact_checks.begin(), rep.contact_checks.end());
  total.energy = rep.energy;
  total.split_substeps += rep.split_substeps;
  total.long_substeps += rep.long_substeps;
  total.timings.detect_s += rep.timings.detect_s;
  total.timings.assemble_s += rep.timings.assemble_s;
  total.timings.solve_s += rep.timings.solve_s;
  total.timings.constraints_s += rep.timings.constraints_s;
}

// A sub-step of length h, done as two of h/2 (recursively) while its motion is too fast for one.
StepReport adaptive_substep(const WireModel& model, const VesselScene* scene, const Control& control,
                            WireState& state, double h, int halvings_left) {
  bool split = false;
  StepReport rep = substep(model, scene, control, state, h, halvings_left > 0, split);
  if (!split) return rep;
  StepReport total;
  total.split_substeps = 1;
  accumulate(total, rep);  // the timings of the attempt
  for (int half = 0; half < 2; ++half) {
    accumulate(total, adaptive_substep(model, scene, control, state, 0.5 * h, halvings_left - 1));
    if (!total.ok) break;
  }
  return total;
}

}  // namespace

StepReport step(const WireModel& model, const VesselScene* scene, const Control& control, WireState& state) {
  StepReport total;
  for (int i = 0; i < model.substeps;) {
    // Adaptive stepping: after a sub-step that met no wall, the longest power-of-two run of sub-steps
    // (up to model.free_span) that the step has left is taken as one; halved again where it meets the wall.
    int span = 1, halvings = kMaxSubstepHalvings;
    if (!state.last_substep_in_contact)
      while (2 * span <= model.free_span && i + 2 * span <= model.substeps) {
        span *= 2;
        ++halvings;
      }
    accumulate(total, adaptive_substep(model, scene, control, state, span * model.h, halvings));
    i += span;
    if (!total.ok) break;
  }
  return total;
}

}  // namespace gw
