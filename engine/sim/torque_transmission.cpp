#include "engine/sim/torque_transmission.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/scene/swept_tube_mesh.hpp"
#include "engine/scene/vessel_scene.hpp"
#include "engine/sim/step.hpp"

namespace gw {

namespace {

constexpr double kSpacing = 1.0;  // centreline sample spacing [mm]
constexpr double kTubeRadius = 1.5, kBendRadius = 10.0, kStraight = 15.0, kLead = 20.0, kInserted = 115.0;

// The centreline every kSpacing mm (each straight and arc split evenly, so samples are ~1 mm apart): lead straight along +x, then three 90-degree bends (about z, then about
// the new heading's side, then about z again) with straights between: points and the parallel-transport
// rotation from the start's frame.
void tube_path(std::vector<Eigen::Vector3d>& points, std::vector<Eigen::Quaterniond>& turns) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero(), t = Eigen::Vector3d::UnitX();
  Eigen::Quaterniond turn = Eigen::Quaterniond::Identity();
  points = {x};
  turns = {turn};
  const double ds = kSpacing;
  auto straight = [&](double length) {
    const int k = static_cast<int>(std::ceil(length / ds));
    for (int i = 0; i < k; ++i) {
      x += (length / k) * t;
      points.push_back(x);
      turns.push_back(turn);
    }
  };
  auto bend = [&](const Eigen::Vector3d& axis) {
    const Eigen::Vector3d centre = x + kBendRadius * axis.cross(t), arm = x - centre;
    const int k = static_cast<int>(std::ceil(kBendRadius * M_PI / 2 / ds));
    const Eigen::Quaterniond start = turn;
    const Eigen::Vector3d t0 = t;
    for (int i = 1; i <= k; ++i) {
      const Eigen::Quaterniond r(Eigen::AngleAxisd(0.5 * M_PI * i / k, axis));
      points.push_back(centre + r * arm);
      turn = (r * start).normalized();
      turns.push_back(turn);
      t = r * t0;
    }
    x = points.back();
  };
  straight(kLead);
  bend(Eigen::Vector3d::UnitZ());  // heading +x -> +y
  straight(kStraight);
  bend(Eigen::Vector3d::UnitX());  // +y -> +z (out of the first bend's plane)
  straight(kStraight);
  bend(Eigen::Vector3d::UnitY());  // +z -> +x
  straight(kInserted);             // more tube than wire
}

// Roll of frame q1 about its tangent relative to frame q0 carried to q1's tangent by the minimal
// rotation, in (-pi, pi].
double roll_between(const Eigen::Quaterniond& q0, const Eigen::Quaterniond& q1) {
  const Eigen::Vector3d t0 = q0 * Eigen::Vector3d::UnitX(), t1 = q1 * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d y0 = Eigen::Quaterniond::FromTwoVectors(t0, t1) * (q0 * Eigen::Vector3d::UnitY());
  const Eigen::Vector3d y1 = q1 * Eigen::Vector3d::UnitY();
  return std::atan2(y0.cross(y1).dot(t1), y0.dot(y1));
}

// The tube's mesh: radius kTubeRadius, 16 sides, swept along the centreline `points`.
TriangleMesh tube_mesh(const std::vector<Eigen::Vector3d>& points) {
  Eigen::MatrixX3d c(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i) c.row(i) = points[i].transpose();
  return swept_tube_mesh(c, kTubeRadius, 16);
}

// Lays the free nodes of `s` along the centreline (points, turns from tube_path): arc a from the inlet on
// point a / ds, frames by parallel transport.
void lay_along_path(const WireModel& model, const std::vector<Eigen::Vector3d>& points,
                    const std::vector<Eigen::Quaterniond>& turns, WireState& s) {
  const int k = first_free_node(model, s);
  std::vector<double> arc{0.0};
  for (std::size_t j = 1; j < points.size(); ++j) arc.push_back(arc.back() + (points[j] - points[j - 1]).norm());
  for (int i = k; i < model.nodes; ++i) {
    const double a = s.inserted_length_mm - model.arc_from_tip[i];
    const std::size_t j = std::min<std::size_t>(
        points.size() - 2, std::max<std::ptrdiff_t>(0, std::upper_bound(arc.begin(), arc.end(), a) - arc.begin() - 1));
    const double f = std::clamp((a - arc[j]) / (arc[j + 1] - arc[j]), 0.0, 1.0);
    s.x[i] = (1 - f) * points[j] + f * points[j + 1];
    s.q[i] = (turns[j].slerp(f, turns[j + 1]) * introducer_frame(s)).normalized();
  }
}

// Steps `s` still for 0.5 s to settle against the walls of `scene`; false (out.ok, out.problem set) when a
// step fails.
bool settle(const WireModel& model, const VesselScene& scene, WireState& s, TorqueTransmission& out) {
  const Control still{0, 0};
  for (int i = 0; i < 50; ++i) {  // 0.5 s to settle against the walls
    const StepReport rep = step(model, &scene, still, s);
    if (!rep.ok) {
      out.ok = false;
      out.problem = rep.problem;
      return false;
    }
  }
  return true;
}

// Adds one control step's report (sub-steps, contacts, sweeps, stage timings) to the sums in `out`.
inline void add_step_report(const WireModel& model, const StepReport& rep, TorqueTransmission& out) {
  out.substeps += model.substeps;
  out.split_substeps += rep.split_substeps;
  out.mean_contacts += rep.contacts;
  out.mean_max_pgs_sweeps += rep.contact_iterations;
  out.stages.detect_s += rep.timings.detect_s;
  out.stages.assemble_s += rep.timings.assemble_s;
  out.stages.solve_s += rep.timings.solve_s;
  out.stages.constraints_s += rep.timings.constraints_s;
}

// Turns the proximal end of `s` one full turn in turn_seconds, back, then holds it 0.5 s: the series
// (every sample_every steps), lags, tip rate and step sums into `out`. Returns the seconds spent in step().
double turn_and_back(const WireModel& model, const VesselScene& scene, double turn_seconds, int sample_every,
                     WireState& s, TorqueTransmission& out) {
  const Eigen::Quaterniond tip0 = s.q.back();
  double tip_roll = 0, last_roll = 0;
  const int per_turn = static_cast<int>(std::round(turn_seconds / model.dt));
  const double rate = 2.0 * M_PI / (per_turn * model.dt);
  auto clock = std::chrono::steady_clock::now();
  double stepping = 0;
  for (int i = 0; i <= 2 * per_turn + 50; ++i) {
    if (i % sample_every == 0) {
      out.time_s.push_back(i * model.dt);
      out.proximal_rad.push_back(s.proximal_rotation_rad);
      out.tip_rad.push_back(tip_roll);
    }
    if (i == 2 * per_turn + 50) break;
    const Control c{0.0, i < per_turn ? rate : (i < 2 * per_turn ? -rate : 0.0)};
    clock = std::chrono::steady_clock::now();
    const StepReport rep = step(model, &scene, c, s);
    stepping += std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
    add_step_report(model, rep, out);
    if (!rep.ok) {
      out.ok = false;
      out.problem = rep.problem;
      break;
    }
    // Unwrapped tip roll: accumulate the change since the last step (far below pi per 10 ms).
    const double roll = roll_between(tip0, s.q.back());
    double d = roll - last_roll;
    d -= 2.0 * M_PI * std::round(d / (2.0 * M_PI));
    tip_roll += d;
    last_roll = roll;
    out.max_tip_rate_rad_per_s = std::max(out.max_tip_rate_rad_per_s, std::abs(d) / model.dt);
    out.max_lag_rad = std::max(out.max_lag_rad, std::abs(s.proximal_rotation_rad - tip_roll));
    if (i + 1 == 2 * per_turn) out.final_lag_rad = std::abs(s.proximal_rotation_rad - tip_roll);
  }
  return stepping;
}

// The run's speed (from `stepping`, the seconds spent in step()) and its per-control-step means.
void finish_means(const WireModel& model, double stepping, TorqueTransmission& out) {
  out.substeps_per_s = stepping > 0 ? out.substeps / stepping : 0;
  const double control_steps = std::max(1.0, static_cast<double>(out.substeps) / model.substeps);
  out.mean_contacts /= control_steps;
  out.mean_max_pgs_sweeps /= control_steps;
}

}  // namespace

TorqueTransmission run_torque_transmission(const WireParams& params, double turn_seconds, int sample_every) {
  TorqueTransmission out;
  WireParams p = params;
  p.tip_curvature_per_mm = 0;
  const WireModel model = make_wire_model(p, 0.01);
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Quaterniond> turns;
  tube_path(points, turns);
  out.tube = tube_mesh(points);
  const VesselScene scene = make_vessel_scene(out.tube);
  // Lay the wire along the centreline, let it settle, then turn its proximal end there and back.
  WireState s = make_initial_state(model, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0, kInserted);
  lay_along_path(model, points, turns, s);
  if (!settle(model, scene, s, out)) return out;
  const double stepping = turn_and_back(model, scene, turn_seconds, sample_every, s, out);
  finish_means(model, stepping, out);
  return out;
}

}  // namespace gw
