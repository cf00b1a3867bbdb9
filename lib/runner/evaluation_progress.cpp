#include "lib/runner/evaluation_progress.hpp"

#include <algorithm>
#include <cmath>

namespace gw {

std::string format_duration(double seconds) {
  const long s = std::max(0L, static_cast<long>(std::floor(seconds)));
  char buf[32];
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%lds", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%ldm%02lds", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%ldh%02ldm", s / 3600, (s % 3600) / 60);
  return buf;
}

std::string progress_text(int done, int total, double elapsed_s) {
  std::string text = std::to_string(done) + "/" + std::to_string(total) + " episodes, " + format_duration(elapsed_s) +
                     " elapsed, ETA ";
  if (done <= 0) return text + "?";
  return text + format_duration(elapsed_s / done * std::max(0, total - done));
}

ProgressMeter::ProgressMeter(int total_episodes, std::FILE* out, bool rewrite_line, double min_interval_s)
    : total_(total_episodes), out_(out), rewrite_(rewrite_line), min_interval_s_(min_interval_s),
      start_(std::chrono::steady_clock::now()) {}

double ProgressMeter::elapsed_s() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressMeter::drop(int episodes) {
  std::lock_guard<std::mutex> lock(mutex_);
  total_ = std::max(done_, total_ - episodes);
}

void ProgressMeter::episode_done(const std::string& what) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++done_;
  const double now = elapsed_s();
  if (!rewrite_ && now - last_print_s_ < min_interval_s_ && done_ != total_) return;
  last_print_s_ = now;
  print(what + " | " + progress_text(done_, total_, now), false);
}

void ProgressMeter::line(const std::string& text) {
  std::lock_guard<std::mutex> lock(mutex_);
  print(text + " | " + progress_text(done_, total_, elapsed_s()), true);
}

int ProgressMeter::done() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return done_;
}

int ProgressMeter::total() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return total_;
}

void ProgressMeter::print(const std::string& text, bool own_line) {
  if (!out_) return;
  if (rewrite_) {
    // \r and "erase to end of line": the episode line is rewritten in place; a row line stays.
    std::fprintf(out_, "\r\033[K[evaluate] %s", text.c_str());
    if (own_line) std::fputc('\n', out_);
  } else {
    std::fprintf(out_, "[evaluate] %s\n", text.c_str());
  }
  std::fflush(out_);
}

}  // namespace gw
