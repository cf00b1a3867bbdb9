#include "base/util/read_json_file.hpp"

#include <fstream>
#include <stdexcept>

namespace gw {

nlohmann::json read_json_file(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the " + what);
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(path + ": the " + what + " is not valid JSON (" + e.what() + ")");
  }
}

}  // namespace gw
