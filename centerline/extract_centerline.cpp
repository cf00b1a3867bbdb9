#include "centerline/extract_centerline.hpp"
#include "centerline/flat_ends.hpp"
#include "base/util/median.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "centerline/estimate_wall_noise.hpp"
#include "centerline/junction_centre.hpp"
#include "centerline/merge_close_junctions.hpp"
#include "centerline/mcf_skeleton.hpp"
#include "centerline/prepare_surface.hpp"
#include "centerline/refine_branch.hpp"
#include "centerline/skeleton_tree.hpp"
#include "centerline/straighten_junction_links.hpp"
#include "centerline/vessel_wall.hpp"

namespace gw {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Typical radius of a chain near its end `at_start`: median over the half next to it.
double end_radius(const RefinedBranch& b, bool at_start) {
  const size_t half = std::max<size_t>(1, b.radii.size() / 2);
  std::vector<double> r;
  if (at_start) r.assign(b.radii.begin(), b.radii.begin() + static_cast<long>(half));
  else r.assign(b.radii.end() - static_cast<long>(half), b.radii.end());
  return r.empty() ? 0.0 : median(r);
}

// The vessel radius of the thinnest chain of `tree`: the smallest median wall distance of a chain's points.
double thinnest_chain_radius(const SkeletonTree& tree, const VesselWall& wall) {
  double thinnest = std::numeric_limits<double>::infinity();
  for (const auto& c : tree.chains) {
    std::vector<double> r;
    for (const auto& p : c.points) r.push_back(wall.distance(p));
    thinnest = std::min(thinnest, r.empty() ? 0.0 : median(r));
  }
  return thinnest;
}

// The known vessel ends (capped open ends, flat ends) that no terminal of `tree` lies within `radii` of the end's
// radii of.
std::vector<SurfaceCap> ends_missed(const SkeletonTree& tree, const std::vector<SurfaceCap>& ends, double radii) {
  const std::vector<int> degree = tree.degree();
  std::vector<SurfaceCap> missed;
  for (const SurfaceCap& end : ends) {
    bool reached = false;
    for (size_t v = 0; v < tree.nodes.size() && !reached; ++v)
      reached = degree[v] == 1 && (tree.nodes[v] - end.centre).norm() < radii * end.radius;
    if (!reached) missed.push_back(end);
  }
  return missed;
}

// How near the first skeleton's terminals must come to a known end: on the validation trees, training patterns and
// validation arches the nearest lies within 3.3 of the end's radii of every end that is a vessel's; on the stub
// arches (anatomies/validation/arches/*_stub*) 15.5 and more from every stub's.
constexpr double kEndReach = 6.0;

// Adds a terminal chain from the skeleton point on the end's axis (the inward normal from its centre, within half
// its radius) nearest the end, else the point nearest that axis (the chain split there, a new junction; a terminal
// there goes on instead) straight to half the end's radius inside it. `grafted`: the chains earlier
// grafts made or extended, which a later one does not take (per chain; grows with the tree).
void graft_end(SkeletonTree& tree, const SurfaceCap& end, std::vector<char>& grafted) {
  grafted.resize(tree.chains.size(), 0);
  size_t best_chain = 0, best_point = 0;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < tree.chains.size(); ++i)
    for (size_t k = 0; k < tree.chains[i].points.size() && !grafted[i]; ++k) {
      const Eigen::Vector3d q = tree.chains[i].points[k] - end.centre;  // its distance to the end's axis, inwards
      const double t = std::max(0.0, -q.dot(end.normal));
      const double off = (q + t * end.normal).norm();
      const double score = off <= 0.5 * end.radius ? t : 1e9 + off;  // on the axis: the point nearest the end
      if (score < best) best = score, best_chain = i, best_point = k;
    }
  SkeletonChain& c = tree.chains[best_chain];
  const Eigen::Vector3d to = end.centre - 0.5 * end.radius * end.normal;
  const auto straight = [&](const Eigen::Vector3d& from) {  // from (excluded) to `to`, about 0.5 mm apart
    std::vector<Eigen::Vector3d> p;
    const int n = std::max(2, static_cast<int>(std::ceil((to - from).norm() / 0.5)));
    for (int k = 1; k <= n; ++k) p.push_back(from + (to - from) * (static_cast<double>(k) / n));
    return p;
  };
  int junction = best_point == 0 ? c.a : best_point + 1 == c.points.size() ? c.b : -1;
  if (junction >= 0 && tree.degree()[static_cast<size_t>(junction)] == 1) {  // a terminal: it goes on to the end
    if (junction == c.a) std::reverse(c.points.begin(), c.points.end()), std::swap(c.a, c.b);
    const std::vector<Eigen::Vector3d> more = straight(c.points.back());
    c.points.insert(c.points.end(), more.begin(), more.end());
    tree.nodes[static_cast<size_t>(junction)] = to;
    grafted[best_chain] = 1;
    return;
  }
  if (junction < 0) {  // split the chain at that point
    junction = static_cast<int>(tree.nodes.size());
    tree.nodes.push_back(c.points[best_point]);
    SkeletonChain rest;
    rest.a = junction;
    rest.b = c.b;
    rest.points.assign(c.points.begin() + static_cast<long>(best_point), c.points.end());
    c.points.resize(best_point + 1);
    c.b = junction;
    tree.chains.push_back(std::move(rest));
  }
  SkeletonChain graft;
  graft.a = junction;
  graft.b = static_cast<int>(tree.nodes.size());
  graft.points = {tree.nodes[static_cast<size_t>(junction)]};
  const std::vector<Eigen::Vector3d> more = straight(graft.points.front());
  graft.points.insert(graft.points.end(), more.begin(), more.end());
  tree.nodes.push_back(to);
  tree.chains.push_back(std::move(graft));
  grafted.resize(tree.chains.size(), 0);
  grafted.back() = 1;
}

// A vessel a few hundredths of a millimetre wide is a mesh in metres (or cm): every
// tolerance below is in millimetres, so refuse rather than return nonsense.
void check_millimetres(double mean_radius) {
  if (mean_radius < 0.05) {
    std::ostringstream msg;
    msg << "vessel radius is about " << mean_radius
        << " mm: the mesh is probably not in millimetres (use --scale, e.g. 1000 for metres)";
    throw std::runtime_error(msg.str());
  }
}

// Stages 3-4 at one edge length: the remeshed surface's MCF skeleton, cleaned into a tree of chains
// (caps: the open ends' centres); adds the face count and seconds to `stats`.
SkeletonTree skeleton_pass(const ClosedSurface& closed, double edge, const VesselWall& wall,
                           const std::vector<Eigen::Vector3d>& caps, const SkeletonCleanup& cleanup,
                           CenterlineStats& stats) {
  auto t0 = std::chrono::steady_clock::now();
  const TriangleMesh coarse = remesh_surface(closed.mesh, edge);
  stats.skeleton_faces = coarse.F.rows();
  stats.seconds_prepare += seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const RawSkeleton raw = mcf_skeleton(coarse);
  stats.seconds_skeleton += seconds_since(t0);
  SkeletonTree tree =
      clean_skeleton(raw, [&](const Eigen::Vector3d& p) { return wall.distance(p); }, caps, cleanup);
  if (tree.chains.empty()) throw std::runtime_error("the skeleton has no branch");
  return tree;
}

// Stages 3-4: the tree of chains at edge length `edge` (floor `finest`), skeletonised again at a
// finer edge when its thinnest chain needs one.
SkeletonTree skeleton_tree(const ClosedSurface& closed, const CenterlineOptions& opt, const VesselWall& wall,
                           double edge, double finest, CenterlineStats& stats) {
  std::vector<Eigen::Vector3d> caps;
  for (const auto& c : closed.caps) caps.push_back(c.centre);
  SkeletonCleanup cleanup;
  cleanup.spur_factor = opt.spur_factor;
  cleanup.merge_factor = opt.merge_factor;
  SkeletonTree tree = skeleton_pass(closed, edge, wall, caps, cleanup, stats);
  // A branch far thinner than the mean radius (the great vessels off an aortic arch: 2.5 times) gets
  // one or two edges across at that edge length, and MCF blurs its origin into its neighbour's.
  const double thin = thinnest_chain_radius(tree, wall);
  double fine = std::max(2 * M_PI * thin / opt.edges_around_thinnest, finest);
  // A known vessel end (a capped open end, an end cut flat) that no terminal of this skeleton reaches (a great
  // vessel cut to a stub on an arch's roof: a few triangles at this edge, contracted by MCF into the aorta's
  // skeleton): finer, for that end's radius.
  std::vector<SurfaceCap> ends = closed.caps;  // the open ends the intake capped, and the ends cut flat
  for (const SurfaceCap& end : flat_ends(closed.mesh, wall)) ends.push_back(end);
  const std::vector<SurfaceCap> missed = ends_missed(tree, ends, kEndReach);
  if (!missed.empty()) {
    for (const SurfaceCap& end : missed)
      fine = std::min(fine, std::max(2 * M_PI * end.radius / opt.edges_around_thinnest, finest));
    stats.missed_ends = static_cast<int>(missed.size());
  }
  if (fine < edge) {
    edge = fine;
    tree = skeleton_pass(closed, edge, wall, caps, cleanup, stats);
    stats.skeleton_passes = 2;
  }
  // An end MCF contracts whatever the mesh (a stub about one radius long) still gets its terminal where none lies
  // within SkeletonCleanup::cap_factor of its radii: a chain from the skeleton's nearest point to it, which
  // refinement re-centres like any other.
  std::vector<char> grafted;
  if (!missed.empty()) {
    for (const SurfaceCap& end : ends_missed(tree, ends, cleanup.cap_factor)) graft_end(tree, end, grafted);
    tree.known_ends = ends;
  }
  return tree;
}

// The tree's chains refined, with its junction nodes re-centred, and its node degrees.
struct RefinedTree {
  std::vector<RefinedBranch> refined;
  std::vector<Eigen::Vector3d> nodes;
  std::vector<int> degree;
};

// Stage 6: every chain refined and the junctions re-centred, close junctions merged (which changes
// `tree`); the wall noise goes to `stats`.
RefinedTree refine_tree(SkeletonTree& tree, const VesselWall& wall, const CenterlineOptions& opt,
                        CenterlineStats& stats) {
  BranchRefinement refinement;
  refinement.spacing = opt.spacing;
  refinement.smoothing_iterations = opt.smoothing_iterations;
  // A segmentation's voxel staircase: the section tests allow for it (0 on a smooth wall).
  std::vector<std::vector<Eigen::Vector3d>> chain_points;
  for (const auto& c : tree.chains) chain_points.push_back(c.points);
  refinement.wall_noise = estimate_wall_noise(chain_points, wall, opt.spacing);
  stats.wall_noise = refinement.wall_noise;
  RefinedTree r;
  std::vector<RefinedBranch>& refined = r.refined;
  std::vector<Eigen::Vector3d>& nodes = r.nodes;
  std::vector<int>& degree = r.degree;
  const auto refine_and_recentre = [&] {
    degree = tree.degree();
    refined.clear();
    for (const auto& c : tree.chains)
      refined.push_back(refine_branch(c.points, degree[c.a] == 1, degree[c.b] == 1, wall, refinement));
    nodes = tree.nodes;
    recentre_junctions(tree, nodes, refined, wall, opt.spacing, 6.0, refinement.wall_noise);
    straighten_junction_links(tree, refined, opt.spacing);
  };
  refine_and_recentre();
  // A trifurcation is two skeleton junctions that re-centring puts within a radius of each other:
  // one junction with three exits (merge_close_junctions.hpp).
  while (merge_close_junctions(tree, nodes, refined, opt.merge_factor)) refine_and_recentre();
  return r;
}

// Stage 5. Inlet: the terminal nearest the given point, else the one on the widest branch
// (ties: lowest x, y, z, so the choice is deterministic). Returns its node.
int choose_inlet(const SkeletonTree& tree, const RefinedTree& r, const CenterlineOptions& opt) {
  const std::vector<RefinedBranch>& refined = r.refined;
  const std::vector<int>& degree = r.degree;
  int inlet_node = -1;
  std::tuple<double, double, double, double> best{0, 0, 0, 0};
  for (size_t i = 0; i < tree.chains.size(); ++i) {
    const auto& c = tree.chains[i];
    for (bool at_start : {true, false}) {
      const int node = at_start ? c.a : c.b;
      if (degree[node] != 1) continue;
      const Eigen::Vector3d end = at_start ? refined[i].points.front() : refined[i].points.back();
      const double score = opt.inlet ? -(end - *opt.inlet).norm() : end_radius(refined[i], at_start);
      const std::tuple<double, double, double, double> key{score, -end.x(), -end.y(), -end.z()};
      if (inlet_node < 0 || key > best) inlet_node = node, best = key;
    }
  }
  if (inlet_node < 0) throw std::runtime_error("the skeleton has no terminal to enter from");
  return inlet_node;
}

// Walk the tree from the inlet so every branch runs distally: the graph's branches and
// bifurcations (no inlet, no targets yet).
CenterlineGraph walk_from_inlet(const SkeletonTree& tree, const RefinedTree& r, int inlet_node,
                                const CenterlineOptions& opt) {
  const std::vector<RefinedBranch>& refined = r.refined;
  const std::vector<Eigen::Vector3d>& nodes = r.nodes;
  const std::vector<int>& degree = r.degree;
  CenterlineGraph g;
  std::vector<int> arriving(tree.nodes.size(), -1);
  std::vector<char> visited(tree.nodes.size(), 0), used(tree.chains.size(), 0);
  std::queue<int> queue;
  queue.push(inlet_node);
  visited[inlet_node] = 1;
  std::vector<int> bifurcation_of(tree.nodes.size(), -1);
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop();
    for (size_t i = 0; i < tree.chains.size(); ++i) {
      const auto& c = tree.chains[i];
      if (used[i] || (c.a != v && c.b != v)) continue;
      used[i] = 1;
      const int far = c.a == v ? c.b : c.a;
      if (visited[far]) continue;
      visited[far] = 1;
      // A terminal chain that re-centring shrank to a stub (its junction moved onto the vessel axes
      // and the chain was cut back to there) is a spur of the skeleton, not a vessel. Dropped only
      // where the junction keeps two other children, so that it stays a bifurcation.
      const Eigen::Vector3d far_end = c.a == v ? refined[i].points.back() : refined[i].points.front();
      if (degree[far] == 1 && degree[v] >= 4 && !tree.at_known_end(far_end) && polyline_length(refined[i].points) <
          opt.spur_factor * *std::max_element(refined[i].radii.begin(), refined[i].radii.end())) {
        continue;
      }
      CenterlineBranch branch;
      branch.id = static_cast<int>(g.branches.size());
      branch.parent = arriving[v];
      branch.points = refined[i].points;
      branch.radii = refined[i].radii;
      if (c.a != v) {
        std::reverse(branch.points.begin(), branch.points.end());
        std::reverse(branch.radii.begin(), branch.radii.end());
      }
      if (branch.parent >= 0) {
        if (bifurcation_of[v] < 0) {
          Bifurcation b;
          b.id = static_cast<int>(g.bifurcations.size());
          b.position = nodes[v];
          b.parent = branch.parent;
          bifurcation_of[v] = b.id;
          g.bifurcations.push_back(b);
        }
        g.bifurcations[bifurcation_of[v]].children.push_back(branch.id);
      }
      arriving[far] = branch.id;
      g.branches.push_back(std::move(branch));
      queue.push(far);
    }
  }
  return g;
}

// The inlet at the root branch's start, and the direction into the vessel from it.
void set_inlet(CenterlineGraph& g, const CenterlineOptions& opt) {
  const CenterlineBranch& root = g.branches.front();
  g.inlet.id = 0;
  g.inlet.position = root.points.front();
  g.inlet.branch = 0;
  g.inlet.radius = root.radii.front();
  // Direction into the vessel: over about two radii of the root branch.
  const double ahead = 2.0 * std::max(root.radii.front(), opt.spacing);
  Eigen::Vector3d towards = root.points.back();
  double run = 0.0;
  for (size_t i = 1; i < root.points.size(); ++i) {
    run += (root.points[i] - root.points[i - 1]).norm();
    if (run >= ahead) {
      towards = root.points[i];
      break;
    }
  }
  if ((towards - root.points.front()).norm() > 0) g.inlet_direction = (towards - root.points.front()).normalized();
}

}  // namespace

CenterlineGraph extract_centerline(const TriangleMesh& mesh, const CenterlineOptions& opt, CenterlineStats* stats_out) {
  const auto t0 = std::chrono::steady_clock::now();
  const ClosedSurface closed = close_surface(mesh);
  CenterlineStats stats;
  CenterlineGraph g = extract_centerline(closed, opt, &stats);
  stats.input_faces = mesh.F.rows();
  stats.seconds_prepare = seconds_since(t0) - stats.seconds_skeleton - stats.seconds_graph;  // closing included
  if (stats_out) *stats_out = stats;
  return g;
}

CenterlineGraph extract_centerline(const ClosedSurface& closed, const CenterlineOptions& opt, CenterlineStats* stats_out) {
  if (!(opt.spacing > 0) || !(opt.edges_per_radius > 0))
    throw std::invalid_argument("centerline options: spacing and edges_per_radius must be positive");
  CenterlineStats stats;
  stats.input_faces = closed.mesh.F.rows();
  auto t0 = std::chrono::steady_clock::now();

  // 1-2. A closed surface, remeshed to a size tied to the vessel radius.
  stats.capped_holes = static_cast<int>(closed.caps.size());
  stats.dropped_components = closed.dropped_components;
  stats.mean_radius = closed.mean_radius();
  stats.repairs = closed.repairs;
  check_millimetres(stats.mean_radius);
  // Edge length tied to the radius, but never so short that MCF gets more than
  // `max_skeleton_faces` (an equilateral triangle of edge e has area 0.433 e^2).
  const double finest = std::sqrt(closed.area / (0.433 * std::max(1000, opt.max_skeleton_faces)));
  const double edge = std::max(stats.mean_radius / opt.edges_per_radius, finest);
  stats.seconds_prepare = seconds_since(t0);

  // 3-4. MCF skeleton of the remeshed surface, cleaned into a tree of chains; the wall of the
  // (un-remeshed) closed input is the reference.
  const VesselWall wall(closed.mesh);
  SkeletonTree tree = skeleton_tree(closed, opt, wall, edge, finest, stats);
  t0 = std::chrono::steady_clock::now();

  // 6 (before 5: refinement does not depend on direction). Terminal ends are free.
  const RefinedTree refined = refine_tree(tree, wall, opt, stats);
  // 5. Inlet, then the walk from it.
  const int inlet_node = choose_inlet(tree, refined, opt);
  CenterlineGraph g = walk_from_inlet(tree, refined, inlet_node, opt);
  set_inlet(g, opt);
  number_targets(g);
  stats.seconds_graph = seconds_since(t0);
  if (stats_out) *stats_out = stats;
  return g;
}

}  // namespace gw
