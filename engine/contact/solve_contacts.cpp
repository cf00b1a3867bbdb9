#include "engine/contact/solve_contacts.hpp"

#include <algorithm>
#include <cmath>

namespace gw {

namespace {

const double kPenetrationRecovery = 0.3;  // fraction of a penetration removed per sub-step

// Rows (n, t1, t2) of H on one node's (v, w) with friction at the wire surface p = x - r n: the surface
// point moves with v - r w x n, so a tangent row is (t^T, -r (n x t)^T); the normal row has no rotation.
Eigen::Matrix<double, 3, 6> surface_rows(const ContactPoint& c, double r) {
  Eigen::Matrix<double, 3, 6> j;
  j.row(0) << c.n.transpose(), 0, 0, 0;
  j.row(1) << c.t1.transpose(), -r * c.n.cross(c.t1).transpose();
  j.row(2) << c.t2.transpose(), -r * c.n.cross(c.t2).transpose();
  return j;
}

// Translational 3x3 block of A^-1 between contact-node slots i and j.
template <class Workspace>
auto& xblock(Workspace& ws, int i, int j) {
  return ws.xtt[static_cast<std::size_t>(i) * ws.nodes.size() + j];
}

// Full 6x6 block of A^-1 between contact-node slots i and j (friction with a lever arm only).
template <class Workspace>
auto& xblock6(Workspace& ws, int i, int j) {
  return ws.x66[static_cast<std::size_t>(i) * ws.nodes.size() + j];
}

// The chain products between consecutive contact nodes, and the blocks of A^-1 that every solve needs:
// each contact node with itself and with its neighbouring contact node (a midpoint's two nodes).
void build_inverse_blocks(const BlockTridiagonalFactor& f, ContactWorkspace& ws) {
  const int k = static_cast<int>(ws.nodes.size());
  if (static_cast<int>(ws.xtt.size()) < k * k) ws.xtt.resize(static_cast<std::size_t>(k) * k);
  if (static_cast<int>(ws.chain.size()) < k) ws.chain.resize(k);
  ws.x_built.assign(k, 0);
  // chain[s] = (-G_{u_s}) ... (-G_{u_{s+1}-1}), so (A^-1)(u_a, u_b) = chain[a] ... chain[b-1] Sigma_{u_b}.
  for (int s = 0; s + 1 < k; ++s) {
    Mat6& t = ws.chain[s];
    t = -f.g[ws.nodes[s]];
    for (int j = ws.nodes[s] + 1; j < ws.nodes[s + 1]; ++j) t = (t * (-f.g[j])).eval();
  }
  if (ws.lever > 0) {  // friction with a lever arm: H also touches the rotations, keep whole blocks
    if (static_cast<int>(ws.x66.size()) < k * k) ws.x66.resize(static_cast<std::size_t>(k) * k);
    for (int a = 0; a < k; ++a) {
      xblock6(ws, a, a) = ws.sigma[ws.nodes[a]];
      if (a + 1 < k) {
        const Mat6 x = ws.chain[a] * ws.sigma[ws.nodes[a + 1]];
        xblock6(ws, a, a + 1) = x;
        xblock6(ws, a + 1, a) = x.transpose();
      }
    }
    return;
  }
  for (int a = 0; a < k; ++a) {
    xblock(ws, a, a) = ws.sigma[ws.nodes[a]].topLeftCorner<3, 3>();
    if (a + 1 < k) {
      const Eigen::Matrix3d x = ws.chain[a].topRows<3>() * ws.sigma[ws.nodes[a + 1]].leftCols<3>();
      xblock(ws, a, a + 1) = x;
      xblock(ws, a + 1, a) = x.transpose();
    }
  }
}

// Blocks of A^-1 between contact node b and every other contact node: O(k) products, walked outwards
// from b. Only the nodes of contacts that press need them (see build_column), not all k^2 pairs.
void build_inverse_column(ContactWorkspace& ws, int b) {
  if (ws.x_built[b]) return;
  const int k = static_cast<int>(ws.nodes.size());
  if (ws.lever > 0) {  // the same walk with whole 6x6 blocks
    Mat6 right = ws.sigma[ws.nodes[b]];
    for (int a = b - 1; a >= 0; --a) {
      right = (ws.chain[a] * right).eval();
      xblock6(ws, a, b) = right;
      xblock6(ws, b, a) = right.transpose();
    }
    Mat6 left = ws.chain[b];
    for (int a = b + 1; a < k; ++a) {
      const Mat6 x = left * ws.sigma[ws.nodes[a]];
      xblock6(ws, b, a) = x;
      xblock6(ws, a, b) = x.transpose();
      if (a + 1 < k) left = (left * ws.chain[a]).eval();
    }
    ws.x_built[b] = 1;
    return;
  }
  Eigen::Matrix<double, 6, 3> right = ws.sigma[ws.nodes[b]].leftCols<3>();
  for (int a = b - 1; a >= 0; --a) {  // (A^-1)(u_a, u_b) = chain[a] ... chain[b-1] Sigma_b
    right = (ws.chain[a] * right).eval();
    xblock(ws, a, b) = right.topRows<3>();
    xblock(ws, b, a) = right.topRows<3>().transpose();
  }
  Eigen::Matrix<double, 3, 6> left = ws.chain[b].topRows<3>();
  for (int a = b + 1; a < k; ++a) {  // (A^-1)(u_b, u_a) = chain[b] ... chain[a-1] Sigma_a
    const Eigen::Matrix3d x = left * ws.sigma[ws.nodes[a]].leftCols<3>();
    xblock(ws, b, a) = x;
    xblock(ws, a, b) = x.transpose();
    if (a + 1 < k) left = (left * ws.chain[a]).eval();
  }
  ws.x_built[b] = 1;
}

}  // namespace

void prepare_contact_compliance(const BlockTridiagonal& a, const BlockTridiagonalFactor& f, int first_free,
                                const std::vector<ContactPoint>& contacts, ContactWorkspace& ws) {
  const int nf = a.size();
  for (int s : ws.nodes) ws.slot[s] = -1;  // forget the previous call's nodes
  ws.nodes.clear();
  ws.first_free = first_free;
  if (contacts.empty() || nf == 0) return;
  if (static_cast<int>(ws.slot.size()) < nf) ws.slot.resize(nf, -1);
  // Contact nodes (local indices), sorted and unique.
  for (const ContactPoint& c : contacts) {
    ws.nodes.push_back(c.node_a - first_free);
    if (c.node_b >= 0) ws.nodes.push_back(c.node_b - first_free);
  }
  std::sort(ws.nodes.begin(), ws.nodes.end());
  ws.nodes.erase(std::unique(ws.nodes.begin(), ws.nodes.end()), ws.nodes.end());
  for (std::size_t s = 0; s < ws.nodes.size(); ++s) ws.slot[ws.nodes[s]] = static_cast<int>(s);
  inverse_diagonal_blocks(f, ws.sigma);
  build_inverse_blocks(f, ws);
}

namespace {

// Block (c, d) of W = H A^-1 H^T: contact c's rows (n, t1, t2) against contact d's.
Eigen::Matrix3d compliance_block(const std::vector<ContactPoint>& contacts, const ContactWorkspace& ws, int ci,
                                 int di) {
  const ContactPoint& c = contacts[ci];
  const ContactPoint& d = contacts[di];
  const int ff = ws.first_free;
  const int ca[2] = {ws.slot[c.node_a - ff], c.node_b >= 0 ? ws.slot[c.node_b - ff] : -1};
  const int da[2] = {ws.slot[d.node_a - ff], d.node_b >= 0 ? ws.slot[d.node_b - ff] : -1};
  const double cw[2] = {c.wa, c.wb}, dw[2] = {d.wa, d.wb};
  if (ws.lever > 0) {  // J_c (sum of weighted 6x6 blocks) J_d^T
    Mat6 x6 = Mat6::Zero();
    for (int p = 0; p < 2; ++p) {
      if (ca[p] < 0) continue;
      for (int q = 0; q < 2; ++q)
        if (da[q] >= 0) x6.noalias() += (cw[p] * dw[q]) * xblock6(ws, ca[p], da[q]);
    }
    const Eigen::Matrix<double, 3, 6> jx = ws.jac[ci] * x6;
    return jx * ws.jac[di].transpose();
  }
  Eigen::Matrix3d x = Eigen::Matrix3d::Zero();
  for (int p = 0; p < 2; ++p) {
    if (ca[p] < 0) continue;
    for (int q = 0; q < 2; ++q)
      if (da[q] >= 0) x.noalias() += (cw[p] * dw[q]) * xblock(ws, ca[p], da[q]);
  }
  const Eigen::Matrix3d bx = ws.basis[ci] * x;
  return bx * ws.basis[di].transpose();
}

// Column block c of W (3 columns, every contact's rows), built the first time contact c's impulse changes.
void build_column(const std::vector<ContactPoint>& contacts, ContactWorkspace& ws, int ci) {
  const int m = static_cast<int>(contacts.size());
  const ContactPoint& c = contacts[ci];
  build_inverse_column(ws, ws.slot[c.node_a - ws.first_free]);
  if (c.node_b >= 0) build_inverse_column(ws, ws.slot[c.node_b - ws.first_free]);
  for (int di = 0; di < m; ++di)
    ws.w.block<3, 3>(3 * di, 3 * ci) = di == ci ? ws.w_diag[ci] : compliance_block(contacts, ws, di, ci);
  ws.column_built[ci] = 1;
}

// Sizes the solve's scratch for m contacts (dim = 3 m rows; grown, never shrunk) and marks every column of
// W as not built yet.
void size_solve_workspace(ContactWorkspace& ws, int m, int dim) {
  if (ws.w.rows() < dim) {
    const int cap = std::max(dim, 2 * static_cast<int>(ws.w.rows()));
    ws.w.resize(cap, cap);
  }
  if (ws.bias.size() < dim) ws.bias.resize(ws.w.rows());
  if (ws.u.size() < dim) ws.u.resize(ws.w.rows());
  if (ws.impulse.size() < dim) ws.impulse.conservativeResize(ws.w.rows());
  if (ws.basis.size() < static_cast<std::size_t>(m)) ws.basis.resize(m);
  if (ws.w_diag.size() < static_cast<std::size_t>(m)) ws.w_diag.resize(m);
  ws.column_built.assign(m, 0);
}

// Each contact's rows (n, t1, t2) into ws.basis and, with friction at the wire surface (ws.lever), its rows
// on the node's (v, w) into ws.jac.
void contact_rows(const std::vector<ContactPoint>& contacts, ContactWorkspace& ws, int m) {
  for (int ci = 0; ci < m; ++ci) {
    const ContactPoint& cc = contacts[ci];
    ws.basis[ci].row(0) = cc.n.transpose();
    ws.basis[ci].row(1) = cc.t1.transpose();
    ws.basis[ci].row(2) = cc.t2.transpose();
  }
  if (ws.lever > 0) {
    if (ws.jac.size() < static_cast<std::size_t>(m)) ws.jac.resize(m);
    for (int ci = 0; ci < m; ++ci) ws.jac[ci] = surface_rows(contacts[ci], ws.lever);
  }
}

// Per contact: its diagonal block of W into ws.w_diag and its free relative velocity with the gap's rate
// (sub-step dt) into ws.bias.
void diagonal_and_bias(const std::vector<ContactPoint>& contacts, double dt, ContactWorkspace& ws, int m) {
  for (int ci = 0; ci < m; ++ci) {
    const ContactPoint& cc = contacts[ci];
    ws.w_diag[ci] = compliance_block(contacts, ws, ci, ci);
    const Eigen::Vector3d vc = cc.v_free - cc.v_wall;  // relative to the wall (v_wall = 0: exactly v_free)
    // End-of-step normal velocity must keep the gap: gap / dt + n.(v_free + dv_c) >= 0.
    // A penetration (gap < 0) is pushed out over a few steps (Baumgarte factor), not in one: a full
    // one-step correction of a deep point throws soft parts of the wire across the vessel.
    const double gap_rate = cc.gap >= 0 ? cc.gap / dt : kPenetrationRecovery * cc.gap / dt;
    ws.bias.segment<3>(3 * ci) << gap_rate + cc.n.dot(vc), cc.t1.dot(vc), cc.t2.dot(vc);
    if (ws.lever > 0) ws.bias.segment<3>(3 * ci) += ws.jac[ci].rightCols<3>() * cc.w_free;  // surface slip
  }
}

// Starting impulses ws.impulse (the last solve's normal ones with `warm_start`, else zero; tangents zero)
// and u = W p + bias for them in ws.u.
void start_impulses(const std::vector<ContactPoint>& contacts, bool warm_start, ContactWorkspace& ws, int m,
                    int dim) {
  auto p = ws.impulse.head(dim);
  auto u = ws.u.head(dim);
  u = ws.bias.head(dim);
  for (int ci = 0; ci < m; ++ci) {
    p[3 * ci] = warm_start ? std::max(0.0, p[3 * ci]) : 0.0;
    p.segment<2>(3 * ci + 1).setZero();  // tangent bases may have changed
    if (p[3 * ci] != 0) {
      build_column(contacts, ws, ci);
      u.noalias() += ws.w.block(0, 3 * ci, dim, 1) * p[3 * ci];
    }
  }
}

// Projected Gauss-Seidel sweeps (at most `iterations`, friction coefficient mu) on ws.impulse and ws.u;
// the sweeps done and the last relative change into `res`.
void gauss_seidel_sweeps(const std::vector<ContactPoint>& contacts, double mu, int iterations, ContactWorkspace& ws,
                         int m, int dim, ContactSolveResult& res) {
  auto p = ws.impulse.head(dim);
  auto u = ws.u.head(dim);
  for (int it = 0; it < iterations; ++it) {
    double change = 0, largest = 1e-300;
    for (int ci = 0; ci < m; ++ci) {
      const int r = 3 * ci;
      // Not pressing and still separating: the projection keeps all three impulses at zero.
      if (p[r] == 0 && u[r] >= 0) continue;
      const Eigen::Matrix3d& wd = ws.w_diag[ci];
      const Eigen::Vector3d old = p.segment<3>(r);
      const double pn = std::max(0.0, old[0] - u[r] / wd(0, 0));
      Eigen::Vector2d pt(old[1] - u[r + 1] / wd(1, 1), old[2] - u[r + 2] / wd(2, 2));
      const double limit = mu * pn;
      const double norm = pt.norm();
      if (norm > limit) pt *= (norm > 0 ? limit / norm : 0.0);
      const Eigen::Vector3d delta = Eigen::Vector3d(pn, pt[0], pt[1]) - old;
      if (delta.isZero(0)) {
        largest = std::max(largest, old.cwiseAbs().maxCoeff());
        continue;
      }
      if (!ws.column_built[ci]) build_column(contacts, ws, ci);
      u.noalias() += ws.w.block(0, r, dim, 3) * delta;
      p.segment<3>(r) += delta;
      change = std::max(change, delta.cwiseAbs().maxCoeff());
      largest = std::max(largest, p.segment<3>(r).cwiseAbs().maxCoeff());
    }
    res.iterations = it + 1;
    res.residual = change / largest;
    if (res.residual < kContactSweepTolerance) break;
  }
}

}  // namespace

ContactSolveResult solve_contact_impulses(const std::vector<ContactPoint>& contacts, double dt, double mu,
                                          int iterations, bool warm_start, ContactWorkspace& ws) {
  ContactSolveResult res;
  const int m = static_cast<int>(contacts.size());
  if (m == 0 || ws.nodes.empty()) return res;
  const int dim = 3 * m;
  size_solve_workspace(ws, m, dim);
  contact_rows(contacts, ws, m);
  diagonal_and_bias(contacts, dt, ws, m);
  // Projected Gauss-Seidel on u = W p + bias, kept up to date column by column: most contacts found by
  // the swept margin never press (about 90% end a sub-step with zero impulse), their impulse never
  // changes, and neither their column of W nor the update u += W_c dp_c is ever computed. A sweep costs
  // O(m) plus O(m) per contact whose impulse moved, instead of O(m^2).
  start_impulses(contacts, warm_start, ws, m, dim);
  gauss_seidel_sweeps(contacts, mu, iterations, ws, m, dim, res);
  return res;
}

void contact_velocity_change(const BlockTridiagonal& a, const BlockTridiagonalFactor& f,
                             const std::vector<ContactPoint>& contacts, ContactWorkspace& ws) {
  const int nf = a.size();
  if (ws.h_t_p.size() < 6 * nf) ws.h_t_p.resize(6 * static_cast<Eigen::Index>(a.diag.size()));
  auto r = ws.h_t_p.head(6 * nf);
  r.setZero();
  const auto& p = ws.impulse;
  for (std::size_t ci = 0; ci < contacts.size(); ++ci) {
    const ContactPoint& c = contacts[ci];
    if (ws.lever > 0) {  // force and the friction's torque about the axis: J^T p
      const Vec6 gen = surface_rows(c, ws.lever).transpose() * p.segment<3>(3 * ci);
      r.segment<6>(6 * (c.node_a - ws.first_free)) += c.wa * gen;
      if (c.node_b >= 0) r.segment<6>(6 * (c.node_b - ws.first_free)) += c.wb * gen;
      continue;
    }
    const Eigen::Vector3d fimp = c.n * p[3 * ci] + c.t1 * p[3 * ci + 1] + c.t2 * p[3 * ci + 2];
    r.segment<3>(6 * (c.node_a - ws.first_free)) += c.wa * fimp;
    if (c.node_b >= 0) r.segment<3>(6 * (c.node_b - ws.first_free)) += c.wb * fimp;
  }
  if (nf > 0) solve_block_tridiagonal(a, f, r);
}

ContactSolveResult solve_contacts(const BlockTridiagonal& a, const BlockTridiagonalFactor& f, int first_free,
                                  const std::vector<ContactPoint>& contacts, double dt, double mu, int iterations,
                                  ContactWorkspace& ws, Eigen::Ref<Eigen::VectorXd> dv) {
  prepare_contact_compliance(a, f, first_free, contacts, ws);
  const ContactSolveResult res = solve_contact_impulses(contacts, dt, mu, iterations, false, ws);
  if (contacts.empty() || a.size() == 0) return res;
  contact_velocity_change(a, f, contacts, ws);
  dv.head(6 * a.size()) += ws.h_t_p.head(6 * a.size());
  return res;
}

}  // namespace gw
