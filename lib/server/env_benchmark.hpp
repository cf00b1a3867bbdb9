#pragma once
// Env steps per second in process (step_episode) and through the socket (TcpServer on loopback,
// a JSON-lines client doing what the Python env does), on identical episodes and actions.
#include <cstdint>

#include "task/navigation_task.hpp"

namespace gw {

struct EnvBenchmark {
  int steps = 0;
  int episodes = 0;
  double inprocess_steps_per_s = 0;
  double socket_steps_per_s = 0;
  double overhead_percent = 0;       // extra time per step through the socket, relative to in process
  double overhead_us_per_step = 0;
  // Robust to load from other processes: the median over steps of (socket - in process) time of the
  // same step, in microseconds and relative to the mean in-process step.
  double median_overhead_us_per_step = 0;
  double median_overhead_percent = 0;
};

// Runs `steps` env steps each way, interleaved step by step: episodes seeded seed, seed+1, ...,
// actions from a fixed
// pseudo-random sequence, resetting when an episode ends. Throws std::runtime_error when the
// socket side fails or disagrees with the in-process rewards (they must match bit for bit).
EnvBenchmark run_env_benchmark(const NavigationTask& task, int steps, std::uint64_t seed);

}  // namespace gw
