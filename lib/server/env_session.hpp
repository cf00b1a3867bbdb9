#pragma once
// One environment behind one connection: turns a request line of the JSON-lines protocol into a
// reply line (docs/architecture.md, "The socket protocol"). No sockets here, so tests can drive it directly.
//   {"cmd":"spec"}                                   -> spaces, protocol and layout versions, anatomies
//   {"cmd":"reset","seed":S,"options":{"anatomy":name|index,"target":id}}  -> obs, info
//   {"cmd":"step","action":[a]}                      -> obs, reward, terminated, truncated, info
//                                                       (act/2 tasks: [rotation, insertion])
//   {"cmd":"close"}                                  -> {"ok":true}, then the connection closes
// Every reply carries "ok"; failures carry "error" and leave the session usable.
#include <cstdint>
#include <string>

#include "task/episode.hpp"

namespace gw {

inline constexpr const char* kProtocolVersion = "guidewire-nav/protocol/1";

struct SessionOptions {
  double step_time_limit_s = 10.0;  // a step running longer is cut off with an error (0 = no limit)
};

class EnvSession {
 public:
  // `task` must outlive the session; `session_seed` seeds resets that come without a seed.
  EnvSession(const NavigationTask& task, SessionOptions options, std::uint64_t session_seed = 0);

  // Handles one request line (without its newline); returns the reply (without newline).
  // Sets `close_connection` after a "close" request. Never throws.
  std::string handle(const std::string& line, bool& close_connection);

 private:
  const NavigationTask& task_;
  SessionOptions options_;
  std::uint64_t seed_stream_;
  EpisodeState state_;
  bool has_episode_ = false;
};

// The "spec" reply body (also used by tests and bench-env).
std::string spec_json(const NavigationTask& task);

}  // namespace gw
