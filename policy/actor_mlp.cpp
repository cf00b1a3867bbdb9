#include "policy/actor_mlp.hpp"

#include <stdexcept>
#include <utility>

namespace gw {

ActorMLP::ActorMLP(std::vector<DenseLayer> layers, ObsNormalization norm, Eigen::VectorXf action_low,
                   Eigen::VectorXf action_high, bool squash, std::string obs_layout, std::string action_layout)
    : layers_(std::move(layers)),
      norm_(std::move(norm)),
      low_(std::move(action_low)),
      high_(std::move(action_high)),
      squash_(squash),
      obs_layout_(std::move(obs_layout)),
      action_layout_(std::move(action_layout)) {
  if (layers_.empty()) throw std::invalid_argument("ActorMLP: no layers");
  obs_size_ = static_cast<int>(layers_.front().weight.cols());
  action_size_ = static_cast<int>(layers_.back().weight.rows());
  buffers_.emplace_back(Eigen::VectorXf::Zero(obs_size_));
  for (const DenseLayer& l : layers_) buffers_.emplace_back(Eigen::VectorXf::Zero(l.weight.rows()));
}

void ActorMLP::act(const Eigen::Ref<const Eigen::VectorXf>& obs, Eigen::Ref<Eigen::VectorXf> action) {
  if (obs.size() != obs_size_ || action.size() != action_size_)
    throw std::invalid_argument("ActorMLP::act: observation has " + std::to_string(obs.size()) +
                                " values, the actor expects " + std::to_string(obs_size_));
  Eigen::VectorXf& x0 = buffers_[0];
  if (norm_.enabled) {
    x0 = ((obs - norm_.mean).array() / (norm_.var.array() + norm_.epsilon).sqrt())
             .cwiseMax(-norm_.clip)
             .cwiseMin(norm_.clip)
             .matrix();
  } else {
    x0 = obs;
  }
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    const DenseLayer& l = layers_[i];
    Eigen::VectorXf& y = buffers_[i + 1];
    y.noalias() = l.weight * buffers_[i];
    y += l.bias;
    switch (l.activation) {
      case Activation::Relu: y = y.cwiseMax(0.0f); break;
      case Activation::Tanh: y = y.array().tanh().matrix(); break;
      case Activation::Identity: break;
    }
  }
  const Eigen::VectorXf& out = buffers_.back();
  if (squash_) {
    action = (low_.array() + (out.array().tanh() + 1.0f) * 0.5f * (high_ - low_).array()).matrix();
  } else {
    action = out;
  }
}

Eigen::VectorXf ActorMLP::act(const Eigen::VectorXf& obs) {
  Eigen::VectorXf a(action_size_);
  act(obs, a);
  return a;
}

}  // namespace gw
