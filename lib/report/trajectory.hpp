#pragma once
// One navigation episode as recorded by the navigate runner: the plain data every
// writer of gw_report takes (trajectory JSON, .vtp, biplane PNG). Millimetres, seconds.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace gw {

struct EpisodeTrace {
  std::string anatomy;     // e.g. "coronary"
  std::string controller;  // "sac-policy" | "push-only" | "scripted-omega" (free text)
  int target_id = 0;
  std::uint64_t seed = 0;
  std::string outcome;  // one of kTraceOutcomes: "success" | "wrong_branch" | "stuck" | "timeout" | "diverged"
  std::string detail;   // e.g. "bifurcation 2: entered branch 5", or the divergence problem

  // Per recorded frame; all four have the same length. Positions may be non-finite in
  // the last frames of a diverged episode: writers skip or null them, never crash.
  std::vector<double> time_s;
  std::vector<Eigen::Vector3d> tip;
  std::vector<double> action;
  std::vector<bool> agent_in_control;
  // The observation at each frame (what the controller is shown for the next action; names in
  // observation_names) and which goal was current (0-based; the last one is the target).
  // Optional: empty, or one entry per frame. They let a person see why a policy turned.
  std::vector<std::vector<double>> observation;
  std::vector<std::string> observation_names;
  std::vector<int> goal;

  // Inserted wire polyline (proximal to distal), every k-th frame (k chosen by the
  // caller) and the last frame. wire_shape_frame[i] is the frame index (into time_s) of
  // wire_shapes[i]; leave it empty when unknown (then the last shape is taken as the
  // final frame's). The last entry of wire_shapes is "the final wire shape".
  std::vector<std::vector<Eigen::Vector3d>> wire_shapes;
  std::vector<int> wire_shape_frame;

  // For a wrong-branch failure: omega (observation 9) when the tip's projection on the path reached
  // the centre of the bifurcation it was lost at, or at the failure if the tip left before that.
  // -1 = the tip bent straight away from the wrong branch: a tip that was aimed and still went wrong
  // points at the wire and the anatomy, not at the controller's aim. NaN for any other outcome.
  double omega_at_loss = std::numeric_limits<double>::quiet_NaN();

  // Wall force per frame, mN (task/wall_force.hpp, StepInfo): over the env step that led to the
  // frame, the largest single-node force, the largest and the mean total over the nodes, the largest
  // force on the distal 1 mm. Optional: empty, or one entry per frame (frame 0, the reset, is 0).
  std::vector<double> wall_force_peak_node_mN;
  std::vector<double> wall_force_peak_total_mN;
  std::vector<double> wall_force_mean_total_mN;
  std::vector<double> tip_force_mN;

  // Recovery (TaskConfig::recovery_attempts, docs/recovery.md). outcome/detail above are always the
  // paper's strict episode's, which ended at frame strict_end_frame (-1 = the last frame); with recovery
  // the frames go on to the end of the procedure, whose outcome is recovery_outcome.
  int strict_end_frame = -1;
  int recovery_attempts_allowed = 0;  // K; 0 = the strict task only (the fields below are unused)
  int recovery_attempts_used = 0;
  std::string recovery_outcome;       // one of kTraceOutcomes when recovery_attempts_allowed > 0
  std::string recovery_detail;
  std::vector<bool> retracting;       // optional, per frame: the env step that led to it pulled the wire back
  std::vector<double> insertion;      // optional, per frame: the insertion action (act/2 tasks), in [-1, 1]
  std::vector<double> push_held_s;    // optional, per frame: simulated time of the env step whose forward push the
                                      // force limit withheld (TaskConfig::force_limit_N; recorded only when it is on)

  // Tip reshape (TraceOptions::reshaped, docs/recovery.md). reshape_tip_per_mm > 0: the procedure could go on
  // with the tip reshaped to this curvature over reshape_tip_length_mm; `reshaped` then holds the second pass
  // (one trace, from the inlet, same seed) when the first did not reach the target, else nothing.
  // reshape_withdrawal_s: the simulated time to pull the wire out after the first pass (its inserted length at
  // the recovery pull speed).
  double reshape_tip_per_mm = 0.0;
  double reshape_tip_length_mm = 0.0;
  double reshape_withdrawal_s = 0.0;
  std::vector<EpisodeTrace> reshaped;
};

// The frame the strict episode ended at (strict_end_frame, or the last frame; 0 for an empty trace).
int strict_end(const EpisodeTrace& trace);

// How the procedure ended: with recovery (recovery_attempts_allowed > 0) recovery_outcome/recovery_detail, else
// the strict episode's outcome/detail.
const std::string& procedure_outcome(const EpisodeTrace& trace);
const std::string& procedure_detail(const EpisodeTrace& trace);

// The outcomes a trace may carry (what navigate's summary counts).
extern const std::vector<std::string> kTraceOutcomes;

// Throws std::invalid_argument "<what>: <problem>" when the trace is inconsistent:
// per-frame vectors of different lengths, an outcome (or a recovery outcome) not in kTraceOutcomes, a
// negative target id, wire_shape_frame neither empty nor one frame index (in range) per shape, a
// strict_end_frame out of range.
// `what` names the trace in the message (e.g. the output file).
void check_trace(const EpisodeTrace& trace, const std::string& what = "trace");

}  // namespace gw
