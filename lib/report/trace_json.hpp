#pragma once
// EpisodeTrace <-> JSON, schema "guidewire-nav/trajectory/1" (millimetres, seconds):
// {
//   "schema": "guidewire-nav/trajectory/1", "units": {"length": "mm", "time": "s"},
//   "anatomy": "coronary", "controller": "sac-policy", "target_id": 3, "seed": 7,
//   "outcome": "success", "detail": "...", "num_frames": N,
//   "frames": {"time_s": [t...], "tip": [[x,y,z]...], "action": [a...], "agent_in_control": [true...]},
//   "wire_shapes": [{"frame": f or null, "time_s": t or null, "points": [[x,y,z]...]}, ...]
// }
// Columns rather than one object per frame: compact, and numpy.asarray() reads them
// directly. Non-finite numbers (a diverged episode) are written as null and read back as NaN.
#include <string>

#include "lib/report/trajectory.hpp"

namespace gw {

inline constexpr const char* kTrajectorySchema = "guidewire-nav/trajectory/1";

// The trace as JSON text (indent < 0: one line). Throws std::invalid_argument when
// check_trace() rejects it.
std::string trace_to_json(const EpisodeTrace& trace, int indent = -1);

// Parses JSON text; throws std::runtime_error "<origin>: <problem>" for malformed text,
// a wrong schema, missing fields or an inconsistent trace.
EpisodeTrace trace_from_json(const std::string& text, const std::string& origin = "<string>");

// Writes trace_to_json(trace, 1) to `path` atomically (temporary file + rename).
// Throws std::invalid_argument "<path>: <problem>" for an inconsistent trace and
// ReportError "<path>: <problem>" when the file cannot be written; nothing is left behind.
void write_trace_json(const EpisodeTrace& trace, const std::string& path);

// Reads a file written by write_trace_json; throws std::runtime_error "<path>: <problem>".
EpisodeTrace read_trace_json(const std::string& path);

}  // namespace gw
