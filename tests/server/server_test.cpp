// The guidewire server driven with raw sockets: every request kind, every bad message, concurrent
// connections, runaway steps. The task is a hand-made Y centerline in free space, so these tests
// exercise the protocol, not the anatomy data (tests/server/training_anatomy_test.cpp does that).
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <thread>

#include "lib/server/tcp_server.hpp"
#include "tests/server/socket_client.hpp"
#include "tests/task/hand_made_graphs.hpp"
#include "task/task_config_json.hpp"

using nlohmann::json;

namespace {

gw::NavigationTask y_task(const gw::TaskConfig& config = {}) {
  std::vector<gw::Anatomy> anatomies;
  anatomies.push_back(gw::make_anatomy("y", gwtest::y_graph(), nullptr));
  anatomies.push_back(gw::make_anatomy("tree", gwtest::two_level_tree(), nullptr));
  return gw::make_navigation_task(config, gw::default_wire_params(), std::move(anatomies));
}

// A server on a free port, serving from a background thread for the lifetime of the object.
struct RunningServer {
  gw::TcpServer server;
  std::thread thread;
  RunningServer(const gw::NavigationTask& task, gw::ServerOptions options = {})
      : server(task, options), thread([this] { server.serve(); }) {}
  ~RunningServer() {
    server.stop();
    thread.join();
  }
};

json ask(gwtest::RawClient& c, const std::string& line) {
  const std::string reply = c.request(line);
  REQUIRE_FALSE(c.eof());
  return json::parse(reply);
}

void require_error(const json& reply, const std::string& fragment) {
  REQUIRE(reply.at("ok") == false);
  CHECK_THAT(reply.at("error").get<std::string>(), Catch::Contains(fragment));
}

// The server still answers on a fresh connection and on `c`.
void still_serving(int port) {
  gwtest::RawClient other(port);
  CHECK(ask(other, R"({"cmd":"spec"})").at("ok") == true);
}

}  // namespace

TEST_CASE("server: spec describes spaces, protocol and layout", "[server]") {
  const gw::NavigationTask task = y_task();
  RunningServer s(task);
  REQUIRE(s.server.port() > 0);
  gwtest::RawClient c(s.server.port());
  const json spec = ask(c, R"({"cmd":"spec"})");
  CHECK(spec.at("ok") == true);
  CHECK(spec.at("protocol") == "guidewire-nav/protocol/1");
  CHECK(spec.at("obs_layout") == "guidewire-nav/obs/3");  // the default task: the shipped actor's
  CHECK(spec.at("task") == gw::task_config_to_json(task.config));  // the whole task, as --task reads it
  CHECK(spec.at("task").at("reward").at("omega_centre") == -0.5);
  CHECK(spec.at("observation_space").at("shape") == json::array({12}));
  CHECK(spec.at("observation_space").at("low").size() == 12);
  CHECK(spec.at("action_space").at("shape") == json::array({1}));
  CHECK(spec.at("action_space").at("low") == json::array({-1.0}));
  CHECK(spec.at("anatomies").size() == 2);
  CHECK(spec.at("anatomies")[1].at("targets") == 3);
}

TEST_CASE("server: with omega_side the layout is obs/3 and every observation has omega's sine", "[server]") {
  gw::TaskConfig config;
  REQUIRE(config.observation.omega_side);  // the default
  const gw::NavigationTask task = y_task(config);
  RunningServer s(task);
  gwtest::RawClient c(s.server.port());
  const json spec = ask(c, R"({"cmd":"spec"})");
  CHECK(spec.at("obs_layout") == "guidewire-nav/obs/3");
  CHECK(spec.at("task").at("observation").at("omega_side") == true);
  CHECK(spec.at("observation_space").at("shape") == json::array({12}));
  CHECK(spec.at("observation_space").at("names").back() == "omega_side");
  CHECK(spec.at("observation_space").at("high").size() == 12);
  CHECK(ask(c, R"({"cmd":"reset","seed":5,"options":{"anatomy":"y","target":1}})").at("obs").size() == 12);
  const json st = ask(c, R"({"cmd":"step","action":[0.5]})");
  REQUIRE(st.at("obs").size() == 12);
  const double omega = st.at("obs")[9].get<double>(), side = st.at("obs")[11].get<double>();
  CHECK(std::abs(side) <= 1.0);
  CHECK(omega * omega + side * side <= 1.0 + 1e-9);  // (cos, sin) of one angle, faded alike
}

TEST_CASE("server: reset and step replies, close ends the connection", "[server]") {
  const gw::NavigationTask task = y_task();
  RunningServer s(task);
  gwtest::RawClient c(s.server.port());
  const json r = ask(c, R"({"cmd":"reset","seed":5,"options":{"anatomy":"tree","target":2}})");
  REQUIRE(r.at("ok") == true);
  CHECK(r.at("obs").size() == 12);
  CHECK(r.at("info").at("anatomy") == "tree");
  CHECK(r.at("info").at("target") == 2);
  CHECK(r.at("info").at("seed") == 5);
  const json st = ask(c, R"({"cmd":"step","action":[0.25]})");
  REQUIRE(st.at("ok") == true);
  CHECK(st.at("obs").size() == 12);
  CHECK(st.at("reward").is_number());
  CHECK(st.at("terminated") == false);
  CHECK(st.at("truncated") == false);
  CHECK(st.at("info").at("step") == 1);
  // Anatomy by index, seedless reset, null options.
  CHECK(ask(c, R"({"cmd":"reset","options":{"anatomy":0}})").at("info").at("anatomy") == "y");
  CHECK(ask(c, R"({"cmd":"reset","seed":null,"options":null})").at("ok") == true);
  CHECK(ask(c, R"({"cmd":"close"})").at("ok") == true);
  CHECK(c.read_line() == "");
  CHECK(c.eof());
}

TEST_CASE("server: same seed and actions give the same replies bit for bit", "[server]") {
  const gw::NavigationTask task = y_task();
  RunningServer s(task);
  auto run = [&] {
    gwtest::RawClient c(s.server.port());
    std::vector<std::string> replies{c.request(R"({"cmd":"reset","seed":11})")};
    for (int k = 0; k < 30; ++k) replies.push_back(c.request(json{{"cmd", "step"}, {"action", {std::cos(k)}}}.dump()));
    return replies;
  };
  CHECK(run() == run());
}

TEST_CASE("server: bad requests get an error reply and the connection stays usable", "[server]") {
  const gw::NavigationTask task = y_task();
  RunningServer s(task);
  gwtest::RawClient c(s.server.port());
  require_error(ask(c, R"({"cmd":"spec")"), "malformed JSON");
  require_error(ask(c, "\xff\xfe garbage"), "malformed JSON");
  require_error(ask(c, R"([1,2,3])"), "JSON object");
  require_error(ask(c, R"({"command":"spec"})"), "cmd");
  require_error(ask(c, R"({"cmd":42})"), "cmd");
  require_error(ask(c, R"({"cmd":"fly"})"), "unknown cmd 'fly'");
  require_error(ask(c, R"({"cmd":"step","action":[0.1]})"), "send reset first");
  require_error(ask(c, R"({"cmd":"reset","seed":-3})"), "seed");
  require_error(ask(c, R"({"cmd":"reset","seed":"abc"})"), "seed");
  require_error(ask(c, R"({"cmd":"reset","options":{"anatomy":"nowhere"}})"), "unknown anatomy 'nowhere'");
  require_error(ask(c, R"({"cmd":"reset","options":{"anatomy":9}})"), "out of range");
  require_error(ask(c, R"({"cmd":"reset","options":{"target":9}})"), "valid targets are");
  require_error(ask(c, R"({"cmd":"reset","options":{"colour":"red"}})"), "unknown option 'colour'");
  require_error(ask(c, R"({"cmd":"reset","options":[1]})"), "options");
  REQUIRE(ask(c, R"({"cmd":"reset","seed":1})").at("ok") == true);
  require_error(ask(c, R"({"cmd":"step"})"), "action");
  require_error(ask(c, R"({"cmd":"step","action":0.5})"), "list");
  require_error(ask(c, R"({"cmd":"step","action":[]})"), "has 0 values, expected 1");
  require_error(ask(c, R"({"cmd":"step","action":[0.1,0.2]})"), "has 2 values, expected 1");
  require_error(ask(c, R"({"cmd":"step","action":["left"]})"), "not a number");
  require_error(ask(c, R"({"cmd":"step","action":[null]})"), "not a number");
  require_error(ask(c, R"({"cmd":"step","action":[NaN]})"), "malformed JSON");  // what Python's json emits
  require_error(ask(c, R"({"cmd":"step","action":[1e999]})"), "");               // overflow: not finite
  // None of that disturbed the episode.
  const json st = ask(c, R"({"cmd":"step","action":[0.0]})");
  CHECK(st.at("ok") == true);
  CHECK(st.at("info").at("step") == 1);
  still_serving(s.server.port());
}

TEST_CASE("server: an oversized line gets an error and a clean disconnect, others are served", "[server]") {
  const gw::NavigationTask task = y_task();
  gw::ServerOptions options;
  options.max_line_bytes = 4096;
  RunningServer s(task, options);
  gwtest::RawClient c(s.server.port());
  gwtest::RawClient bystander(s.server.port());
  REQUIRE(ask(bystander, R"({"cmd":"reset","seed":2})").at("ok") == true);
  SECTION("without a newline") {
    c.send(std::string(100000, 'x'));
  }
  SECTION("with a newline") {
    c.send(R"({"cmd":"spec","pad":")" + std::string(10000, ' ') + "\"}\n");
  }
  const json reply = json::parse(c.read_line());
  require_error(reply, "longer than 4096 bytes");
  CHECK(c.read_line() == "");
  CHECK(c.eof());
  CHECK(ask(bystander, R"({"cmd":"step","action":[0.3]})").at("ok") == true);
  still_serving(s.server.port());
}

TEST_CASE("server: clients vanishing mid-message do not disturb the others", "[server]") {
  const gw::NavigationTask task = y_task();
  RunningServer s(task);
  gwtest::RawClient bystander(s.server.port());
  REQUIRE(ask(bystander, R"({"cmd":"reset","seed":2})").at("ok") == true);
  for (int i = 0; i < 5; ++i) {
    gwtest::RawClient c(s.server.port());
    REQUIRE(ask(c, R"({"cmd":"reset","seed":3})").at("ok") == true);
    c.send(R"({"cmd":"step","act)");  // half a request, then gone
    c.close();
  }
  {
    gwtest::RawClient c(s.server.port());
    c.send(R"({"cmd":"step","action":[0.1]})" "\n");  // request sent, reply never read
  }
  CHECK(ask(bystander, R"({"cmd":"step","action":[0.3]})").at("ok") == true);
  // Their threads end: only the bystander remains.
  for (int k = 0; k < 100 && s.server.active_connections() > 1; ++k) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK(s.server.active_connections() == 1);
}

TEST_CASE("server: a runaway step is cut off with an error, the episode must be reset", "[server]") {
  const gw::NavigationTask task = y_task();
  gw::ServerOptions options;
  options.session.step_time_limit_s = 1e-9;  // every step "runs away"
  RunningServer s(task, options);
  gwtest::RawClient c(s.server.port());
  REQUIRE(ask(c, R"({"cmd":"reset","seed":2})").at("ok") == true);
  require_error(ask(c, R"({"cmd":"step","action":[0.3]})"), "time limit");
  require_error(ask(c, R"({"cmd":"step","action":[0.3]})"), "episode is over");
  CHECK(ask(c, R"({"cmd":"reset","seed":2})").at("ok") == true);
  still_serving(s.server.port());
}

TEST_CASE("server: many connections at once, one independent environment each", "[server]") {
  const gw::NavigationTask task = y_task();
  RunningServer s(task);
  // Reference: the same episodes in process.
  auto reference = [&](std::uint64_t seed) {
    gw::EpisodeState st = gw::reset_episode(task, 1, 3, seed);
    std::vector<double> rewards;
    for (int k = 0; k < 60 && !st.done; ++k) rewards.push_back(gw::step_episode(task, st, std::sin(0.1 * k)).reward);
    return rewards;
  };
  constexpr int kClients = 6;
  std::vector<std::vector<double>> got(kClients);
  std::vector<std::thread> threads;
  for (int i = 0; i < kClients; ++i) {
    threads.emplace_back([&, i] {
      gwtest::RawClient c(s.server.port());
      const std::string reset = R"({"cmd":"reset","seed":)" + std::to_string(100 + i) +
                                R"(,"options":{"anatomy":1,"target":3}})";
      if (json::parse(c.request(reset)).at("ok") != true) return;
      for (int k = 0; k < 60; ++k) {
        const json r = json::parse(c.request(json{{"cmd", "step"}, {"action", {std::sin(0.1 * k)}}}.dump()));
        if (r.at("ok") != true) return;
        got[static_cast<size_t>(i)].push_back(r.at("reward").get<double>());
        if (r.at("terminated") == true || r.at("truncated") == true) break;
      }
    });
  }
  for (auto& t : threads) t.join();
  for (int i = 0; i < kClients; ++i) {
    const std::vector<double> want = reference(static_cast<std::uint64_t>(100 + i));
    REQUIRE_FALSE(got[static_cast<size_t>(i)].empty());
    CHECK(got[static_cast<size_t>(i)] == want);  // bit for bit through JSON
  }
}

TEST_CASE("server: EnvSession never throws, even on internal errors", "[server]") {
  const gw::NavigationTask task = y_task();
  gw::EnvSession session(task, {});
  bool close = false;
  const json r = json::parse(session.handle(R"({"cmd":"reset","seed":18446744073709551615})", close));
  CHECK(r.at("ok") == true);  // the largest seed is fine
  CHECK_FALSE(close);
  CHECK(json::parse(session.handle("", close)).at("ok") == false);
  CHECK(json::parse(session.handle(R"({"cmd":"close"})", close)).at("ok") == true);
  CHECK(close);
}
