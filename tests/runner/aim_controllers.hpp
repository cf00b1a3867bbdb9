#pragma once
// Test controllers that aim the tip on purpose, shared by the runner tests: the scripted rule's rotation
// turned towards the wrong branch (omega -> +1) or away from it (omega -> -1), under the constant push.
#include <string>

#include "lib/runner/controller.hpp"
#include "task/observation.hpp"

namespace gwtest {

// The rotation rate that turns the tip's bend towards the wrong branch (at_wrong) or away from it.
inline double aim_rotation(const gw::Observation& obs, bool at_wrong) {
  return at_wrong ? (obs[gw::obs_index::kOmega] < 0.95 ? 1.0 : 0.0) : (obs[gw::obs_index::kOmega] > -0.95 ? 1.0 : 0.0);
}

// Turns the tip's bend towards the wrong branch and holds it there, pushing: t1's Y is lost with the tip
// aimed at the wrong branch.
class AimAtWrongBranch : public gw::Controller {
 public:
  const std::string& name() const override { return name_; }
  gw::Action act(const gw::Observation& obs) override { return {aim_rotation(obs, true), 1.0}; }

 private:
  std::string name_ = "aim-at-wrong";
};

}  // namespace gwtest
