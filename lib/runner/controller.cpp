#include "lib/runner/controller.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <filesystem>
#include <cstdlib>
#include <stdexcept>

#include "lib/runner/rotation_schedules.hpp"
#include "policy/load_actor.hpp"

namespace gw {
namespace {

class PolicyController final : public Controller {
 public:
  explicit PolicyController(const std::string& path) : actor_(load_actor(path)) {
    try {
      layout_ = ObservationLayout::parse(actor_.obs_layout());
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(path + ": the actor was trained on an unknown observation: " + e.what());
    }
    size_ = layout_.size();
    if (actor_.obs_size() != size_)
      throw std::runtime_error(path + ": the actor takes " + std::to_string(actor_.obs_size()) + " observations, its layout " +
                               actor_.obs_layout() + " has " + std::to_string(size_));
    try {
      action_layout_ = parse_action_layout(actor_.action_layout());
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(path + ": the actor was trained on an unknown action: " + e.what());
    }
    if (actor_.action_size() != action_layout_size(action_layout_))
      throw std::runtime_error(path + ": the actor outputs " + std::to_string(actor_.action_size()) + " actions, its layout " +
                               actor_.action_layout() + " has " + std::to_string(action_layout_size(action_layout_)));
    if (layout_.push_pull != (action_layout_ == ActionLayout::kRotationInsertion))
      throw std::runtime_error(path + ": the actor's layouts do not go together: " + actor_.obs_layout() + " with " +
                               actor_.action_layout() + " (obs/5 and obs/8 go with act/2, the others with act/1)");
    obs_.resize(size_);
    action_.resize(actor_.action_size());
  }
  const std::string& name() const override { return name_; }
  void adapt(TaskConfig& config) const override {
    config.observation.omega_plane = layout_.omega_plane;
    config.observation.omega_side = layout_.omega_side;
    // An obs/4 actor needs combined junctions and an obs/6 one k-way junctions; an obs/3 one runs with any
    // reading (the entries mean the same on two-way forks), as the user set it.
    if (layout_.junctions != JunctionModel::kSeparate) config.observation.junctions = layout_.junctions;
    config.observation.push_pull = layout_.push_pull;
    config.observation.tip_force = layout_.tip_force;
    config.action = action_layout_;
  }
  Action act(const Observation& obs) override {
    for (int i = 0; i < size_; ++i) obs_[i] = static_cast<float>(obs[static_cast<std::size_t>(i)]);
    actor_.act(obs_, action_);
    Action a{static_cast<double>(action_[0]), 1.0};
    if (action_.size() > 1) a.insertion = static_cast<double>(action_[1]);
    return a;
  }

 private:
  std::string name_ = "sac-policy";
  ActorMLP actor_;
  ObservationLayout layout_;  // the actor's, from its JSON
  ActionLayout action_layout_ = ActionLayout::kRotation;
  int size_ = 0;
  Eigen::VectorXf obs_, action_;
};

class PushOnlyController final : public Controller {
 public:
  const std::string& name() const override { return name_; }
  Action act(const Observation&) override { return {0.0, 1.0}; }

 private:
  std::string name_ = "push-only";
};

class ScriptedOmegaController final : public Controller {
 public:
  ScriptedOmegaController(double release, double turn)
      : name_(turn < 0 ? "scripted-omega-ccw" : "scripted-omega"), release_(release), turn_(turn) {}
  const std::string& name() const override { return name_; }
  Action act(const Observation& obs) override {
    // omega = +1: the tip bends straight at the wrong branch; -1: straight away from it. Turning
    // one way at a constant rate sweeps the bend direction round until omega drops below release.
    return {scripted_omega_action(obs[obs_index::kOmega], release_, turn_), 1.0};
  }

 private:
  std::string name_;
  double release_;
  double turn_;
};

}  // namespace

std::unique_ptr<Controller> make_policy_controller(const std::string& actor_path) {
  return std::make_unique<PolicyController>(actor_path);
}
std::unique_ptr<Controller> make_push_only_controller() { return std::make_unique<PushOnlyController>(); }
std::unique_ptr<Controller> make_scripted_omega_controller(double release, double turn) {
  if (!(turn == 1.0 || turn == -1.0)) throw std::invalid_argument("scripted omega: turn must be +1 or -1");
  return std::make_unique<ScriptedOmegaController>(release, turn);
}

std::unique_ptr<Controller> make_controller(const std::string& kind, const std::string& actor_path) {
  if (kind == "policy" || kind == "sac-policy") return make_policy_controller(actor_path);
  if (kind == "push-only") return make_push_only_controller();
  if (kind == "scripted-omega") return make_scripted_omega_controller();
  if (kind == "scripted-omega-ccw") return make_scripted_omega_controller(kScriptedOmegaRelease, -1.0);
  const auto& schedules = rotation_schedule_names();
  if (std::find(schedules.begin(), schedules.end(), kind) != schedules.end()) return make_rotation_schedule(kind);
  throw std::invalid_argument("unknown controller '" + kind +
                              "' (expected policy, push-only, scripted-omega, scripted-omega-ccw or a rotation "
                              "schedule: " + rotation_schedule_list() + ")");
}

std::string default_policy_path() {
  if (const char* env = std::getenv("GW_POLICY"); env && *env) return env;
  return shipped_path("policy/trained/sac_actor.json");
}

std::string shipped_path(const std::string& relative) { return std::string(GW_SOURCE_DIR) + "/" + relative; }

std::string recorded_path(const std::string& path) {
  const std::filesystem::path p(path), source(GW_SOURCE_DIR);
  if (!p.is_absolute()) return path;
  const std::filesystem::path relative = p.lexically_normal().lexically_relative(source.lexically_normal());
  if (relative.empty() || *relative.begin() == "..") return path;
  return relative.generic_string();
}

std::string base_policy_path(const std::string& policy_path) {
  return std::filesystem::path(policy_path).replace_filename("sac_actor_base.json").string();
}

}  // namespace gw
