#include "centerline/skeleton_tree.hpp"
#include "base/util/median.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <set>
#include <stdexcept>

#include "base/graph/centerline_graph.hpp"

namespace gw {

std::vector<int> SkeletonTree::degree() const {
  std::vector<int> deg(nodes.size(), 0);
  for (const auto& c : chains) ++deg[c.a], ++deg[c.b];
  return deg;
}

namespace {

struct Work {
  std::vector<Eigen::Vector3d> node;
  std::vector<SkeletonChain> chains;  // alive ones only (erased on removal)

  std::vector<int> degree() const {
    std::vector<int> deg(node.size(), 0);
    for (const auto& c : chains) ++deg[c.a], ++deg[c.b];
    return deg;
  }
};

// Walks the raw skeleton from every key node (degree != 2) along degree-2 nodes.
Work build_chains(const RawSkeleton& raw) {
  const int n = static_cast<int>(raw.nodes.size());
  std::vector<std::vector<int>> adj(n);
  std::set<std::pair<int, int>> unique_edges;
  for (auto [a, b] : raw.edges) {
    if (a == b || a < 0 || b < 0 || a >= n || b >= n) continue;
    if (unique_edges.insert({std::min(a, b), std::max(a, b)}).second) {
      adj[a].push_back(b);
      adj[b].push_back(a);
    }
  }
  Work w;
  for (const auto& node : raw.nodes) w.node.push_back(node.point);
  std::set<std::pair<int, int>> used;  // directed edges already walked
  for (int s = 0; s < n; ++s) {
    if (adj[s].size() == 2) continue;
    for (int first : adj[s]) {
      if (used.count({s, first})) continue;
      SkeletonChain c;
      c.a = s;
      c.points.push_back(w.node[s]);
      int prev = s, cur = first;
      used.insert({s, first});
      while (adj[cur].size() == 2 && cur != s) {
        c.points.push_back(w.node[cur]);
        const int next = adj[cur][0] == prev ? adj[cur][1] : adj[cur][0];
        used.insert({cur, next});
        used.insert({cur, prev});
        prev = cur;
        cur = next;
      }
      used.insert({cur, prev});
      c.points.push_back(w.node[cur]);
      c.b = cur;
      w.chains.push_back(std::move(c));
    }
  }
  return w;
}

bool prune_one_spur(Work& w, const std::function<double(const Eigen::Vector3d&)>& radius_at,
                    const std::vector<Eigen::Vector3d>& caps, const SkeletonCleanup& o) {
  const auto deg = w.degree();
  // Terminal chains: which cap (open end) each one ends at, -1 for none. A capped end is a real
  // terminal and survives the length rule, but one cap is one outlet: when MCF forks just before a
  // noisy cap, both prongs end "at the cap" and all but the longest are spurs.
  struct Terminal {
    size_t chain;
    int cap;
    double length, radius;
  };
  std::vector<Terminal> terminals;
  for (size_t i = 0; i < w.chains.size(); ++i) {
    const auto& c = w.chains[i];
    const bool end_a = deg[c.a] == 1, end_b = deg[c.b] == 1;
    if (end_a == end_b) continue;  // not a terminal chain (or an isolated segment)
    const int junction = end_a ? c.b : c.a, terminal = end_a ? c.a : c.b;
    if (deg[junction] < 3) continue;
    const double r = radius_at(w.node[junction]);
    int cap = -1;
    for (size_t k = 0; k < caps.size() && cap < 0; ++k)
      if ((caps[k] - w.node[terminal]).norm() < o.cap_factor * std::max(r, radius_at(w.node[terminal])))
        cap = static_cast<int>(k);
    terminals.push_back({i, cap, polyline_length(c.points), r});
  }
  int best = -1;
  double best_length = std::numeric_limits<double>::infinity();
  for (const Terminal& t : terminals) {
    if (t.length >= best_length) continue;
    bool spur = t.cap < 0 && t.length < o.spur_factor * t.radius;
    if (t.cap >= 0)
      spur = std::any_of(terminals.begin(), terminals.end(), [&](const Terminal& u) {
        return u.chain != t.chain && u.cap == t.cap && (u.length > t.length || (u.length == t.length && u.chain < t.chain));
      });
    if (!spur) continue;
    best = static_cast<int>(t.chain);
    best_length = t.length;
  }
  if (best < 0) return false;
  w.chains.erase(w.chains.begin() + best);
  return true;
}

// The radius of the thinnest arm at junction v but chain `link`: each arm's median wall distance over
// its points `from`..`to` away from v (past the lumen the junction sits in; an arm that never gets that
// far: its far end's).
double thinnest_raw_arm(const Work& w, int v, size_t link, double from, double to,
                          const std::function<double(const Eigen::Vector3d&)>& radius_at) {
  double thinnest = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < w.chains.size(); ++i) {
    const auto& c = w.chains[i];
    if (i == link || (c.a != v && c.b != v)) continue;
    std::vector<double> r;
    for (const auto& p : c.points) {
      const double d = (p - w.node[v]).norm();
      if (d >= from && d <= to) r.push_back(radius_at(p));
    }
    if (r.empty()) r.push_back(radius_at(c.a == v ? c.points.back() : c.points.front()));
    thinnest = std::min(thinnest, median(r));
  }
  return thinnest;
}

bool merge_one_junction_pair(Work& w, const std::function<double(const Eigen::Vector3d&)>& radius_at,
                             const SkeletonCleanup& o) {
  const auto deg = w.degree();
  int best = -1;
  double best_length = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < w.chains.size(); ++i) {
    const auto& c = w.chains[i];
    if (c.a == c.b || deg[c.a] < 3 || deg[c.b] < 3) continue;
    const double length = polyline_length(c.points);
    const Eigen::Vector3d mid = 0.5 * (w.node[c.a] + w.node[c.b]);
    const double r = radius_at(mid);
    if (length >= o.merge_factor * r || length >= best_length) continue;
    // Two thin side branches of a wide vessel (the great vessels off the aortic arch) can leave closer
    // than the vessel's radius and still be two openings: they are one junction only when their
    // openings overlap, as merge_close_junctions decides once the junctions are re-centred.
    const double thin_a = thinnest_raw_arm(w, c.a, i, r, 3 * r, radius_at);
    const double thin_b = thinnest_raw_arm(w, c.b, i, r, 3 * r, radius_at);
    if (length >= o.merge_factor * (thin_a + thin_b)) continue;
    best = static_cast<int>(i);
    best_length = length;
  }
  if (best < 0) return false;
  const SkeletonChain c = w.chains[best];
  w.chains.erase(w.chains.begin() + best);
  // The merged centre is the middle of the short chain; every chain that met either
  // end now starts exactly there.
  const Eigen::Vector3d centre = 0.5 * (w.node[c.a] + w.node[c.b]);
  w.node[c.a] = centre;
  for (auto& d : w.chains) {
    if (d.a == c.b) d.a = c.a;
    if (d.b == c.b) d.b = c.a;
    if (d.a == c.a) d.points.front() = centre;
    if (d.b == c.a) d.points.back() = centre;
  }
  return true;
}

bool join_one_pass_through(Work& w) {
  const auto deg = w.degree();
  for (size_t v = 0; v < w.node.size(); ++v) {
    if (deg[v] != 2) continue;
    std::vector<size_t> at;
    for (size_t i = 0; i < w.chains.size(); ++i)
      if (w.chains[i].a == static_cast<int>(v) || w.chains[i].b == static_cast<int>(v)) at.push_back(i);
    if (at.size() != 2) continue;  // a self-loop through v
    SkeletonChain x = w.chains[at[0]], y = w.chains[at[1]];
    if (x.b != static_cast<int>(v)) std::reverse(x.points.begin(), x.points.end()), std::swap(x.a, x.b);
    if (y.a != static_cast<int>(v)) std::reverse(y.points.begin(), y.points.end()), std::swap(y.a, y.b);
    x.points.insert(x.points.end(), y.points.begin() + 1, y.points.end());
    x.b = y.b;
    w.chains.erase(w.chains.begin() + static_cast<long>(at[1]));
    w.chains[at[0]] = std::move(x);
    return true;
  }
  return false;
}

// Keeps a spanning forest: drops self-loops and any chain whose ends are already joined.
void cut_cycles(Work& w) {
  std::vector<int> parent(w.node.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  // Longest chains first: a cycle is cut at its shortest chain (a junction artefact).
  std::stable_sort(w.chains.begin(), w.chains.end(), [](const SkeletonChain& a, const SkeletonChain& b) {
    return polyline_length(a.points) > polyline_length(b.points);
  });
  std::vector<SkeletonChain> kept;
  for (auto& c : w.chains) {
    const int ra = find(c.a), rb = find(c.b);
    if (ra == rb) continue;
    parent[ra] = rb;
    kept.push_back(std::move(c));
  }
  w.chains = std::move(kept);
}

}  // namespace

bool SkeletonTree::at_known_end(const Eigen::Vector3d& p) const {
  return std::any_of(known_ends.begin(), known_ends.end(),
                     [&](const SurfaceCap& e) { return (p - e.centre).norm() < 2.0 * e.radius; });
}

SkeletonTree clean_skeleton(const RawSkeleton& raw, const std::function<double(const Eigen::Vector3d&)>& radius_at,
                            const std::vector<Eigen::Vector3d>& caps, const SkeletonCleanup& o) {
  Work w = build_chains(raw);
  if (w.chains.empty()) throw std::runtime_error("the skeleton is a closed loop with no end (a torus-like surface?)");
  for (bool changed = true; changed;) {
    cut_cycles(w);
    changed = prune_one_spur(w, radius_at, caps, o) || merge_one_junction_pair(w, radius_at, o) ||
              join_one_pass_through(w);
  }
  // Renumber the key nodes still used by a chain (the skeleton of one closed surface is
  // connected, and pruning only removes terminal chains, so the tree stays connected).
  SkeletonTree tree;
  std::vector<int> index(w.node.size(), -1);
  for (const auto& c : w.chains)
    for (int v : {c.a, c.b})
      if (index[v] < 0) {
        index[v] = static_cast<int>(tree.nodes.size());
        tree.nodes.push_back(w.node[v]);
      }
  for (auto c : w.chains) {
    c.a = index[c.a];
    c.b = index[c.b];
    tree.chains.push_back(std::move(c));
  }
  return tree;
}

}  // namespace gw
