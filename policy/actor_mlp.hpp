#pragma once
// SAC actor MLP in plain Eigen (RTNeural-like): a constant model (layers, normalisation,
// action bounds) plus preallocated work buffers so act() never allocates.
#include <Eigen/Dense>
#include <string>
#include <vector>

namespace gw {

enum class Activation { Identity, Relu, Tanh };

/// One dense layer: y = act(W x + b), W is (out x in).
struct DenseLayer {
  Eigen::MatrixXf weight;
  Eigen::VectorXf bias;
  Activation activation = Activation::Identity;
};

/// Optional observation normalisation, as SB3 VecNormalize: clip((obs-mean)/sqrt(var+eps), -clip, clip).
struct ObsNormalization {
  bool enabled = false;
  Eigen::VectorXf mean, var;
  float clip = 10.0f;
  float epsilon = 1e-8f;
};

/// The deterministic SAC actor: action = low + (tanh(mu(latent(obs))) + 1)/2 * (high - low).
class ActorMLP {
 public:
  ActorMLP() = default;
  /// Builds the actor from validated parts and allocates the work buffers once.
  ActorMLP(std::vector<DenseLayer> layers, ObsNormalization norm, Eigen::VectorXf action_low,
           Eigen::VectorXf action_high, bool squash, std::string obs_layout,
           std::string action_layout = "guidewire-nav/act/1");

  int obs_size() const { return obs_size_; }
  int action_size() const { return action_size_; }
  const std::string& obs_layout() const { return obs_layout_; }
  /// What the actions mean: "guidewire-nav/act/1" (rotation, the paper's) or ".../act/2" (rotation, insertion).
  const std::string& action_layout() const { return action_layout_; }

  /// obs (obs_size) -> action (action_size, written into `action`). No heap allocation.
  void act(const Eigen::Ref<const Eigen::VectorXf>& obs, Eigen::Ref<Eigen::VectorXf> action);
  /// Convenience overload that returns a new vector (allocates).
  Eigen::VectorXf act(const Eigen::VectorXf& obs);

 private:
  std::vector<DenseLayer> layers_;
  ObsNormalization norm_;
  Eigen::VectorXf low_, high_;
  bool squash_ = true;
  std::string obs_layout_;
  std::string action_layout_;
  int obs_size_ = 0, action_size_ = 0;
  std::vector<Eigen::VectorXf> buffers_;  // buffers_[0] = normalised obs, [i+1] = layer i output
};

}  // namespace gw
