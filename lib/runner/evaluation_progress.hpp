#pragma once
// Progress of a long batch on stderr: episodes done of the total, time spent and an ETA
// (evaluate runs ~2,200 episodes in ~40 min; a line per row alone said nothing about the end).
#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>

namespace gw {

// "12s", "3m05s", "1h02m" (whole seconds, rounded down).
std::string format_duration(double seconds);

// "412/2200 episodes, 5m12s elapsed, ETA 22m40s": the remaining episodes at the mean rate so far;
// "ETA ?" before the first episode.
std::string progress_text(int done, int total, double elapsed_s);

class ProgressMeter {
 public:
  // `out` = nullptr: silent. `rewrite_line`: each episode rewrites one line in place (a terminal);
  // otherwise an episode line at most every `min_interval_s` (a log file stays short).
  ProgressMeter(int total_episodes, std::FILE* out, bool rewrite_line, double min_interval_s = 10.0);

  // Episodes that will not run after all (a row skipped when its anatomy is missing).
  void drop(int episodes);
  // One episode finished; `what` names where ("row 2/10 coronary-like, push-only: 37/50"). Thread-safe.
  void episode_done(const std::string& what);
  // A line of its own (a finished row), followed by the counts and the ETA.
  void line(const std::string& text);

  int done() const;
  int total() const;

 private:
  double elapsed_s() const;
  void print(const std::string& text, bool own_line);  // caller holds mutex_

  mutable std::mutex mutex_;
  int total_ = 0, done_ = 0;
  std::FILE* out_ = nullptr;
  bool rewrite_ = false;
  double min_interval_s_ = 10.0, last_print_s_ = -1e300;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace gw
