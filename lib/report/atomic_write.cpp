#include "lib/report/atomic_write.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace gw {

void write_file_atomic(const std::string& path, const std::string& bytes) {
  if (path.empty()) throw ReportError("<empty path>: no output file name given");
  const std::string tmp = path + ".tmp";
  // stdio rather than ofstream: errno tells the user *why* (no such directory, read-only...).
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw ReportError(path + ": cannot open for writing (" + std::strerror(errno) + ")");
  const std::size_t written = bytes.empty() ? 0 : std::fwrite(bytes.data(), 1, bytes.size(), f);
  const int write_errno = errno;
  const bool flushed = std::fflush(f) == 0;
  const int close_status = std::fclose(f);
  if (written != bytes.size() || !flushed || close_status != 0) {
    std::remove(tmp.c_str());
    throw ReportError(path + ": write failed after " + std::to_string(written) + " of " +
                      std::to_string(bytes.size()) + " bytes (" + std::strerror(write_errno) + ")");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int e = errno;
    std::remove(tmp.c_str());
    throw ReportError(path + ": cannot replace with the written file (" + std::strerror(e) + ")");
  }
}

}  // namespace gw
