#include "policy/load_actor.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace gw {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& src, const std::string& field, const std::string& what) {
  throw std::runtime_error(src + ": field '" + field + "': " + what);
}

const json& need(const json& j, const char* key, const std::string& src, const std::string& prefix) {
  if (!j.is_object() || !j.contains(key)) fail(src, prefix + key, "missing");
  return j.at(key);
}

float number(const json& v, const std::string& src, const std::string& field) {
  if (!v.is_number()) fail(src, field, "expected a number, got " + std::string(v.type_name()));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(src, field, "not finite");
  return static_cast<float>(d);
}

int count(const json& v, const std::string& src, const std::string& field) {
  if (!v.is_number_integer() || v.get<long long>() <= 0) fail(src, field, "expected a positive integer");
  return v.get<int>();
}

Eigen::VectorXf vec(const json& v, const std::string& src, const std::string& field, long expected) {
  if (!v.is_array()) fail(src, field, "expected an array");
  if (static_cast<long>(v.size()) != expected)
    fail(src, field, "has " + std::to_string(v.size()) + " values, expected " + std::to_string(expected));
  Eigen::VectorXf out(expected);
  for (long i = 0; i < expected; ++i)
    out[i] = number(v[static_cast<std::size_t>(i)], src, field + "[" + std::to_string(i) + "]");
  return out;
}

Activation activation(const json& v, const std::string& src, const std::string& field) {
  if (!v.is_string()) fail(src, field, "expected a string");
  const std::string s = v.get<std::string>();
  if (s == "relu") return Activation::Relu;
  if (s == "tanh") return Activation::Tanh;
  if (s == "identity") return Activation::Identity;
  fail(src, field, "unknown activation '" + s + "' (expected relu, tanh or identity)");
}

}  // namespace

ActorMLP parse_actor(const std::string& text, const std::string& src) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(src + ": invalid JSON: " + e.what());
  }
  if (!j.is_object()) throw std::runtime_error(src + ": expected a JSON object at top level");
  const json& fmt = need(j, "format", src, "");
  if (!fmt.is_string() || fmt.get<std::string>() != kActorFormat)
    fail(src, "format", "unsupported version " + fmt.dump() + " (expected \"" + kActorFormat + "\")");

  const int obs_size = count(need(j, "obs_size", src, ""), src, "obs_size");
  const int action_size = count(need(j, "action_size", src, ""), src, "action_size");
  std::string layout;
  if (j.contains("obs_layout")) {
    if (!j["obs_layout"].is_string()) fail(src, "obs_layout", "expected a string");
    layout = j["obs_layout"].get<std::string>();
  }
  std::string action_layout = "guidewire-nav/act/1";  // actors exported before action layouts: rotation only
  if (j.contains("action_layout")) {
    if (!j["action_layout"].is_string()) fail(src, "action_layout", "expected a string");
    action_layout = j["action_layout"].get<std::string>();
  }

  const json& jl = need(j, "layers", src, "");
  if (!jl.is_array() || jl.empty()) fail(src, "layers", "expected a non-empty array");
  std::vector<DenseLayer> layers;
  long prev = obs_size;
  for (std::size_t i = 0; i < jl.size(); ++i) {
    const std::string p = "layers[" + std::to_string(i) + "].";
    const json& L = jl[i];
    const json& shape = need(L, "shape", src, p);
    if (!shape.is_array() || shape.size() != 2)
      fail(src, p + "shape", "expected [out, in]");
    const int out = count(shape[0], src, p + "shape[0]");
    const int in = count(shape[1], src, p + "shape[1]");
    if (in != prev)
      fail(src, p + "shape", "input size " + std::to_string(in) + " does not match the previous output size " +
                                 std::to_string(prev) + (i == 0 ? " (obs_size)" : ""));
    DenseLayer d;
    const Eigen::VectorXf w = vec(need(L, "weight", src, p), src, p + "weight", static_cast<long>(out) * in);
    // Row-major on disk (torch's (out, in) layout) -> column-major Eigen matrix.
    d.weight = Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(w.data(), out, in);
    d.bias = vec(need(L, "bias", src, p), src, p + "bias", out);
    d.activation = activation(need(L, "activation", src, p), src, p + "activation");
    layers.push_back(std::move(d));
    prev = out;
  }
  if (prev != action_size)
    fail(src, "layers", "last layer outputs " + std::to_string(prev) + " values but action_size is " +
                            std::to_string(action_size));

  ObsNormalization norm;
  if (j.contains("obs_normalization") && !j["obs_normalization"].is_null()) {
    const json& n = j["obs_normalization"];
    const std::string p = "obs_normalization.";
    norm.enabled = true;
    norm.mean = vec(need(n, "mean", src, p), src, p + "mean", obs_size);
    norm.var = vec(need(n, "var", src, p), src, p + "var", obs_size);
    norm.clip = number(need(n, "clip", src, p), src, p + "clip");
    norm.epsilon = number(need(n, "epsilon", src, p), src, p + "epsilon");
    if ((norm.var.array() < 0).any()) fail(src, p + "var", "negative variance");
  }

  const json& out = need(j, "output", src, "");
  const std::string squash_s = need(out, "squash", src, "output.").is_string()
                                   ? out["squash"].get<std::string>() : std::string();
  bool squash;
  if (squash_s == "tanh") squash = true;
  else if (squash_s == "none") squash = false;
  else fail(src, "output.squash", "expected \"tanh\" or \"none\"");
  Eigen::VectorXf low = vec(need(out, "low", src, "output."), src, "output.low", action_size);
  Eigen::VectorXf high = vec(need(out, "high", src, "output."), src, "output.high", action_size);
  if ((high.array() < low.array()).any()) fail(src, "output.high", "below output.low");
  return ActorMLP(std::move(layers), std::move(norm), std::move(low), std::move(high), squash, layout,
                  std::move(action_layout));
}

ActorMLP load_actor(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot open actor file");
  std::stringstream ss;
  ss << f.rdbuf();
  if (ss.str().empty()) throw std::runtime_error(path + ": empty actor file");
  return parse_actor(ss.str(), path);
}

}  // namespace gw
