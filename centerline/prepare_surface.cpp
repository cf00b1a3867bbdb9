#include "centerline/prepare_surface.hpp"

#include "base/util/fixed_digits.hpp"
#include "centerline/alpha_wrap_surface.hpp"
#include "centerline/smooth_staircase.hpp"
#include "centerline/vessel_scale.hpp"

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Random.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Edge_length_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Midpoint_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <array>
#include <cstdint>
#include <unordered_map>
#include <chrono>
#include <iterator>
#include <set>
#include <sstream>
#include <cmath>
#include <algorithm>
#include <stdexcept>

namespace gw {
namespace {

using K = CGAL::Simple_cartesian<double>;
using Point = K::Point_3;
using SMesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;
constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d to_eigen(const Point& p) { return {p.x(), p.y(), p.z()}; }

// Direct halfedge construction; false when a face would make the mesh non-manifold or
// repeats an index (the soup path below then repairs it).
bool build_directly(const TriangleMesh& mesh, SMesh& sm) {
  std::vector<SMesh::Vertex_index> vertex;
  vertex.reserve(static_cast<size_t>(mesh.V.rows()));
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    vertex.push_back(sm.add_vertex(Point(mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2))));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    const int n = static_cast<int>(mesh.V.rows());
    if (a < 0 || b < 0 || c < 0 || a >= n || b >= n || c >= n || a == b || b == c || a == c) return false;
    if (sm.add_face(vertex[a], vertex[b], vertex[c]) == SMesh::null_face()) return false;
  }
  // Isolated vertices would make later steps fail; a clean surface has none.
  for (auto v : sm.vertices())
    if (sm.is_isolated(v)) return false;
  return true;
}

// The faces as a polygon soup, repaired (duplicate/degenerate faces), oriented consistently and
// with non-manifold joins split by duplicating their vertices. Counts what it changed.
SMesh soup_to_surface_mesh(const TriangleMesh& mesh, long* split_vertices = nullptr) {
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> faces;
  points.reserve(static_cast<size_t>(mesh.V.rows()));
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) points.emplace_back(mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    std::array<std::size_t, 3> face;
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.F(f, k);
      if (v < 0 || v >= mesh.V.rows()) throw std::runtime_error("face " + std::to_string(f) + " has an invalid vertex index");
      face[k] = static_cast<std::size_t>(v);
    }
    faces.push_back(face);
  }
  // Soup repair first: STL exports carry duplicate and degenerate faces; orienting the
  // soup duplicates vertices shared by several sheets so the result is a 2-manifold.
  PMP::repair_polygon_soup(points, faces);
  const std::size_t before = points.size();
  PMP::orient_polygon_soup(points, faces);
  if (split_vertices) *split_vertices = static_cast<long>(points.size() - before);
  SMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, faces, sm);
  return sm;
}

SMesh to_surface_mesh(const TriangleMesh& mesh) {
  SMesh sm;
  if (build_directly(mesh, sm)) return sm;
  return soup_to_surface_mesh(mesh);
}

// Vertex clustering (Rossignac-Borrel): every vertex moves to the mean of the vertices in its grid
// cell of side `cell`; faces whose corners fall into fewer than three cells disappear.
TriangleMesh cluster_vertices(const TriangleMesh& mesh, double cell) {
  const Eigen::RowVector3d origin = mesh.V.colwise().minCoeff();
  std::unordered_map<std::uint64_t, int> cluster_of_cell;
  std::vector<int> cluster(static_cast<size_t>(mesh.V.rows()));
  std::vector<Eigen::Vector3d> sum;
  std::vector<int> count;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const Eigen::RowVector3d q = (mesh.V.row(v) - origin) / cell;
    const std::uint64_t key = (static_cast<std::uint64_t>(q.x()) << 42) ^ (static_cast<std::uint64_t>(q.y()) << 21) ^
                              static_cast<std::uint64_t>(q.z());
    auto [it, fresh] = cluster_of_cell.emplace(key, static_cast<int>(sum.size()));
    if (fresh) sum.emplace_back(Eigen::Vector3d::Zero()), count.push_back(0);
    cluster[static_cast<size_t>(v)] = it->second;
    sum[static_cast<size_t>(it->second)] += mesh.V.row(v).transpose();
    ++count[static_cast<size_t>(it->second)];
  }
  TriangleMesh out;
  out.V.resize(static_cast<Eigen::Index>(sum.size()), 3);
  for (size_t c = 0; c < sum.size(); ++c) out.V.row(static_cast<Eigen::Index>(c)) = (sum[c] / count[c]).transpose();
  std::vector<Eigen::Vector3i> faces;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const int a = cluster[static_cast<size_t>(mesh.F(f, 0))], b = cluster[static_cast<size_t>(mesh.F(f, 1))],
              c = cluster[static_cast<size_t>(mesh.F(f, 2))];
    if (a != b && b != c && a != c) faces.emplace_back(a, b, c);
  }
  out.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) out.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  return out;
}

TriangleMesh to_triangle_mesh(const SMesh& sm) {
  TriangleMesh out;
  out.V.resize(static_cast<Eigen::Index>(sm.number_of_vertices()), 3);
  out.F.resize(static_cast<Eigen::Index>(sm.number_of_faces()), 3);
  std::vector<int> index(sm.num_vertices(), -1);
  int n = 0;
  for (auto v : sm.vertices()) {
    index[v.idx()] = n;
    out.V.row(n++) = to_eigen(sm.point(v)).transpose();
  }
  int f = 0;
  for (auto face : sm.faces()) {
    int k = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(face), sm)) out.F(f, k++) = index[v.idx()];
    ++f;
  }
  return out;
}

}  // namespace

namespace {

double face_area(const SMesh& sm, SMesh::Face_index f) {
  return std::sqrt(CGAL::to_double(CGAL::squared_area(sm.point(sm.source(sm.halfedge(f))),
                                                      sm.point(sm.target(sm.halfedge(f))),
                                                      sm.point(sm.target(sm.next(sm.halfedge(f)))))));
}


// Stage "islands": drops pieces below the area share; returns how many pieces remain.
int drop_islands(SMesh& sm, const SurfaceRepairOptions& o, ClosedSurface& out) {
  auto component = sm.add_property_map<SMesh::Face_index, std::size_t>("f:gw_component", 0).first;
  const std::size_t n = PMP::connected_components(sm, component);
  std::vector<double> area(n, 0.0);
  std::vector<long> faces(n, 0);
  for (auto f : sm.faces()) area[component[f]] += face_area(sm, f), ++faces[component[f]];
  const double largest = *std::max_element(area.begin(), area.end());
  std::vector<bool> keep(n, false);
  int kept = 0;
  for (std::size_t c = 0; c < n; ++c) {
    keep[c] = area[c] >= o.island_area_fraction * largest && area[c] > 0;
    if (keep[c]) ++kept;
    else {
      ++out.dropped_components;
      out.dropped_faces += faces[c];
      out.largest_dropped_area = std::max(out.largest_dropped_area, area[c]);
    }
  }
  if (out.dropped_components > 0) {
    std::vector<SMesh::Face_index> drop;
    for (auto f : sm.faces())
      if (!keep[component[f]]) drop.push_back(f);
    for (auto f : drop) CGAL::Euler::remove_face(sm.halfedge(f), sm);
    sm.collect_garbage();
    out.repairs.push_back("dropped " + std::to_string(out.dropped_components) + " island(s) of " +
                          std::to_string(out.dropped_faces) + " faces in all (largest " +
                          fixed_digits(out.largest_dropped_area) + " mm^2, the vessel " + fixed_digits(largest, 0) + " mm^2)");
  }
  sm.remove_property_map(component);
  return kept;
}

// Stage "cap": closes every boundary loop; round loops are recorded as open vessel ends.
void cap_holes(SMesh& sm, ClosedSurface& out) {
  std::vector<SMesh::Halfedge_index> holes;
  std::vector<bool> round;  // per hole: an open vessel end
  std::set<SMesh::Halfedge_index> seen;
  for (auto h : sm.halfedges()) {
    if (!sm.is_border(h) || seen.count(h)) continue;
    std::vector<Eigen::Vector3d> loop;
    auto g = h;
    do {
      seen.insert(g);
      loop.push_back(to_eigen(sm.point(sm.target(g))));
      g = sm.next(g);
    } while (g != h);
    holes.push_back(h);
    SurfaceCap cap;
    for (const auto& p : loop) cap.centre += p;
    cap.centre /= double(loop.size());
    Eigen::Vector3d area_vector = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < loop.size(); ++i) {
      cap.radius += (loop[i] - cap.centre).norm();
      area_vector += 0.5 * (loop[i] - cap.centre).cross(loop[(i + 1) % loop.size()] - cap.centre);
    }
    cap.radius /= double(loop.size());
    // An open vessel end is a roundish planar loop; a slit left by a split non-manifold join or a
    // crack encloses almost no area and is no terminal.
    round.push_back(loop.size() >= 5 && cap.radius > 0 && area_vector.norm() > 0.5 * kPi * cap.radius * cap.radius);
    if (round.back()) {
      cap.normal = area_vector.normalized();
      out.caps.push_back(cap);
    }
  }
  for (size_t k = 0; k < holes.size(); ++k) {
    const auto h = holes[k];
    std::vector<SMesh::Face_index> patch;
    // Only the planar (2D constrained Delaunay) filling: the 3D Delaunay search loops forever on
    // some ragged cut ends with this inexact kernel, and the cubic search takes minutes on loops of
    // a few hundred edges. What they would have filled gets a fan around the centroid instead.
    PMP::triangulate_hole(sm, h, std::back_inserter(patch),
                          PMP::parameters::use_delaunay_triangulation(false).do_not_use_cubic_algorithm(true));
    if (sm.is_border(h)) {
      // A fan around a new centroid vertex always closes a loop topologically. On a round vessel end
      // it is a fine cap; on any other loop (a seam left by split non-manifold joins) its shape is
      // makeshift and the wrap stage rebuilds the surface.
      CGAL::Euler::fill_hole(h, sm);
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      int corners = 0;
      for (auto v : CGAL::vertices_around_face(h, sm)) c += to_eigen(sm.point(v)), ++corners;
      c /= std::max(1, corners);
      const auto centre = CGAL::Euler::add_center_vertex(h, sm);
      sm.point(sm.target(centre)) = Point(c.x(), c.y(), c.z());
      if (round[k]) ++out.fan_end_caps;
      else ++out.fan_caps;
    }
  }
  if (!holes.empty())
    out.repairs.push_back("capped " + std::to_string(holes.size()) + " open boundary loop(s), " +
                          std::to_string(out.caps.size()) + " of them round vessel ends" +
                          (out.fan_caps ? ", " + std::to_string(out.fan_caps) + " other(s) only with a makeshift fan" : std::string()));
}

// Every piece of a closed mesh with outward normals (per piece: pieces may nest or overlap).
void orient_pieces_outward(SMesh& sm) {
  auto component = sm.add_property_map<SMesh::Face_index, std::size_t>("f:gw_piece", 0).first;
  const std::size_t n = PMP::connected_components(sm, component);
  std::vector<double> volume(n, 0.0);
  for (auto f : sm.faces()) {
    auto h = sm.halfedge(f);
    const Eigen::Vector3d a = to_eigen(sm.point(sm.source(h))), b = to_eigen(sm.point(sm.target(h))),
                          c = to_eigen(sm.point(sm.target(sm.next(h))));
    volume[component[f]] += a.dot(b.cross(c)) / 6.0;
  }
  for (std::size_t c = 0; c < n; ++c) {
    if (volume[c] >= 0) continue;
    std::vector<SMesh::Face_index> piece;
    for (auto f : sm.faces())
      if (component[f] == c) piece.push_back(f);
    PMP::reverse_face_orientations(piece, sm);
  }
  sm.remove_property_map(component);
}

// Stage "build": the input as a halfedge mesh, through the soup repair (recorded in `out`) when its
// faces do not form one consistently oriented 2-manifold.
SMesh build_surface(const TriangleMesh& mesh, ClosedSurface& out) {
  SMesh sm;
  if (!build_directly(mesh, sm)) {
    sm = soup_to_surface_mesh(mesh, &out.split_vertices);
    out.soup_repaired = true;
    out.repairs.push_back("faces did not form one consistently oriented 2-manifold: soup repaired and reoriented" +
                          (out.split_vertices ? ", " + std::to_string(out.split_vertices) +
                                                    " vertices duplicated to split non-manifold joins"
                                              : std::string()));
  }
  if (sm.number_of_faces() == 0) throw std::runtime_error("the surface has no usable faces");
  return sm;
}

// Stage "wrap": a surface of several pieces or with makeshift fan caps (or any, when asked for)
// becomes its alpha wrap, in `sm` and out.mesh; throws when it needs one and wrapping is off.
void wrap_if_needed(SMesh& sm, const SurfaceRepairOptions& options, ClosedSurface& out) {
  const bool wrap = options.force_wrap || out.kept_pieces > 1 || out.fan_caps > 0;
  if (wrap) {
    const std::string why = options.force_wrap      ? "asked for"
                            : out.kept_pieces > 1 ? std::to_string(out.kept_pieces) + " separate vessel-sized pieces"
                                                  : "holes only a fan could close";
    if (!options.allow_wrap)
      throw std::runtime_error("the surface needs alpha wrapping (" + why + ") and wrapping is off");
    orient_pieces_outward(sm);
    const TriangleMesh soup = to_triangle_mesh(sm);
    const VesselScale scale = estimate_vessel_scale(soup);
    out.wrap_scale_radius = scale.small_radius;
    out.wrap_alpha = options.wrap_alpha_factor * scale.small_radius;
    out.wrap_offset = options.wrap_offset_factor * scale.small_radius;
    out.mesh = alpha_wrap_surface(soup, out.wrap_alpha, out.wrap_offset);
    out.wrapped = true;
    out.repairs.push_back("alpha-wrapped (" + why + "): alpha " + fixed_digits(out.wrap_alpha, 3) + ", offset " +
                          fixed_digits(out.wrap_offset, 3) + " (thin vessels' radius " + fixed_digits(scale.small_radius, 3) + ")");
    sm = to_surface_mesh(out.mesh);
  }
}

// Stage "orient". Border halfedges of an outward-oriented surface run counter-clockwise seen from
// outside the hole, so the loop's area vector points out of the vessel; flip the cap normals
// with the surface when it had to be reversed.
void orient_outward(SMesh& sm, ClosedSurface& out) {
  if (PMP::volume(sm) < 0) {
    PMP::reverse_face_orientations(sm);
    for (auto& cap : out.caps) cap.normal = -cap.normal;
    if (!out.wrapped) {
      out.flipped = true;
      out.repairs.push_back("normals pointed into the lumen: reversed");
    }
  }
}

// Stage "smooth": out.mesh from `sm`; a voxel staircase (marching cubes of a binary label map) breaks
// every round-section fit of the centerline and snags the wire; Taubin smoothing removes it and keeps
// the tube. Then out.volume and out.area, which must be positive.
void smooth_and_measure(SMesh& sm, const SurfaceRepairOptions& options, ClosedSurface& out) {
  out.mesh = to_triangle_mesh(sm);
  out.lattice_share = lattice_area_share(out.mesh);
  if (out.lattice_share > options.staircase_share && options.staircase_passes > 0) {
    out.mesh = taubin_smooth(out.mesh, options.staircase_passes);
    sm = to_surface_mesh(out.mesh);  // same vertex and face order: volume and area of the smoothed surface
    out.smoothed = true;
    out.repairs.push_back("voxel staircase (" + fixed_digits(100.0 * out.lattice_share, 0) +
                          "% of the area faces lattice directions): Taubin-smoothed, " +
                          std::to_string(options.staircase_passes) + " passes");
  }
  out.volume = PMP::volume(sm);
  out.area = PMP::area(sm);
  if (!(out.volume > 0) || !(out.area > 0)) throw std::runtime_error("the surface encloses no volume (a single open sheet?)");
}

}  // namespace

ClosedSurface close_surface(const TriangleMesh& mesh, const SurfaceRepairOptions& options) {
  if (mesh.F.rows() == 0) throw std::runtime_error("the surface has no faces");
  if (!mesh.V.allFinite()) throw std::runtime_error("the surface has non-finite vertex coordinates");
  ClosedSurface out;
  auto t0 = std::chrono::steady_clock::now();
  auto lap = [&](const char* stage) {
    const auto t = std::chrono::steady_clock::now();
    out.stage_seconds.emplace_back(stage, std::chrono::duration<double>(t - t0).count());
    t0 = t;
  };

  SMesh sm = build_surface(mesh, out);
  lap("build");
  // islands
  out.kept_pieces = drop_islands(sm, options, out);
  if (sm.number_of_faces() < 4) throw std::runtime_error("the surface has fewer than 4 usable faces");
  lap("islands");
  // cap
  cap_holes(sm, out);
  if (!CGAL::is_closed(sm) || !CGAL::is_triangle_mesh(sm))
    throw std::runtime_error("the surface cannot be closed into a triangle 2-manifold (holes that cannot be capped)");
  lap("cap");
  wrap_if_needed(sm, options, out);
  lap("wrap");
  orient_outward(sm, out);
  lap("orient");
  smooth_and_measure(sm, options, out);
  lap("smooth");
  return out;
}

TriangleMesh remesh_surface(const TriangleMesh& closed, double edge_length, int iterations) {
  if (!(edge_length > 0)) throw std::runtime_error("remeshing needs a positive edge length");
  CGAL::get_default_random() = CGAL::Random(0);  // deterministic output, whatever ran before
  double area = 0.0;
  for (Eigen::Index f = 0; f < closed.F.rows(); ++f) {
    const Eigen::Vector3d a = closed.V.row(closed.F(f, 0)), b = closed.V.row(closed.F(f, 1)), c = closed.V.row(closed.F(f, 2));
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  const double target_faces = area / (0.433 * edge_length * edge_length);
  SMesh sm;
  if (static_cast<double>(closed.F.rows()) > kClusterDecimationRatio * target_faces) {
    // Far denser than the target (a fine marching-cubes surface: 1M faces for 15k): shortest-edge
    // collapse costs about 15 us per input face, so vertices are first clustered on a grid of
    // half the target edge (linear time; the thinnest vessel keeps 4+ cells across its radius),
    // the soup repaired, and the collapse runs on the ~10x smaller result.
    sm = soup_to_surface_mesh(cluster_vertices(closed, 0.5 * edge_length));
    PMP::keep_largest_connected_components(sm, 1);
    sm.collect_garbage();
    // Clustering can pinch a few spots; the soup repair opens them into small holes: cap them.
    ClosedSurface scratch;
    cap_holes(sm, scratch);
    if (!CGAL::is_closed(sm) || !CGAL::is_triangle_mesh(sm) || sm.number_of_faces() < 4) sm = to_surface_mesh(closed);
  } else {
    sm = to_surface_mesh(closed);
  }
  {
    // A dense input (segmentations and generated anatomies come at a fraction of the
    // radius per edge) is first decimated by shortest-edge collapse, which is far cheaper
    // per removed edge than the remesher's collapse pass; the remesher then evens it out.
    namespace SMS = CGAL::Surface_mesh_simplification;
    SMS::edge_collapse(sm, SMS::Edge_length_stop_predicate<double>(0.5 * edge_length),
                       CGAL::parameters::get_cost(SMS::Edge_length_cost<SMesh>())
                           .get_placement(SMS::Midpoint_placement<SMesh>()));
    sm.collect_garbage();
  }
  // No projection back onto the input: it costs an AABB query per vertex per pass on
  // the (possibly dense) input, and MCF needs the shape, not sub-edge fidelity; every
  // measurement afterwards is taken on the original wall.
  PMP::isotropic_remeshing(faces(sm), edge_length, sm,
                           PMP::parameters::number_of_iterations(iterations).do_project(false));
  sm.collect_garbage();
  return to_triangle_mesh(sm);
}

}  // namespace gw
