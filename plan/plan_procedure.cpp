#include "plan/plan_procedure.hpp"

#include "base/util/fixed_digits.hpp"
#include "plan/lead_in.hpp"
#include "plan/narrowest_passage.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <utility>

namespace gw {
namespace {

struct Maneuver {
  double insertion, rotation;
};

// Push or pull with five rotation rates, or turn in place either way: 12 maneuvers, tried in this order.
const std::vector<Maneuver>& maneuvers() {
  static const std::vector<Maneuver> m = [] {
    std::vector<Maneuver> v;
    for (const double insertion : {1.0, -1.0})
      for (const double rotation : {0.0, 0.5, -0.5, 1.0, -1.0}) v.push_back({insertion, rotation});
    v.push_back({0.0, 1.0});
    v.push_back({0.0, -1.0});
    return v;
  }();
  return m;
}

struct Node {
  int parent = -1;
  std::vector<Action> applied;  // the env steps of the maneuver that led here
  std::vector<bool> in_control;
  EpisodeState state;           // released once none of its maneuvers is left open
  double cost = 0.0;
  double peak_tip_mN = 0.0, peak_node_mN = 0.0;
};

double remaining_mm(const EpisodeState& s) { return current_course(s).line.length - s.progress_mm; }
double tip_to_target_mm(const EpisodeState& s) { return (s.tip - current_course(s).target).norm(); }

// The visited-cell key: progress, distance from the course and inserted length in 1 mm, the proximal roll in 30 deg.
std::array<long, 4> cell_of(const EpisodeState& s) {
  const double roll = std::remainder(s.wire.proximal_rotation_rad, 2.0 * M_PI) + M_PI;
  return {static_cast<long>(std::floor(s.progress_mm)), static_cast<long>(std::floor(s.course_distance_mm)),
          static_cast<long>(std::floor(s.wire.inserted_length_mm)), static_cast<long>(std::floor(roll / (M_PI / 6)))};
}

// Greedy best-first search with deferred evaluation: a node's maneuvers enter the open list at the node's cost
// (plus a small preference: pushing before turning in place before pulling) and are simulated only when taken
// from it, so a search that goes straight simulates one maneuver per step forward, not twelve.
class Search {
 public:
  Search(const NavigationTask& task, const PlanOptions& o, bool strict, long budget)
      : task_(task), o_(o), strict_(strict), budget_(budget) {}

  // Runs from `start` (its state; its steps from the reset, a lead-in's, are the plan's first) until `successes`
  // plans are found, the budget is spent or nothing is left open.
  // Output: the found plans' node ids (in the order found) and the stats.
  std::vector<int> run(Node start) {
    const auto t0 = std::chrono::steady_clock::now();
    start.cost = cost(start.state, start.peak_tip_mN);
    stats_.nearest_target_mm = tip_to_target_mm(start.state);
    stats_.best_tip = start.state.tip;
    visited_.insert(cell_of(start.state));
    add(std::move(start));
    if (strict_)
      for (const PlanGuide& g : o_.guides)
        if (static_cast<int>(found_.size()) < o_.successes && stats_.env_steps < budget_) try_guide(0, g);
    while (!open_.empty() && stats_.env_steps < budget_ && static_cast<int>(found_.size()) < o_.successes) {
      const Entry e = *open_.begin();
      ++stats_.maneuvers;
      open_.erase(open_.begin());
      try_maneuver(e.node, maneuvers()[static_cast<std::size_t>(e.maneuver)]);
      release(e.node);
    }
    stats_.found = static_cast<int>(found_.size());
    stats_.exhausted = open_.empty() && found_.empty() && !dropped_;
    stats_.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return found_;
  }

  const std::deque<Node>& nodes() const { return nodes_; }
  const SearchStats& stats() const { return stats_; }
  // The guide whose procedure node `id` ends ("": a node of the search).
  std::string guide_of(int id) const {
    const auto it = guide_of_.find(id);
    return it == guide_of_.end() ? std::string() : it->second;
  }

 private:
  struct Entry {
    double cost;
    long order;  // ties: the older entry first
    int node, maneuver;
    bool operator<(const Entry& o) const { return cost != o.cost ? cost < o.cost : order < o.order; }
  };
  static constexpr std::size_t kMaxOpen = 20000;  // open entries kept; the worst are dropped past it

  double cost(const EpisodeState& s, double peak_tip_mN) const {
    return remaining_mm(s) + o_.off_course_weight * s.course_distance_mm + o_.force_weight * peak_tip_mN / 1000.0;
  }

  // Adds a node and its maneuvers to the open list. The node keeps its state without the contact broad phase's
  // cache (WireState::wall_cache, rebuilt on the next step: the contact answers are exact, so the trajectory is the
  // same bit for bit, which every plan's replay checks), the bulk of a state on a wall the wire presses.
  void add(Node node) {
    node.state.wire.wall_cache.clear();
    node.state.wire.wall_cache.shrink_to_fit();
    node.state.wire.wall_cache_scene = nullptr;
    nodes_.push_back(std::move(node));
    const int id = static_cast<int>(nodes_.size()) - 1;
    pending_.push_back(0);
    for (std::size_t m = 0; m < maneuvers().size(); ++m) {
      const Maneuver& mv = maneuvers()[m];
      const double preference = mv.insertion > 0 ? 0.0 : mv.insertion == 0 ? 0.5 : 1.0;
      open_.insert({nodes_.back().cost + preference, order_++, id, static_cast<int>(m)});
      ++pending_.back();
    }
    while (open_.size() > kMaxOpen) {  // drop the worst entries
      const auto worst = std::prev(open_.end());
      const int n = worst->node;
      open_.erase(worst);
      dropped_ = true;
      release(n);
    }
  }

  // One maneuver of node `n` is done with: its state goes once none is left.
  void release(int n) {
    if (--pending_[static_cast<std::size_t>(n)] == 0) nodes_[static_cast<std::size_t>(n)].state = EpisodeState{};
  }

  // One env step of `child` with `action`, recorded in it (action, control, peak forces) and counted.
  StepOutcome step_child(Node& child, const Action& action) {
    child.in_control.push_back(child.state.in_control);
    child.applied.push_back(action);
    const StepOutcome out = step_episode(task_, child.state, action);
    ++stats_.env_steps;
    child.peak_tip_mN = std::max(child.peak_tip_mN, out.info.tip_force_mN);
    child.peak_node_mN = std::max(child.peak_node_mN, out.info.wall_force_peak_node_mN);
    return out;
  }

  // Simulates maneuver `m` from node `id`; keeps the child when it stays within the budget and the rules and
  // reaches a new cell (or the target).
  void try_maneuver(int id, const Maneuver& m) {
    const Node& parent = nodes_[static_cast<std::size_t>(id)];
    Node child;
    child.parent = id;
    child.state = parent.state;
    child.peak_tip_mN = parent.peak_tip_mN;
    child.peak_node_mN = parent.peak_node_mN;
    EpisodeState& s = child.state;
    const int entries_before = s.procedure.attempts_used;
    bool reached = false;
    for (int k = 0; k < o_.hold_steps && !reached; ++k) {
      const StepOutcome out = step_child(child, Action{m.rotation, m.insertion});
      if (out.info.tip_force_mN > 1000.0 * o_.force_limit_N) return void(++stats_.over_force);
      if (strict_ && (out.info.wrong_branch || s.procedure.attempts_used > entries_before))
        return void(++stats_.wrong_branch);
      reached = out.info.success;
      if (!reached && (out.terminated || out.truncated || !out.info.problem.empty())) return void(++stats_.ended);
    }
    if (!reached && !visited_.insert(cell_of(s)).second) return;
    child.cost = cost(s, child.peak_tip_mN);
    ++stats_.generated;
    if (tip_to_target_mm(s) < stats_.nearest_target_mm) {
      stats_.nearest_target_mm = tip_to_target_mm(s);
      stats_.best_tip = s.tip;
    }
    if (reached) {
      nodes_.push_back(std::move(child));
      pending_.push_back(1);  // its state stays: the plan's end
      found_.push_back(static_cast<int>(nodes_.size()) - 1);
      return;
    }
    add(std::move(child));
  }

  // Runs guide `g` from node `id` until its episode ends, the budget is spent, a step goes over the force budget or
  // it enters a wrong branch (the strict search's rules); one that reaches the target is a plan found.
  void try_guide(int id, const PlanGuide& g) {
    Node child;
    child.parent = id;
    child.state = nodes_[static_cast<std::size_t>(id)].state;
    child.peak_tip_mN = nodes_[static_cast<std::size_t>(id)].peak_tip_mN;
    child.peak_node_mN = nodes_[static_cast<std::size_t>(id)].peak_node_mN;
    EpisodeState& s = child.state;
    const int entries_before = s.procedure.attempts_used;
    if (g.begin) g.begin();
    while (stats_.env_steps < budget_) {
      const StepOutcome out = step_child(child, g.act(s.obs));
      if (out.info.tip_force_mN > 1000.0 * o_.force_limit_N) return void(++stats_.over_force);
      if (out.info.wrong_branch || s.procedure.attempts_used > entries_before) return void(++stats_.wrong_branch);
      if (tip_to_target_mm(s) < stats_.nearest_target_mm) {
        stats_.nearest_target_mm = tip_to_target_mm(s);
        stats_.best_tip = s.tip;
      }
      if (out.info.success) {
        nodes_.push_back(std::move(child));
        pending_.push_back(1);  // its state stays: the plan's end
        found_.push_back(static_cast<int>(nodes_.size()) - 1);
        guide_of_[found_.back()] = g.name;
        ++stats_.guided;
        return;
      }
      if (out.terminated || out.truncated || !out.info.problem.empty()) return void(++stats_.ended);
    }
  }

  const NavigationTask& task_;
  const PlanOptions& o_;
  const bool strict_;
  const long budget_;
  std::deque<Node> nodes_;
  std::vector<int> pending_;  // per node: its maneuvers still open (its state is kept while any is)
  std::set<Entry> open_;
  long order_ = 0;
  std::set<std::array<long, 4>> visited_;
  std::vector<int> found_;
  std::map<int, std::string> guide_of_;  // found guide procedures: node id -> guide name
  bool dropped_ = false;  // open entries were dropped past kMaxOpen: an empty open list is then no exhaustion
  SearchStats stats_;
};

// The plan of node `id`: its maneuvers from the root, its figures.
ProcedurePlan plan_of(const NavigationTask& task, const std::deque<Node>& nodes, int id, PlanKind kind) {
  ProcedurePlan plan;
  plan.kind = kind;
  std::vector<int> chain;
  for (int k = id; k >= 0; k = nodes[static_cast<std::size_t>(k)].parent) chain.push_back(k);  // the root's: a lead-in
  for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
    const Node& n = nodes[static_cast<std::size_t>(*it)];
    plan.actions.insert(plan.actions.end(), n.applied.begin(), n.applied.end());
    plan.in_control.insert(plan.in_control.end(), n.in_control.begin(), n.in_control.end());
  }
  const Node& end = nodes[static_cast<std::size_t>(id)];
  plan.steps = static_cast<int>(plan.actions.size());
  plan.time_s = plan.steps * task.config.frame_skip * task.config.dt_s;
  plan.peak_tip_force_N = end.peak_tip_mN / 1000.0;
  plan.peak_node_force_N = end.peak_node_mN / 1000.0;
  plan.wrong_entries = end.state.procedure.attempts_used;
  plan.tip_end = end.state.tip;
  plan.tip_to_target_mm = tip_to_target_mm(end.state);
  return plan;
}

// The found plan with the lowest peak tip force (the first found of equals).
int lowest_force(const std::deque<Node>& nodes, const std::vector<int>& found) {
  int best = found.front();
  for (const int id : found)
    if (nodes[static_cast<std::size_t>(id)].peak_tip_mN < nodes[static_cast<std::size_t>(best)].peak_tip_mN) best = id;
  return best;
}

// Why no plan was found, from what the searches did (`procedure` null: only the strict search ran).
std::string why_none(const SearchStats& strict, const SearchStats* procedure, long budget) {
  const SearchStats& last = procedure ? *procedure : strict;
  const long spent = strict.env_steps + (procedure ? procedure->env_steps : 0);
  const std::string tried = std::to_string(last.maneuvers) + " maneuvers: " + std::to_string(last.ended) +
                            " ended the episode (stall, wire out), " + std::to_string(last.over_force) +
                            " over the force budget, " + std::to_string(last.wrong_branch) + " into a wrong branch";
  if (last.exhausted)
    return "search exhausted: from every state it reached, every maneuver ended the episode, went over the force "
           "budget, entered a wrong branch (strict) or led only to visited cells (" + tried + ")";
  return "budget spent: " + std::to_string(spent) + " of " + std::to_string(budget) +
         " env steps, ways forward still open; not a proof that the target is out of reach (" + tried + ")";
}

// The plan "unreachable" because the course narrows below the wire somewhere, or none.
std::optional<ProcedurePlan> too_narrow(const NavigationTask& task, int anatomy, int target_id, const EpisodeState& root) {
  const double wire_radius = 0.5 * wire_of(task, anatomy).params.diameter_mm;
  const auto passage = narrowest_passage(task.anatomies[static_cast<std::size_t>(anatomy)].graph, target_id, wire_radius);
  if (!passage) return std::nullopt;
  ProcedurePlan plan;
  plan.narrow = passage;
  plan.tip_end = root.tip;
  plan.tip_to_target_mm = tip_to_target_mm(root);
  plan.why = "unreachable: the lumen narrows to " + fixed_digits(passage->radius_mm, 3) + " mm radius over " +
             fixed_digits(passage->length_mm, 1) + " mm from " + fixed_digits(passage->start_mm, 1) +
             " mm along the course, below the wire's radius " + fixed_digits(wire_radius, 3) +
             " mm; the walls are rigid, so no maneuver passes (nothing was searched)";
  return plan;
}

// The search's root: the reset, or where options.lead_in's controller stopped getting deeper (its steps to there
// carried by the root, so every plan starts with them); `report` says what the lead-in did.
Node root_node(const NavigationTask& task, int anatomy, int target_id, std::uint64_t seed, const PlanOptions& options,
               std::optional<LeadInReport>& report) {
  Node root;
  if (!options.lead_in) {
    root.state = reset_episode(task, anatomy, target_id, seed);
    return root;
  }
  LeadIn li = lead_in(task, anatomy, target_id, seed, *options.lead_in, options.lead_in_back_steps, options.force_limit_N);
  report = LeadInReport{options.lead_in->name, li.steps, li.deepest_step, li.ran, li.outcome};
  root.state = std::move(li.state);
  root.applied = std::move(li.actions);
  root.in_control = std::move(li.in_control);
  root.peak_tip_mN = li.peak_tip_mN;
  root.peak_node_mN = li.peak_node_mN;
  return root;
}

}  // namespace

const char* plan_kind_name(PlanKind kind) {
  switch (kind) {
    case PlanKind::kStrict: return "strict";
    case PlanKind::kProcedure: return "procedure";
    case PlanKind::kNone: return "none";
  }
  return "none";
}

ProcedurePlan plan_procedure(const NavigationTask& task, int anatomy, int target_id, std::uint64_t seed,
                             const PlanOptions& options) {
  if (task.config.action != ActionLayout::kRotationInsertion)
    throw std::invalid_argument("plan_procedure: the task must have the act/2 action space (planning_task_config)");
  if (!(options.force_limit_N > 0) || options.hold_steps < 1 || options.max_env_steps < 1 || options.successes < 1)
    throw std::invalid_argument("plan_procedure: force limit, hold steps, budget and successes must be positive");
  std::optional<LeadInReport> lead_in_report;
  const Node root = root_node(task, anatomy, target_id, seed, options, lead_in_report);
  const auto with_lead_in = [&](ProcedurePlan p) {
    p.lead_in = lead_in_report;
    return p;
  };
  if (lead_in_report && lead_in_report->steps == lead_in_report->ran) {  // it reached the target within the budget
    const std::deque<Node> only{root};
    ProcedurePlan plan = plan_of(task, only, 0, root.state.procedure.attempts_used == 0 ? PlanKind::kStrict
                                                                                         : PlanKind::kProcedure);
    plan.guide = lead_in_report->controller;  // its own episode, nothing searched
    return with_lead_in(plan);
  }
  if (auto narrow = too_narrow(task, anatomy, target_id, root.state)) return with_lead_in(*narrow);
  const long strict_budget = options.strict_only ? options.max_env_steps : options.max_env_steps / 2;
  Search strict(task, options, true, strict_budget);
  const std::vector<int> strict_found = strict.run(root);
  ProcedurePlan plan;
  if (!strict_found.empty()) {
    const int best = lowest_force(strict.nodes(), strict_found);
    plan = plan_of(task, strict.nodes(), best, PlanKind::kStrict);
    plan.guide = strict.guide_of(best);
    plan.strict = strict.stats();
    return with_lead_in(plan);
  }
  if (options.strict_only) {
    plan.strict = strict.stats();
    plan.why = why_none(strict.stats(), nullptr, options.max_env_steps);
    plan.tip_end = strict.stats().best_tip;
    plan.tip_to_target_mm = strict.stats().nearest_target_mm;
    return with_lead_in(plan);
  }
  Search procedure(task, options, false, options.max_env_steps - strict.stats().env_steps);
  const std::vector<int> found = procedure.run(root);
  if (!found.empty()) {
    const int id = lowest_force(procedure.nodes(), found);
    plan = plan_of(task, procedure.nodes(), id, PlanKind::kProcedure);
  } else {
    const bool procedure_nearer = procedure.stats().nearest_target_mm < strict.stats().nearest_target_mm;
    const SearchStats& nearer = procedure_nearer ? procedure.stats() : strict.stats();
    plan.tip_end = nearer.best_tip;
    plan.tip_to_target_mm = nearer.nearest_target_mm;
    plan.why = why_none(strict.stats(), &procedure.stats(), options.max_env_steps);
  }
  plan.strict = strict.stats();
  plan.procedure = procedure.stats();
  return with_lead_in(plan);
}

}  // namespace gw
