#include "lib/runner/replay_controller.hpp"

#include <string>
#include <utility>

namespace gw {
namespace {

class ReplayController : public Controller {
 public:
  explicit ReplayController(std::vector<Action> actions) : actions_(std::move(actions)) {}
  const std::string& name() const override { return name_; }
  Action act(const Observation& /*obs*/) override {
    return next_ < actions_.size() ? actions_[next_++] : Action{0.0, 0.0};
  }
  void begin_episode() override { next_ = 0; }

 private:
  std::string name_ = "replay";
  std::vector<Action> actions_;
  std::size_t next_ = 0;
};

}  // namespace

std::unique_ptr<Controller> make_replay_controller(std::vector<Action> actions) {
  return std::make_unique<ReplayController>(std::move(actions));
}

}  // namespace gw
