#include "lib/server/tcp_server.hpp"

#include <arpa/inet.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace gw {

namespace {

// Writes all of `data`; false when the peer is gone. MSG_NOSIGNAL: a vanished client must not
// SIGPIPE the whole server.
bool send_all(int fd, const std::string& data) {
  size_t sent = 0;
  while (sent < data.size()) {
    const ssize_t n = ::send(fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    sent += static_cast<size_t>(n);
  }
  return true;
}

}  // namespace

TcpServer::TcpServer(const NavigationTask& task, ServerOptions options) : task_(task), options_(std::move(options)) {
  const std::string where = options_.host + ":" + std::to_string(options_.port);
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  addrinfo* res = nullptr;
  const std::string port_text = std::to_string(options_.port);
  if (const int rc = ::getaddrinfo(options_.host.c_str(), port_text.c_str(), &hints, &res); rc != 0)
    throw std::runtime_error("cannot resolve " + where + ": " + gai_strerror(rc));
  std::string last_error = "no address";
  for (addrinfo* ai = res; ai; ai = ai->ai_next) {
    const int fd = ::socket(ai->ai_family, ai->ai_socktype | SOCK_CLOEXEC, ai->ai_protocol);
    if (fd < 0) continue;
    const int one = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    if (::bind(fd, ai->ai_addr, ai->ai_addrlen) == 0 && ::listen(fd, 64) == 0) {
      listen_fd_ = fd;
      break;
    }
    last_error = std::strerror(errno);
    ::close(fd);
  }
  ::freeaddrinfo(res);
  if (listen_fd_ < 0) throw std::runtime_error("cannot listen on " + where + ": " + last_error);
  sockaddr_storage addr{};
  socklen_t len = sizeof addr;
  ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &len);
  port_ = addr.ss_family == AF_INET6 ? ntohs(reinterpret_cast<sockaddr_in6*>(&addr)->sin6_port)
                                     : ntohs(reinterpret_cast<sockaddr_in*>(&addr)->sin_port);
}

TcpServer::~TcpServer() {
  stop();
  if (listen_fd_ >= 0) ::close(listen_fd_);
}

void TcpServer::serve() {
  while (!stop_requested_) {
    pollfd p{listen_fd_, POLLIN, 0};
    const int r = ::poll(&p, 1, 100);
    reap_finished();
    if (r <= 0 || !(p.revents & POLLIN)) continue;
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) continue;  // e.g. the client gave up before we accepted
    const int one = 1;
    ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);  // small request/reply lines
    std::lock_guard<std::mutex> lock(mutex_);
    if (stop_requested_) {
      ::close(fd);
      break;
    }
    auto c = std::make_unique<Connection>();
    c->fd = fd;
    Connection* raw = c.get();
    ++active_;
    const std::uint64_t seed = options_.seed + accepted_++;
    c->thread = std::thread([this, raw, seed] { run_connection(raw, seed); });
    connections_.push_back(std::move(c));
  }
}

void TcpServer::run_connection(Connection* c, std::uint64_t seed) {
  EnvSession session(task_, options_.session, seed);
  std::string buffer;
  char chunk[16384];
  bool open = true;
  while (open) {
    const ssize_t n = ::recv(c->fd, chunk, sizeof chunk, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // client closed or vanished (a partial line is dropped)
    buffer.append(chunk, static_cast<size_t>(n));
    size_t start = 0;
    for (size_t nl; open && (nl = buffer.find('\n', start)) != std::string::npos; start = nl + 1) {
      size_t end = nl;
      if (end > start && buffer[end - 1] == '\r') --end;
      if (end - start > options_.max_line_bytes) {
        send_all(c->fd, "{\"ok\":false,\"error\":\"request line longer than " +
                            std::to_string(options_.max_line_bytes) + " bytes; closing the connection\"}\n");
        open = false;
        break;
      }
      if (end == start) continue;  // blank line: ignore
      bool close_connection = false;
      const std::string reply = session.handle(buffer.substr(start, end - start), close_connection);
      if (!send_all(c->fd, reply + "\n") || close_connection) open = false;
    }
    buffer.erase(0, start);
    if (open && buffer.size() > options_.max_line_bytes) {
      send_all(c->fd, "{\"ok\":false,\"error\":\"request line longer than " + std::to_string(options_.max_line_bytes) +
                          " bytes; closing the connection\"}\n");
      open = false;
    }
  }
  ::shutdown(c->fd, SHUT_RDWR);
  --active_;
  c->finished = true;
}

void TcpServer::reap_finished() {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = connections_.begin(); it != connections_.end();) {
    if ((*it)->finished) {
      (*it)->thread.join();
      ::close((*it)->fd);
      it = connections_.erase(it);
    } else {
      ++it;
    }
  }
}

void TcpServer::stop() {
  stop_requested_ = true;
  std::list<std::unique_ptr<Connection>> all;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto& c : connections_) ::shutdown(c->fd, SHUT_RDWR);  // wakes the blocked recv
    all.swap(connections_);
  }
  for (auto& c : all) {
    if (c->thread.joinable()) c->thread.join();
    ::close(c->fd);
  }
}

}  // namespace gw
