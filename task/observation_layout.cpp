#include "task/observation_layout.hpp"

#include <stdexcept>

namespace gw {

namespace {
// omega_side is measured about the approach direction only: the paper's plane (normal to the correct
// branch) is the one where omega is blind, and nothing was trained on that combination.
// obs/4 is obs/3 with junctions combined (ObservationLayout::junctions): the same entries, which mean the same on
// a two-way fork with no fork close behind it.
struct Layout {
  const char* name;
  OmegaPlane plane;
  bool omega_side;
  JunctionModel junctions;
  bool push_pull;
  bool tip_force;
};
// obs/6 is obs/3 with k-way junctions read together (close forks apart): the same entries again.
// obs/5 is obs/3 with the push/pull actor's two entries (act/2) after omega_side; obs/8 is obs/5 with the tip's
// wall force after them.
constexpr Layout kLayouts[] = {
    {"guidewire-nav/obs/1", OmegaPlane::kCorrectBranch, false, JunctionModel::kSeparate, false, false},
    {"guidewire-nav/obs/3", OmegaPlane::kApproach, true, JunctionModel::kSeparate, false, false},
    {"guidewire-nav/obs/4", OmegaPlane::kApproach, true, JunctionModel::kCombined, false, false},
    {"guidewire-nav/obs/5", OmegaPlane::kApproach, true, JunctionModel::kSeparate, true, false},
    {"guidewire-nav/obs/6", OmegaPlane::kApproach, true, JunctionModel::kKWay, false, false},
    {"guidewire-nav/obs/8", OmegaPlane::kApproach, true, JunctionModel::kSeparate, true, true}};
}  // namespace

const char* ObservationLayout::name() const {
  for (const Layout& l : kLayouts)
    if (l.plane == omega_plane && l.omega_side == omega_side && l.junctions == junctions && l.push_pull == push_pull &&
        l.tip_force == tip_force)
      return l.name;
  if (tip_force && !push_pull)
    throw std::invalid_argument("the tip-force entry comes after the push/pull entries (layout obs/8)");
  if (push_pull)
    throw std::invalid_argument("the push/pull entries need omega's plane 'approach', omega_side and separate junctions (layout obs/5)");
  if (omega_side && omega_plane != OmegaPlane::kApproach)
    throw std::invalid_argument("omega_side needs omega's plane 'approach' (no layout has it in the paper's plane)");
  if (!omega_side && omega_plane == OmegaPlane::kApproach && junctions == JunctionModel::kSeparate)
    throw std::invalid_argument("omega in the approach plane needs omega_side (layout obs/3); obs/2, without it, is "
                                "retired (docs/policy_history.md)");
  if (junctions == JunctionModel::kKWay)
    throw std::invalid_argument("k-way junctions need omega's plane 'approach' and omega_side (layout obs/6)");
  throw std::invalid_argument("combined junctions need omega's plane 'approach' and omega_side (layout obs/4)");
}

int ObservationLayout::size() const {
  if (tip_force) return kTipForceObservationSize;
  return push_pull ? kPushPullObservationSize : omega_side ? kSideObservationSize : kPaperObservationSize;
}

ObservationLayout ObservationLayout::parse(const std::string& name) {
  std::string known;
  for (const Layout& l : kLayouts) {
    if (name == l.name) return {l.plane, l.omega_side, l.junctions, l.push_pull, l.tip_force};
    known += std::string(known.empty() ? "" : ", ") + l.name;
  }
  throw std::invalid_argument("observation layout '" + name + "' is not one of " + known);
}

OmegaPlane parse_omega_plane(const std::string& text) {
  if (text == "correct_branch") return OmegaPlane::kCorrectBranch;
  if (text == "approach") return OmegaPlane::kApproach;
  throw std::invalid_argument("omega plane '" + text + "' is not one of correct_branch, approach");
}

const char* omega_plane_name(OmegaPlane plane) {
  return plane == OmegaPlane::kCorrectBranch ? "correct_branch" : "approach";
}

JunctionModel parse_junction_model(const std::string& text) {
  if (text == "separate") return JunctionModel::kSeparate;
  if (text == "combined") return JunctionModel::kCombined;
  if (text == "kway") return JunctionModel::kKWay;
  throw std::invalid_argument("junction model '" + text + "' is not one of separate, combined, kway");
}

const char* junction_model_name(JunctionModel model) {
  switch (model) {
    case JunctionModel::kSeparate: return "separate";
    case JunctionModel::kCombined: return "combined";
    case JunctionModel::kKWay: return "kway";
  }
  return "separate";
}

}  // namespace gw
