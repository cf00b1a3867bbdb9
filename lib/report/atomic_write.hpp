#pragma once
// Write a whole file or nothing: every gw_report writer goes through here.
#include <stdexcept>
#include <string>

namespace gw {

// Every output problem the user must hear about: message is "<path>: <problem>".
class ReportError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `bytes` (text or binary) to `path` through a temporary file "<path>.tmp" in the
// same directory, renamed over `path` once complete, so a reader never sees half a file
// and a failure leaves neither `path` changed nor the temporary behind.
// Throws ReportError "<path>: <problem>" (missing directory, not writable, disk full,
// `path` is a directory). Does not create directories.
void write_file_atomic(const std::string& path, const std::string& bytes);

}  // namespace gw
