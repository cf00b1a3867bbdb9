#include "base/graph/declared_coordinate_space.hpp"

#include <fstream>

namespace gw {

std::string declared_coordinate_space(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  const size_t lps = head.find("SPACE=LPS"), ras = head.find("SPACE=RAS");
  if (lps == std::string::npos && ras == std::string::npos) return "";
  return lps < ras ? "LPS" : "RAS";  // npos is the largest value: the one that is present wins
}

}  // namespace gw
