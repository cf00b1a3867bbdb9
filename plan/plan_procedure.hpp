#pragma once
// plan_procedure: for one target, a search over procedures built from push, pull and rotation (the act/2
// action space at the task's control period) for one that reaches the target with every step's tip force
// within a budget, using what a controller never has: the simulator itself (deterministic: a copied
// EpisodeState is a branch point) and the whole course to the target.
//
// The search (docs/planning.md): greedy best-first over maneuvers, each one action held for hold_steps env
// steps (insertion +1 or -1, or 0 with a full turn, and rotation -1, -0.5, 0, 0.5, 1). A node's cost is the
// tip's remaining way, (course length - progress along the course) + off_course_weight * its distance from
// the course (deep in a wrong branch it grows, so pulling back out pays), plus force_weight times the peak tip
// force so far. A child whose state falls in a visited cell (progress, distance from the course and inserted
// length in 1 mm, proximal roll in 30 degrees) is dropped: when a branch of the search stalls, its cells are
// used up and the search goes on from the next best node, e.g. one pulled back. First a strict search (no
// child that enters a wrong branch), then, if it finds nothing, a procedure search (wrong branches entered and
// pulled out of again). Among the first `successes` plans found the one with the lowest peak tip force wins.
// Guides (PlanOptions::guides: closed-loop controllers, e.g. the scripted rule) are run first by the strict search,
// each one episode from the start under the planning task and the force budget; a guide that reaches the target
// gives a plan like any other, so the plans reach at least what the guides reach from the same start.
//
// Inputs: a task made with planning_task_config (act/2; throws std::invalid_argument otherwise), the anatomy
// and target, the episode seed (the start orientation), options. Output: the plan, or what was tried and where
// the tip got nearest, and why none was found: the course narrows below the wire (then nothing is searched), the
// search ran out of ways forward, or of budget. Deterministic: the same inputs give the same plan.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "plan/narrowest_passage.hpp"
#include "task/episode.hpp"
#include "task/navigation_task.hpp"

namespace gw {

// A closed-loop controller the strict search runs first from the start: the action for the planning task's
// observation (obs/8; a controller of a shorter layout reads its first entries; a rotation-only
// controller pushes at +1).
struct PlanGuide {
  std::string name;
  std::function<Action(const Observation&)> act;
  std::function<void()> begin;  // called before its episode (may be empty)
};

struct PlanOptions {
  double force_limit_N = 1.5;      // budget: no env step's tip force (StepInfo::tip_force_mN) above this
  int hold_steps = 5;              // env steps one maneuver holds its action (0.2 s at 0.04 s a step)
  long max_env_steps = 20000;      // search budget over both searches, env steps simulated on every branch
  int successes = 3;               // plans to find before choosing the one with the lowest peak tip force
  double off_course_weight = 2.0;  // cost per mm of the tip's distance from the course
  double force_weight = 10.0;      // cost (mm) per N of peak tip force so far
  bool strict_only = false;        // skip the procedure search
  std::vector<PlanGuide> guides;   // run first by the strict search, in order (none: the search alone)
  // The search starts where this controller's episode stopped getting deeper, lead_in_back_steps before its deepest
  // step (plan/lead_in.hpp); the plan's first steps are the controller's. One that reaches the target within the
  // force budget is the plan itself (nothing searched; `guide` names it). None: from the reset.
  std::optional<PlanGuide> lead_in;
  int lead_in_back_steps = 25;     // 1 s at 0.04 s a step
};

// What a lead-in did (ProcedurePlan::lead_in): the plan's first `steps` env steps are its controller's.
struct LeadInReport {
  std::string controller;
  int steps = 0;         // the controller's steps in the plan (the search started after them)
  int deepest_step = 0;  // the step after which its tip was deepest along the course
  int ran = 0;           // the steps its own episode ran
  std::string outcome;   // how its own episode ended (LeadIn::outcome)
};

enum class PlanKind { kNone, kStrict, kProcedure };
const char* plan_kind_name(PlanKind kind);  // "none" | "strict" | "procedure"

// What one search did.
struct SearchStats {
  long env_steps = 0;               // simulated on every branch
  int maneuvers = 0;                // maneuvers simulated (each hold_steps env steps at most)
  int generated = 0;                // children kept (new cells within the budget)
  int over_force = 0;               // children dropped for a step above the force budget
  int ended = 0;                    // children whose episode ended without reaching (stall, wire out, diverged)
  int wrong_branch = 0;             // children dropped for entering a wrong branch (strict search)
  int found = 0;                    // plans found
  int guided = 0;                   // of those, guides' procedures (strict search)
  double nearest_target_mm = 0.0;   // the nearest any node's tip got to the target (straight distance)
  Eigen::Vector3d best_tip = Eigen::Vector3d::Zero();
  double seconds = 0.0;             // wall time
  bool exhausted = false;           // nothing was left open before the budget was spent or the plans were found
};

struct ProcedurePlan {
  PlanKind kind = PlanKind::kNone;
  std::vector<Action> actions;      // per env step, from the reset: what a controller is asked for in control
  std::vector<bool> in_control;     // per env step, whether the action was applied (replay asks only for those)
  int steps = 0;
  double time_s = 0.0;              // simulated procedure time
  int wrong_entries = 0;            // wrong branches entered (and pulled out of): 0 for a strict plan
  double peak_tip_force_N = 0.0;    // over the plan's steps
  double peak_node_force_N = 0.0;   // the largest single-node wall force over its steps (any node)
  Eigen::Vector3d tip_end = Eigen::Vector3d::Zero();  // where the tip ended (none found: the nearest node's)
  double tip_to_target_mm = 0.0;    // the tip's straight distance to the target at the end (none found: the nearest)
  SearchStats strict, procedure;    // procedure: left at zero when the strict search found a plan
  std::string guide;                // the guide whose procedure this is ("": the search's own)
  std::optional<LeadInReport> lead_in;  // set when the search started from a lead-in (PlanOptions::lead_in)
  // None found: why, in words. "unreachable: ..." where the course narrows below the wire (narrowest_passage; no
  // search is run), "search exhausted: ..." where every way forward was tried, "budget spent: ..." otherwise.
  std::string why;
  std::optional<NarrowPassage> narrow;  // set when the course narrows below the wire (the first kind of why)
};

ProcedurePlan plan_procedure(const NavigationTask& task, int anatomy, int target_id, std::uint64_t seed,
                             const PlanOptions& options = {});

}  // namespace gw
