#include "lib/runner/controller_guides.hpp"

#include <memory>

#include "lib/runner/controller.hpp"

namespace gw {

std::vector<PlanGuide> controller_guides(const std::string& actor_path) {
  std::vector<PlanGuide> guides;
  for (const char* kind : {"policy", "scripted-omega", "scripted-omega-ccw"}) {
    std::shared_ptr<Controller> c = make_controller(kind, actor_path);
    guides.push_back({c->name(), [c](const Observation& obs) { return c->act(obs); }, [c] { c->begin_episode(); }});
  }
  return guides;
}

PlanGuide actor_guide(const std::string& actor_path) {
  std::shared_ptr<Controller> c = make_controller("policy", actor_path);
  return {recorded_path(actor_path), [c](const Observation& obs) { return c->act(obs); }, [c] { c->begin_episode(); }};
}

}  // namespace gw
