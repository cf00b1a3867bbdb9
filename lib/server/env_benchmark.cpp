#include "lib/server/env_benchmark.hpp"
#include "base/util/median.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <thread>
#include <vector>

#include "lib/server/tcp_server.hpp"
#include "task/episode.hpp"

namespace gw {

namespace {

using Clock = std::chrono::steady_clock;

double action_at(int k) { return std::sin(0.37 * k) * 0.8; }  // smooth, covers both directions

class LineClient {
 public:
  explicit LineClient(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<uint16_t>(port));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd_ < 0 || ::connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0)
      throw std::runtime_error("bench-env: cannot connect to the in-process server");
    const int one = 1;
    ::setsockopt(fd_, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  }
  ~LineClient() { ::close(fd_); }
  nlohmann::json request(const std::string& line) {
    const std::string out = line + "\n";
    for (size_t sent = 0; sent < out.size();) {
      const ssize_t n = ::send(fd_, out.data() + sent, out.size() - sent, MSG_NOSIGNAL);
      if (n <= 0) throw std::runtime_error("bench-env: send failed");
      sent += static_cast<size_t>(n);
    }
    size_t nl;
    while ((nl = buffer_.find('\n')) == std::string::npos) {
      char chunk[8192];
      const ssize_t n = ::recv(fd_, chunk, sizeof chunk, 0);
      if (n <= 0) throw std::runtime_error("bench-env: server closed the connection");
      buffer_.append(chunk, static_cast<size_t>(n));
    }
    nlohmann::json reply = nlohmann::json::parse(buffer_.substr(0, nl));
    buffer_.erase(0, nl + 1);
    if (reply.at("ok") != true) throw std::runtime_error("bench-env: server error: " + reply.value("error", ""));
    return reply;
  }

 private:
  int fd_ = -1;
  std::string buffer_;
};

}  // namespace

EnvBenchmark run_env_benchmark(const NavigationTask& task, int steps, std::uint64_t seed) {
  if (steps < 1) throw std::invalid_argument("bench-env: steps must be >= 1");
  EnvBenchmark b;
  b.steps = steps;
  // Both ways step by step, interleaved, so that load from other processes hits both alike: the
  // same episode runs in process (step_episode) and through the socket (TcpServer threads in this
  // process, loopback TCP, JSON both ways).
  ServerOptions options;
  TcpServer server(task, options);
  std::thread serving([&server] { server.serve(); });
  double inprocess_s = 0, socket_s = 0;
  std::vector<double> differences;  // per step: socket minus in process (same state, same action)
  differences.reserve(static_cast<size_t>(steps));
  try {
    LineClient client(server.port());
    std::uint64_t episode_seed = seed;
    EpisodeState state;
    bool done = true;
    for (int k = 0; k < steps; ++k) {
      if (done) {
        if (k > 0) ++episode_seed;
        ++b.episodes;
        auto t0 = Clock::now();
        state = reset_episode(task, -1, 0, episode_seed);
        inprocess_s += std::chrono::duration<double>(Clock::now() - t0).count();
        t0 = Clock::now();
        client.request(R"({"cmd":"reset","seed":)" + std::to_string(episode_seed) + "}");
        socket_s += std::chrono::duration<double>(Clock::now() - t0).count();
      }
      auto t0 = Clock::now();
      const StepOutcome out = step_episode(task, state, action_at(k));
      const double local = std::chrono::duration<double>(Clock::now() - t0).count();
      t0 = Clock::now();
      const nlohmann::json r = client.request(nlohmann::json{{"cmd", "step"}, {"action", {action_at(k)}}}.dump());
      const double remote = std::chrono::duration<double>(Clock::now() - t0).count();
      inprocess_s += local;
      socket_s += remote;
      differences.push_back(remote - local);
      if (r.at("reward").get<double>() != out.reward)
        throw std::runtime_error("bench-env: socket and in-process rewards differ at step " + std::to_string(k));
      done = out.terminated || out.truncated;
    }
  } catch (...) {
    server.stop();
    serving.join();
    throw;
  }
  server.stop();
  serving.join();

  b.inprocess_steps_per_s = steps / inprocess_s;
  b.socket_steps_per_s = steps / socket_s;
  b.overhead_percent = 100.0 * (socket_s - inprocess_s) / inprocess_s;
  b.overhead_us_per_step = 1e6 * (socket_s - inprocess_s) / steps;
  const double median_difference = median(differences);
  b.median_overhead_us_per_step = 1e6 * median_difference;
  b.median_overhead_percent = 100.0 * median_difference / (inprocess_s / steps);
  return b;
}

}  // namespace gw
