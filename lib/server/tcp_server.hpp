#pragma once
// The guidewire server: newline-delimited JSON over TCP, one EnvSession per connection, one thread
// per connection, all sessions sharing one constant NavigationTask.
// A line longer than max_line_bytes gets an error reply and the connection is closed (the stream
// cannot be resynchronised); a client vanishing mid-line just ends its connection.
#include <atomic>
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "lib/server/env_session.hpp"

namespace gw {

struct ServerOptions {
  std::string host = "127.0.0.1";
  int port = 0;                         // 0 = let the OS pick a free port (see TcpServer::port)
  std::size_t max_line_bytes = 65536;   // requests are tiny; anything this long is an error
  SessionOptions session;
  std::uint64_t seed = 0;               // session k gets seed + k for seedless resets
};

class TcpServer {
 public:
  // Binds and listens; throws std::runtime_error naming the host:port on failure.
  TcpServer(const NavigationTask& task, ServerOptions options);
  ~TcpServer();
  TcpServer(const TcpServer&) = delete;
  TcpServer& operator=(const TcpServer&) = delete;

  int port() const { return port_; }

  // Accepts connections until stop() (blocking). Each connection runs in its own thread.
  void serve();

  // Makes serve() return and closes every connection; safe from any thread (not from a signal handler:
  // use request_stop there).
  void stop();
  // Async-signal-safe: serve() notices within ~100 ms and then stops.
  void request_stop() { stop_requested_ = true; }

  int active_connections() const { return active_.load(); }

 private:
  struct Connection {
    int fd = -1;
    std::thread thread;
    std::atomic<bool> finished{false};
  };
  void run_connection(Connection* c, std::uint64_t seed);
  void reap_finished();

  const NavigationTask& task_;
  ServerOptions options_;
  int listen_fd_ = -1;
  int port_ = 0;
  std::atomic<bool> stop_requested_{false};
  std::atomic<int> active_{0};
  std::mutex mutex_;
  std::list<std::unique_ptr<Connection>> connections_;
  std::uint64_t accepted_ = 0;
};

}  // namespace gw
