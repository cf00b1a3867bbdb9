#include "lib/report/biplane_render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "lib/report/bitmap_font.hpp"
#include "lib/report/draw.hpp"
#include "lib/report/palette.hpp"
#include "lib/report/png_encoder.hpp"

namespace gw {
namespace {

namespace pal = palette;

// Layout, in pixels.
constexpr int kOuter = 8;                    // image border and gap between panels
constexpr int kHeadlineScale = 3, kTitleScale = 2;
constexpr int kLineGap = 5;
constexpr int kPadSide = 16, kPadTop = 36, kPadBottom = 44;  // inside a panel: name on top, scale bar below
constexpr int kMinPanelHeight = 120;
constexpr int kLegendHeight = 30;            // the legend strip at the bottom
constexpr Rgb kHalo = pal::kBackground;

std::string format(const char* fmt, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

std::string outcome_label(const std::string& o) {
  if (o == "success") return "SUCCESS";
  if (o == "wrong_branch") return "WRONG BRANCH";
  if (o == "stuck") return "STUCK";
  if (o == "timeout") return "TIMEOUT";
  if (o == "diverged") return "DIVERGED";
  return o;
}

// Cuts `s` with "..." so that it fits in `max_width` pixels at `scale`.
std::string fit_text(std::string s, int max_width, int scale) {
  if (text_width(s, scale) <= max_width) return s;
  while (!s.empty() && text_width(s + "...", scale) > max_width) s.pop_back();
  return s + "...";
}

// Greedy word wrap into lines of at most `max_width` pixels (a word longer than a line is cut).
std::vector<std::string> wrap_text(const std::string& text, int max_width, int scale) {
  std::vector<std::string> lines;
  std::string line, word;
  auto flush_word = [&] {
    if (word.empty()) return;
    const std::string joined = line.empty() ? word : line + " " + word;
    if (text_width(joined, scale) <= max_width || line.empty()) line = joined;
    else {
      lines.push_back(line);
      line = word;
    }
    word.clear();
  };
  for (char c : text) {
    if (c == ' ') flush_word();
    else word += c;
  }
  flush_word();
  if (!line.empty()) lines.push_back(line);
  return lines;
}

std::string headline(const std::vector<EpisodeTrace>& traces, Rgb& color) {
  if (traces.empty()) {
    color = pal::kText;
    return "NO EPISODE RECORDED";
  }
  if (traces.size() == 1) {
    const EpisodeTrace& t = traces[0];
    color = pal::outcome_color(t.outcome);
    return outcome_label(t.outcome) + (t.detail.empty() ? "" : ": " + t.detail);
  }
  std::size_t ok = 0;
  std::string failures;
  for (const std::string& o : kTraceOutcomes) {
    const auto n = static_cast<std::size_t>(
        std::count_if(traces.begin(), traces.end(), [&](const EpisodeTrace& t) { return t.outcome == o; }));
    if (o == "success") ok = n;
    else if (n > 0) failures += (failures.empty() ? "" : ", ") + outcome_label(o) + " " + std::to_string(n);
  }
  color = ok == traces.size() ? pal::outcome_color("success") : ok == 0 ? pal::outcome_color("wrong_branch") : pal::kText;
  return std::to_string(ok) + "/" + std::to_string(traces.size()) + " SUCCESS" +
         (failures.empty() ? "" : "   (" + failures + ")");
}

std::string summary_line(const std::vector<EpisodeTrace>& traces, const Terminal& target) {
  if (traces.empty()) return "target T" + std::to_string(target.id);
  const EpisodeTrace& t = traces[0];
  if (traces.size() == 1) {
    std::size_t agent = 0;
    for (bool b : t.agent_in_control) agent += b ? 1 : 0;
    const double duration = t.time_s.empty() ? 0.0 : t.time_s.back();
    const double share = t.time_s.empty() ? 0.0 : 100.0 * static_cast<double>(agent) / static_cast<double>(t.time_s.size());
    return (t.anatomy.empty() ? std::string() : t.anatomy + " | ") + "target T" + std::to_string(target.id) + " | " +
           (t.controller.empty() ? "controller ?" : t.controller) + " | seed " + std::to_string(t.seed) + " | " +
           format("%.2f", duration) + " s, " + std::to_string(t.time_s.size()) + " frames, agent in control " +
           format("%.0f", share) + "%";
  }
  std::string controllers;
  for (const auto& e : traces)
    if (controllers.find(e.controller) == std::string::npos) controllers += (controllers.empty() ? "" : ", ") + e.controller;
  return (t.anatomy.empty() ? std::string() : t.anatomy + " | ") + "target T" + std::to_string(target.id) + " | " +
         std::to_string(traces.size()) + " episodes | " + controllers;
}

// "+x" for an axis-aligned direction, "(+0.71, +0.00, -0.71)" otherwise.
std::string direction_text(const Eigen::Vector3d& d) {
  static const char* names[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k)
    if (std::abs(std::abs(d[k]) - 1.0) < 1e-9) return std::string(d[k] > 0 ? "+" : "-") + names[k];
  return "(" + format("%+.2f", d.x()) + ", " + format("%+.2f", d.y()) + ", " + format("%+.2f", d.z()) + ")";
}

// Largest 1, 2 or 5 x 10^k not above `limit` (millimetres).
double nice_length(double limit) {
  if (!(limit > 0.0) || !std::isfinite(limit)) return 1.0;
  const double p = std::pow(10.0, std::floor(std::log10(limit)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * p <= limit) return m * p;
  return p;
}

struct PanelInput {
  const TriangleMesh& mesh;
  const CenterlineGraph& graph;
  const std::vector<Eigen::Vector3d>& path;
  const Terminal& target;
  const std::vector<EpisodeTrace>& traces;
  const BiplaneOptions& options;
  double t_max;
};

// How many projected triangles cover each pixel of the panel.
CoverageRaster coverage(const Image& panel, const ViewProjection& view, const TriangleMesh& mesh) {
  std::vector<Eigen::Vector2d> px(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) px[static_cast<std::size_t>(v)] = view.to_pixel(mesh.V.row(v).transpose());
  CoverageRaster cov(panel.width, panel.height);
  const auto nv = mesh.V.rows();
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    if (a < 0 || b < 0 || c < 0 || a >= nv || b >= nv || c >= nv) continue;  // validate_mesh reports these
    cov.add_triangle(px[static_cast<std::size_t>(a)], px[static_cast<std::size_t>(b)], px[static_cast<std::size_t>(c)]);
  }
  return cov;
}

// The silhouette's boundary, 2 px wide (the last covered and the first uncovered pixel).
void draw_outline(Image& panel, const ViewProjection& view, const TriangleMesh& mesh, Rgb color) {
  if (mesh.F.rows() == 0) return;
  const CoverageRaster cov = coverage(panel, view, mesh);
  auto covered = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < panel.width && y < panel.height && cov.at(x, y) > 0;
  };
  for (int y = 0; y < panel.height; ++y)
    for (int x = 0; x < panel.width; ++x) {
      const bool in = covered(x, y);
      if (in != covered(x - 1, y) || in != covered(x + 1, y) || in != covered(x, y - 1) || in != covered(x, y + 1))
        panel.set(x, y, color);
    }
}

void draw_vessel(Image& panel, const ViewProjection& view, const TriangleMesh& mesh) {
  if (mesh.F.rows() == 0) return;
  const CoverageRaster cov = coverage(panel, view, mesh);
  for (int y = 0; y < panel.height; ++y)
    for (int x = 0; x < panel.width; ++x) {
      const int n = cov.at(x, y);
      if (n == 0) continue;
      const bool edge = x == 0 || y == 0 || x == panel.width - 1 || y == panel.height - 1 || cov.at(x - 1, y) == 0 ||
                        cov.at(x + 1, y) == 0 || cov.at(x, y - 1) == 0 || cov.at(x, y + 1) == 0;
      if (edge) {
        panel.set(x, y, pal::kVesselEdge);
        continue;
      }
      // A closed tube is crossed by two walls; every further pair is another vessel in front.
      const int layers = (n + 1) / 2;
      const int g = std::max(160, pal::kVesselFill.r - 24 * (layers - 1));
      panel.set(x, y, Rgb{static_cast<std::uint8_t>(g), static_cast<std::uint8_t>(g), static_cast<std::uint8_t>(g)});
    }
}

std::vector<Eigen::Vector2d> project(const ViewProjection& view, const std::vector<Eigen::Vector3d>& pts) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(pts.size());
  for (const auto& p : pts)
    out.push_back(p.allFinite() ? view.to_pixel(p) : Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()));
  return out;
}

void draw_final_wires(Image& panel, const ViewProjection& view, const PanelInput& in) {
  if (!in.options.draw_final_wire) return;
  for (const EpisodeTrace& t : in.traces)
    if (!t.wire_shapes.empty()) {
      const auto px = project(view, t.wire_shapes.back());
      for (std::size_t i = 1; i < px.size(); ++i) draw_segment(panel, px[i - 1], px[i], 2.0, pal::kWire);
    }
}

void draw_traces(Image& panel, const ViewProjection& view, const PanelInput& in) {
  // One episode: its final wire on top of its trace (the trace shows on both sides of it).
  // Several: the wires underneath, or they would hide every trace where they overlap.
  const bool batch = in.traces.size() > 1;
  if (batch) draw_final_wires(panel, view, in);
  for (const EpisodeTrace& t : in.traces) {
    Eigen::Vector2d prev;
    bool have_prev = false;
    for (std::size_t i = 0; i < t.tip.size(); ++i) {
      if (!t.tip[i].allFinite()) {
        have_prev = false;  // diverged frames: break the line
        continue;
      }
      const Eigen::Vector2d p = view.to_pixel(t.tip[i]);
      const Rgb c = in.options.coloring == TraceColoring::Time ? pal::time_color(t.time_s[i] / in.t_max)
                    : t.agent_in_control[i]                    ? pal::kTipAgent
                                                               : pal::kTipPush;
      // 5 px under the 2 px final wire: the colour stays visible on both sides of it.
      const double width = batch ? 3.0 : 5.0;
      if (have_prev) draw_segment(panel, prev, p, width, c);
      else fill_disc(panel, p, width / 2.0, c);
      prev = p;
      have_prev = true;
    }
  }
  if (!batch) draw_final_wires(panel, view, in);
  for (const EpisodeTrace& t : in.traces)
    for (std::size_t i = t.tip.size(); i-- > 0;)
      if (t.tip[i].allFinite()) {
        const Eigen::Vector2d p = view.to_pixel(t.tip[i]);
        fill_disc(panel, p, 5.0, pal::outcome_color(t.outcome));
        draw_ring(panel, p, 5.5, 1.5, pal::kWire);
        break;
      }
}

void draw_panel(Image& panel, const ViewProjection& view, const PanelInput& in) {
  draw_vessel(panel, view, in.mesh);
  for (const WallOutline& o : in.options.wall_outlines) draw_outline(panel, view, o.mesh, o.color);
  draw_polyline(panel, project(view, in.path), 3.0, pal::kPath);

  if (in.options.draw_other_targets)
    for (const Terminal& t : in.graph.targets) {
      if (t.id == in.target.id || !t.position.allFinite()) continue;
      const Eigen::Vector2d p = view.to_pixel(t.position);
      draw_ring(panel, p, 6.0, 2.0, pal::kOtherTarget);
      draw_text(panel, static_cast<int>(p.x()) + 9, static_cast<int>(p.y()) - 15, "T" + std::to_string(t.id),
                pal::kOtherTarget, 2, &kHalo);
    }
  for (const Bifurcation& b : in.graph.bifurcations) {
    if (!b.position.allFinite()) continue;
    const Eigen::Vector2d p = view.to_pixel(b.position);
    fill_disc(panel, p, 4.0, pal::kBifurcation);
    if (in.options.label_bifurcations)
      draw_text(panel, static_cast<int>(p.x()) + 7, static_cast<int>(p.y()) + 4, "B" + std::to_string(b.id),
                pal::kBifurcation, 1, &kHalo);
  }
  if (in.graph.inlet.position.allFinite()) {
    const Eigen::Vector2d p = view.to_pixel(in.graph.inlet.position);
    const int x = static_cast<int>(std::floor(p.x())), y = static_cast<int>(std::floor(p.y()));
    fill_rect(panel, x - 5, y - 5, x + 6, y + 6, pal::kInlet);
    draw_text(panel, x + 9, y - 4, "inlet", pal::kInlet, 1, &kHalo);
  }

  draw_traces(panel, view, in);

  if (in.target.position.allFinite()) {
    const Eigen::Vector2d p = view.to_pixel(in.target.position);
    draw_ring(panel, p, 10.0, 3.0, pal::kTarget);
    fill_disc(panel, p, 3.0, pal::kTarget);
    draw_text(panel, static_cast<int>(p.x()) + 13, static_cast<int>(p.y()) - 18, "T" + std::to_string(in.target.id),
              pal::kTarget, 2, &kHalo);
  }

  // Name, axes, scale bar, border.
  draw_text(panel, 8, 6, view.axes.name, pal::kText, 2);
  draw_text(panel, 8, 24, "right " + direction_text(view.axes.right) + "   up " + direction_text(view.axes.up),
            pal::kText, 1);
  const double bar_mm = nice_length(0.25 * panel.width / view.px_per_mm);
  const int bar_px = std::max(1, static_cast<int>(std::lround(bar_mm * view.px_per_mm)));
  const int bx = 14, by = panel.height - 14;
  fill_rect(panel, bx, by - 1, bx + bar_px, by + 2, pal::kText);
  fill_rect(panel, bx, by - 6, bx + 2, by + 7, pal::kText);
  fill_rect(panel, bx + bar_px - 2, by - 6, bx + bar_px, by + 7, pal::kText);
  draw_text(panel, bx, by - 24, format("%g", bar_mm) + " mm", pal::kText, 2, &kHalo);
  for (int x = 0; x < panel.width; ++x) {
    panel.set(x, 0, pal::kPanelBorder);
    panel.set(x, panel.height - 1, pal::kPanelBorder);
  }
  for (int y = 0; y < panel.height; ++y) {
    panel.set(0, y, pal::kPanelBorder);
    panel.set(panel.width - 1, y, pal::kPanelBorder);
  }
}

void draw_legend(Image& img, int y0, const BiplaneOptions& options, double t_max, Rgb tip_color, bool batch) {
  enum Kind { Box, Line, Square, Ring, Dot, Tip, Ramp };
  struct Item { Kind kind; Rgb color; std::string label; };
  std::vector<Item> items = {{Box, pal::kVesselFill, options.vessel_label}};
  for (const WallOutline& o : options.wall_outlines) items.push_back({Line, o.color, o.label});
  items.insert(items.end(), {{Line, pal::kPath, "path"},
                             {Square, pal::kInlet, "inlet"},    {Ring, pal::kTarget, "target"},
                             {Dot, pal::kBifurcation, "bifurcation"}});
  if (options.coloring == TraceColoring::AgentControl) {
    items.push_back({Line, pal::kTipPush, "tip: push"});
    items.push_back({Line, pal::kTipAgent, "tip: agent"});
  } else {
    items.push_back({Ramp, pal::kText, "tip time 0-" + format("%.3g", t_max) + " s"});
  }
  if (options.draw_final_wire) items.push_back({Line, pal::kWire, "final wire"});
  // Several episodes: the header lists the outcomes; a neutral swatch says "coloured by outcome".
  items.push_back({Tip, batch ? pal::outcome_color("") : tip_color, "final tip"});

  constexpr int kSwatch = 26, kGap = 22;
  int scale = 2, total = 0;
  for (int s : {2, 1}) {
    scale = s;
    total = 0;
    for (const auto& it : items) total += kSwatch + 6 + text_width(it.label, s) + kGap;
    if (total <= img.width - 2 * kOuter) break;
  }
  int x = kOuter + 4;
  const int cy = y0 + 10;
  for (const auto& it : items) {
    const Eigen::Vector2d c(x + kSwatch / 2.0, cy + 0.5);
    switch (it.kind) {
      case Box: fill_rect(img, x, cy - 7, x + kSwatch, cy + 8, it.color);
        fill_rect(img, x, cy - 7, x + kSwatch, cy - 6, pal::kVesselEdge);
        fill_rect(img, x, cy + 7, x + kSwatch, cy + 8, pal::kVesselEdge);
        break;
      case Line: draw_segment(img, {x + 1.0, cy + 0.5}, {x + kSwatch - 1.0, cy + 0.5}, 3.0, it.color); break;
      case Square: fill_rect(img, x + 8, cy - 5, x + 19, cy + 6, it.color); break;
      case Ring: draw_ring(img, c, 8.0, 3.0, it.color);
        fill_disc(img, c, 2.5, it.color);
        break;
      case Dot: fill_disc(img, c, 4.0, it.color); break;
      case Tip: fill_disc(img, c, 5.0, it.color);
        draw_ring(img, c, 5.5, 1.5, pal::kWire);
        break;
      case Ramp:
        for (int k = 0; k < kSwatch * 2; ++k) fill_rect(img, x + k, cy - 5, x + k + 1, cy + 6, pal::time_color(k / (kSwatch * 2.0 - 1)));
        x += kSwatch;
        break;
    }
    x += kSwatch + 6;
    draw_text(img, x, cy - 7 * scale / 2, it.label, pal::kText, scale);
    x += text_width(it.label, scale) + kGap;
  }
}

// Refuses (std::invalid_argument) an image size outside 320x240 .. 16384x16384 and an inconsistent trace.
void check_biplane_input(const std::vector<EpisodeTrace>& traces, const BiplaneOptions& options) {
  const int W = options.width, H = options.height;
  if (W < 320 || H < 240 || W > 16384 || H > 16384)
    throw std::invalid_argument("biplane: image size " + std::to_string(W) + "x" + std::to_string(H) +
                                " is outside 320x240 .. 16384x16384");
  for (std::size_t i = 0; i < traces.size(); ++i) check_trace(traces[i], "biplane: trace " + std::to_string(i));
}

// The scene that frames both views: mesh and wall outlines, path, inlet, targets, bifurcations and branches
// (traces excluded: a diverged one would blow it up).
std::vector<Eigen::Vector3d> framing_scene(const TriangleMesh& mesh, const CenterlineGraph& graph,
                                           const std::vector<Eigen::Vector3d>& path_points, const Terminal& target,
                                           const BiplaneOptions& options) {
  std::vector<Eigen::Vector3d> scene;
  scene.reserve(static_cast<std::size_t>(mesh.V.rows()) + path_points.size() + 16);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) scene.push_back(mesh.V.row(v).transpose());
  for (const WallOutline& o : options.wall_outlines)
    for (Eigen::Index v = 0; v < o.mesh.V.rows(); ++v) scene.push_back(o.mesh.V.row(v).transpose());
  scene.insert(scene.end(), path_points.begin(), path_points.end());
  scene.push_back(graph.inlet.position);
  scene.push_back(target.position);
  for (const auto& t : graph.targets) scene.push_back(t.position);
  for (const auto& b : graph.bifurcations) scene.push_back(b.position);
  for (const auto& b : graph.branches) scene.insert(scene.end(), b.points.begin(), b.points.end());
  return scene;
}

// Header drawn into `img`: outcome line, generated summary, caller's lines (as many as leave a usable panel).
// Returns the y below its last line; head_color: the outcome line's colour.
int draw_header(Image& img, const std::vector<EpisodeTrace>& traces, const Terminal& target,
                const std::vector<std::string>& title_lines, const BiplaneOptions& options, Rgb& head_color) {
  const int W = options.width, H = options.height;
  // An outcome too long for one big line keeps its label big and wraps the detail below it.
  const int text_w = W - 2 * kOuter - 4;
  std::string head = headline(traces, head_color);
  std::vector<std::pair<std::string, Rgb>> lines;
  if (text_width(head, kHeadlineScale) > text_w && traces.size() == 1) {
    head = outcome_label(traces[0].outcome);
    for (const auto& l : wrap_text(traces[0].detail, text_w, kTitleScale)) {
      if (lines.size() == 2) break;  // the JSON holds the full text
      lines.emplace_back(l, head_color);
    }
  }
  lines.emplace_back(summary_line(traces, target), pal::kText);
  for (const auto& l : title_lines) lines.emplace_back(l, pal::kText);
  const int line_h = kGlyphHeight * kTitleScale + kLineGap;
  const int head_h = kOuter + kGlyphHeight * kHeadlineScale + 2 * kLineGap;
  const int max_lines = std::max(0, (H - kLegendHeight - kMinPanelHeight - head_h - kOuter) / line_h);
  if (static_cast<int>(lines.size()) > max_lines) lines.resize(static_cast<std::size_t>(max_lines));
  draw_text(img, kOuter + 2, kOuter, fit_text(head, text_w, kHeadlineScale), head_color, kHeadlineScale);
  int y = head_h;
  for (const auto& [l, color] : lines) {
    draw_text(img, kOuter + 2, y, fit_text(l, text_w, kTitleScale), color, kTitleScale);
    y += line_h;
  }
  return y;
}

// One scale for both views (a biplane reader compares lengths across panels), and each view's centre (u, v).
struct ViewFit {
  double ppm;
  std::array<Eigen::Vector2d, 2> centre;
};

// The largest scale at which the scene fits a panel_w x panel_h panel (inside its padding) in both views.
ViewFit fit_views(const std::vector<Eigen::Vector3d>& scene, const std::array<ViewAxes, 2>& axes, int panel_w,
                  int panel_h) {
  double ppm = std::numeric_limits<double>::infinity();
  std::array<Eigen::Vector2d, 2> centre;
  for (int v = 0; v < 2; ++v) {
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const auto& p : scene)
      if (p.allFinite()) {
        const Eigen::Vector2d q(p.dot(axes[v].right), p.dot(axes[v].up));
        lo = lo.cwiseMin(q);
        hi = hi.cwiseMax(q);
      }
    centre[v] = (lo + hi) / 2.0;
    const Eigen::Vector2d ext = hi - lo;
    if (ext.x() > 1e-9) ppm = std::min(ppm, (panel_w - 2.0 * kPadSide) / ext.x());
    if (ext.y() > 1e-9) ppm = std::min(ppm, (panel_h - kPadTop - kPadBottom) / ext.y());
  }
  if (!std::isfinite(ppm)) ppm = 10.0;  // a single point: any scale shows it
  return {ppm, centre};
}

// The traces' last finite time (1 s when none): the end of the time colouring.
double trace_time_max(const std::vector<EpisodeTrace>& traces) {
  double m = 0.0;
  for (const auto& t : traces)
    for (double s : t.time_s)
      if (std::isfinite(s)) m = std::max(m, s);
  return m > 0.0 ? m : 1.0;
}

// Both views drawn as panel_w x panel_h panels side by side from panel_y into out.image; out.views: where
// each landed and its projection.
void draw_views(BiplaneRender& out, const PanelInput& in, const std::array<ViewAxes, 2>& axes, const ViewFit& fit,
                int panel_w, int panel_h, int panel_y) {
  Image& img = out.image;
  const double ppm = fit.ppm;
  for (int v = 0; v < 2; ++v) {
    ViewProjection local;
    local.axes = axes[v];
    local.px_per_mm = ppm;
    // Shift the scene a little down: the panel name takes more room on top than the bar below.
    local.centre_uv = fit.centre[v] + Eigen::Vector2d(0.0, (kPadTop - kPadBottom) / 2.0 / ppm);
    local.panel_size = {panel_w, panel_h};
    Image panel(panel_w, panel_h, pal::kBackground);
    draw_panel(panel, local, in);
    const int x0 = kOuter + v * (panel_w + kOuter);
    for (int py = 0; py < panel_h; ++py)
      std::copy_n(panel.rgb.begin() + static_cast<std::ptrdiff_t>(panel.index(0, py)), 3 * panel_w,
                  img.rgb.begin() + static_cast<std::ptrdiff_t>(img.index(x0, panel_y + py)));
    out.views[static_cast<std::size_t>(v)] = local;
    out.views[static_cast<std::size_t>(v)].panel_origin = {x0, panel_y};
  }
}

}  // namespace

BiplaneRender render_biplane(const TriangleMesh& mesh, const CenterlineGraph& graph,
                             const std::vector<Eigen::Vector3d>& path_points, const Terminal& target,
                             const std::vector<EpisodeTrace>& traces, const std::vector<std::string>& title_lines,
                             const BiplaneOptions& options) {
  const int W = options.width, H = options.height;
  check_biplane_input(traces, options);
  const std::vector<Eigen::Vector3d> scene = framing_scene(mesh, graph, path_points, target, options);
  const std::array<ViewAxes, 2> axes = choose_biplane_axes(scene, graph.inlet.position, options.axes);

  BiplaneRender out{Image(W, H, pal::kBackground), {}};
  Rgb head_color;
  const int panel_y = draw_header(out.image, traces, target, title_lines, options, head_color) + 2;
  const int panel_h = H - kLegendHeight - panel_y;
  const int panel_w = (W - 3 * kOuter) / 2;
  const ViewFit fit = fit_views(scene, axes, panel_w, panel_h);
  const double t_max = trace_time_max(traces);

  const PanelInput in{mesh, graph, path_points, target, traces, options, t_max};
  draw_views(out, in, axes, fit, panel_w, panel_h, panel_y);
  draw_legend(out.image, H - kLegendHeight + 4, options, t_max,
              traces.size() == 1 ? head_color : pal::outcome_color("success"), traces.size() > 1);
  return out;
}

void render_biplane_png(const TriangleMesh& mesh, const CenterlineGraph& graph,
                        const std::vector<Eigen::Vector3d>& path_points, const Terminal& target,
                        const std::vector<EpisodeTrace>& traces, const std::vector<std::string>& title_lines,
                        const std::string& out_path, const BiplaneOptions& options) {
  write_png(render_biplane(mesh, graph, path_points, target, traces, title_lines, options).image, out_path);
}

}  // namespace gw
