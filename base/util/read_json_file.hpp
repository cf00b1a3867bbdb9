#pragma once
// read_json_file: the JSON document of a file, every reader's one way in.
// Inputs: path; what = the file's role, named in errors ("wire parameter file", "motion file").
// Output: the parsed document. Throws std::runtime_error "PATH: cannot open the WHAT" when the file
// cannot be read, "PATH: the WHAT is not valid JSON (parser message)" when it does not parse.
#include <nlohmann/json.hpp>
#include <string>

namespace gw {

nlohmann::json read_json_file(const std::string& path, const std::string& what);

}  // namespace gw
