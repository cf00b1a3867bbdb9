#include "base/graph/read_slicer_markups.hpp"
#include "base/util/read_json_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "base/graph/polyline_tree.hpp"

namespace gw {
namespace {

using nlohmann::json;

struct Curve {
  std::string name;
  std::vector<Eigen::Vector3d> points;
  std::vector<double> radii;
};

// Control points of one markup, in RAS mm.
std::vector<std::pair<std::string, Eigen::Vector3d>> control_points(const json& m, const std::string& name) {
  const std::string system = m.value("coordinateSystem", std::string("LPS"));
  if (system != "LPS" && system != "RAS")
    throw std::runtime_error(name + ": coordinateSystem '" + system + "' (LPS or RAS)");
  const std::string units = m.value("coordinateUnits", std::string("mm"));
  if (units != "mm" && units != "um") throw std::runtime_error(name + ": coordinateUnits '" + units + "' (mm or um)");
  const double scale = units == "um" ? 1e-3 : 1.0;
  std::vector<std::pair<std::string, Eigen::Vector3d>> out;
  if (!m.contains("controlPoints")) return out;
  const json& cps = m.at("controlPoints");
  if (!cps.is_array()) throw std::runtime_error(name + ": controlPoints is not an array");
  for (size_t i = 0; i < cps.size(); ++i) {
    const json& cp = cps[i];
    if (cp.value("positionStatus", std::string("defined")) == "undefined") continue;
    const json& p = cp.at("position");
    if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() || !p[2].is_number())
      throw std::runtime_error(name + ": control point " + std::to_string(i) + ": position is not 3 numbers");
    Eigen::Vector3d v(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
    if (!v.allFinite()) throw std::runtime_error(name + ": control point " + std::to_string(i) + " is not finite");
    if (system == "LPS") v = Eigen::Vector3d(-v.x(), -v.y(), v.z());
    out.emplace_back(cp.value("label", std::string()), scale * v);
  }
  return out;
}

std::string markup_name(const json& m, size_t index) {
  std::string name = "markup " + std::to_string(index);
  if (m.contains("name") && m["name"].is_string()) name += " '" + m["name"].get<std::string>() + "'";
  else if (m.contains("controlPoints") && m["controlPoints"].is_array() && !m["controlPoints"].empty() &&
           m["controlPoints"][0].contains("label") && m["controlPoints"][0]["label"].is_string())
    name += " ('" + m["controlPoints"][0]["label"].get<std::string>() + "'...)";
  return name;
}

const json& markup_list(const json& j) {
  if (!j.is_object() || !j.contains("markups") || !j["markups"].is_array())
    throw std::runtime_error("not a 3D Slicer markups file (no \"markups\" array)");
  return j["markups"];
}

json parse_file(const std::string& path) { return read_json_file(path, "markups file"); }

}  // namespace

CenterlineGraph centerline_from_slicer_markups(const json& j, const std::string& origin) {
  try {
    const json& list = markup_list(j);
    std::vector<Curve> curves;
    for (size_t i = 0; i < list.size(); ++i) {
      const json& m = list[i];
      const std::string type = m.value("type", std::string());
      if (type != "Curve" && type != "ClosedCurve" && type != "Line") continue;
      Curve c;
      c.name = markup_name(m, i);
      const auto cps = control_points(m, c.name);
      for (const auto& cp : cps)
        if (c.points.empty() || (cp.second - c.points.back()).norm() > 1e-9) c.points.push_back(cp.second);
      if (type == "ClosedCurve" && c.points.size() > 2) c.points.push_back(c.points.front());
      if (c.points.size() < 2) throw std::runtime_error(c.name + ": fewer than 2 distinct control points");
      c.radii.assign(c.points.size(), 0.0);
      for (const json& meas : m.value("measurements", json::array())) {
        if (meas.value("name", std::string()) != "Radius" || !meas.contains("controlPointValues")) continue;
        const auto values = meas["controlPointValues"].get<std::vector<double>>();
        if (values.size() != cps.size())
          throw std::runtime_error(c.name + ": Radius measurement has " + std::to_string(values.size()) +
                                   " values for " + std::to_string(cps.size()) + " control points");
        if (cps.size() == c.points.size()) c.radii = values;  // (duplicates dropped: radii stay unknown)
        for (double& r : c.radii)
          if (!std::isfinite(r) || r < 0) r = 0.0;
        if (m.value("coordinateUnits", std::string("mm")) == "um")
          for (double& r : c.radii) r *= 1e-3;
      }
      curves.push_back(std::move(c));
    }
    if (curves.empty()) throw std::runtime_error("no Curve, ClosedCurve or Line markup: no centerline in this file");

    PolylineTree tree(curves.front().points, curves.front().radii);
    std::vector<char> placed(curves.size(), 0);
    placed[0] = 1;
    for (size_t done = 1; done < curves.size();) {
      bool progress = false;
      for (size_t i = 1; i < curves.size(); ++i) {
        if (placed[i]) continue;
        Curve& c = curves[i];
        const TreePoint head = tree.nearest(c.points.front()), tail = tree.nearest(c.points.back());
        const auto reach = [](const TreePoint& t) { return std::max(kSlicerJoinRadii * t.radius, kSlicerJoinMm); };
        const bool head_ok = head.distance <= reach(head), tail_ok = tail.distance <= reach(tail);
        if (!head_ok && !tail_ok) continue;
        if (!head_ok || (tail_ok && tail.distance < head.distance)) {
          std::reverse(c.points.begin(), c.points.end());
          std::reverse(c.radii.begin(), c.radii.end());
        }
        const TreePoint at = tree.nearest(c.points.front());
        tree.attach(at, std::vector<Eigen::Vector3d>(c.points.begin() + 1, c.points.end()),
                    std::vector<double>(c.radii.begin() + 1, c.radii.end()));
        placed[i] = 1;
        ++done;
        progress = true;
      }
      if (!progress) {
        for (size_t i = 1; i < curves.size(); ++i) {
          if (placed[i]) continue;
          const TreePoint head = tree.nearest(curves[i].points.front());
          std::ostringstream s;
          s << curves[i].name << " does not start on another curve: its ends are " << head.distance << " and "
            << tree.nearest(curves[i].points.back()).distance << " mm from the nearest one (at most "
            << kSlicerJoinMm << " mm or " << kSlicerJoinRadii << " radii)";
          throw std::runtime_error(s.str());
        }
      }
    }
    return tree.graph();
  } catch (const json::exception& e) {
    throw std::runtime_error(origin + ": malformed markups (" + e.what() + ")");
  } catch (const std::exception& e) {
    throw std::runtime_error(origin + ": " + e.what());
  }
}

CenterlineGraph read_slicer_markups(const std::string& path) { return centerline_from_slicer_markups(parse_file(path), path); }

std::vector<SlicerPoint> read_slicer_points(const std::string& path) {
  const json j = parse_file(path);
  try {
    std::vector<SlicerPoint> out;
    const json& list = markup_list(j);
    for (size_t i = 0; i < list.size(); ++i) {
      if (list[i].value("type", std::string()) != "Fiducial") continue;
      for (const auto& cp : control_points(list[i], markup_name(list[i], i))) out.push_back({cp.first, cp.second});
    }
    return out;
  } catch (const json::exception& e) {
    throw std::runtime_error(path + ": malformed markups (" + e.what() + ")");
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace gw
