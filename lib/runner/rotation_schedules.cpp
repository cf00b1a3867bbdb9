#include "lib/runner/rotation_schedules.hpp"

#include <cmath>
#include <functional>
#include <stdexcept>

namespace gw {
namespace {

class ScheduleController final : public Controller {
 public:
  using Rule = std::function<double(const Observation&, int)>;
  ScheduleController(std::string name, Rule rule) : name_(std::move(name)), rule_(std::move(rule)) {}
  const std::string& name() const override { return name_; }
  Action act(const Observation& obs) override { return {rule_(obs, step_++), 1.0}; }
  void begin_episode() override { step_ = 0; }

 private:
  std::string name_;
  Rule rule_;
  int step_ = 0;  // actions asked for so far (the task asks only while the policy is in control)
};

ScheduleController::Rule rule_of(const std::string& name) {
  auto aim = [](double release, double turn) {
    return [=](const Observation& o, int) { return scripted_omega_action(o[obs_index::kOmega], release, turn); };
  };
  auto spin = [](double rate) { return [=](const Observation&, int) { return rate; }; };
  if (name == "aim-0.95") return aim(kScriptedOmegaRelease, 1.0);  // the scripted-omega controller's rule
  if (name == "aim-0.7") return aim(-0.7, 1.0);
  if (name == "aim-0.95-ccw") return aim(kScriptedOmegaRelease, -1.0);
  if (name == "spin-1") return spin(-1.0);
  if (name == "spin-0.3") return spin(-0.3);
  if (name == "spin+0.3") return spin(0.3);
  if (name == "spin+1") return spin(1.0);
  if (name == "wiggle") return [](const Observation&, int k) { return std::sin(0.3 * k); };
  throw std::invalid_argument("unknown rotation schedule '" + name + "' (known: " + rotation_schedule_list() + ")");
}

}  // namespace

const std::vector<std::string>& rotation_schedule_names() {
  static const std::vector<std::string> names = {"aim-0.95", "aim-0.7", "aim-0.95-ccw", "spin-1",
                                                 "spin-0.3", "spin+0.3", "spin+1",      "wiggle"};
  return names;
}

std::string rotation_schedule_list() {
  std::string list;
  for (const std::string& n : rotation_schedule_names()) list += (list.empty() ? "" : ", ") + n;
  return list;
}

std::unique_ptr<Controller> make_rotation_schedule(const std::string& name) {
  return std::make_unique<ScheduleController>(name, rule_of(name));
}

}  // namespace gw
