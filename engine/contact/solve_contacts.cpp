#include "engine/contact/solve_contacts.hpp"

#include <algorithm>
#include <cmath>

namespace gw {

namespace {

const double kPenetrationRecovery = 0.3;  // fraction of a penetration removed per sub-step

// Translational 3x3 block of A^-1 between contact-node slots i and j.
const Eigen::Matrix3d& xblock(const ContactWorkspace& ws, int i, int j) {
  return ws.xtt[static_cast<std::size_t>(i) * ws.nodes.size() + j];
}

void build_inverse_blocks(const BlockTridiagonalFactor& f, ContactWorkspace& ws) {
  const int k = static_cast<int>(ws.nodes.size());
  if (static_cast<int>(ws.xtt.size()) < k * k) ws.xtt.resize(static_cast<std::size_t>(k) * k);
  if (static_cast<int>(ws.chain.size()) < k) ws.chain.resize(k);
  // chain[s] = (-G_{u_s}) ... (-G_{u_{s+1}-1}), so (A^-1)(u_a, u_b) = chain[a] ... chain[b-1] Sigma_{u_b}.
  for (int s = 0; s + 1 < k; ++s) {
    Mat6& t = ws.chain[s];
    t = -f.g[ws.nodes[s]];
    for (int j = ws.nodes[s] + 1; j < ws.nodes[s + 1]; ++j) t = (t * (-f.g[j])).eval();
  }
  Eigen::Matrix<double, 3, 6> q;
  for (int a = 0; a < k; ++a) {
    ws.xtt[static_cast<std::size_t>(a) * k + a] = ws.sigma[ws.nodes[a]].topLeftCorner<3, 3>();
    q = ws.chain[a].topRows<3>();
    for (int b = a + 1; b < k; ++b) {
      const Eigen::Matrix3d x = q * ws.sigma[ws.nodes[b]].leftCols<3>();
      ws.xtt[static_cast<std::size_t>(a) * k + b] = x;
      ws.xtt[static_cast<std::size_t>(b) * k + a] = x.transpose();
      if (b + 1 < k) q = (q * ws.chain[b]).eval();
    }
  }
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

ContactSolveResult solve_contact_impulses(const std::vector<ContactPoint>& contacts, double dt, double mu,
                                          int iterations, bool warm_start, ContactWorkspace& ws) {
  ContactSolveResult res;
  const int m = static_cast<int>(contacts.size());
  if (m == 0 || ws.nodes.empty()) return res;
  const int first_free = ws.first_free;
  // W = H A^-1 H^T, 3x3 block per contact pair; rows of a contact: (n, t1, t2).
  const int dim = 3 * m;
  if (ws.w.rows() < dim) {
    const int cap = std::max(dim, 2 * static_cast<int>(ws.w.rows()));
    ws.w.resize(cap, cap);
  }
  if (ws.bias.size() < dim) ws.bias.resize(ws.w.rows());
  if (ws.impulse.size() < dim) ws.impulse.conservativeResize(ws.w.rows());
  // Each contact's rows (n, t1, t2) and its nodes' blocks, looked up once.
  if (ws.basis.size() < static_cast<std::size_t>(m)) ws.basis.resize(m);
  for (int ci = 0; ci < m; ++ci) {
    ws.basis[ci].row(0) = contacts[ci].n.transpose();
    ws.basis[ci].row(1) = contacts[ci].t1.transpose();
    ws.basis[ci].row(2) = contacts[ci].t2.transpose();
  }
  Eigen::Matrix3d x, bx;
  for (int ci = 0; ci < m; ++ci) {
    const ContactPoint& c = contacts[ci];
    const int ca[2] = {ws.slot[c.node_a - first_free], c.node_b >= 0 ? ws.slot[c.node_b - first_free] : -1};
    const double cw[2] = {c.wa, c.wb};
    for (int di = ci; di < m; ++di) {
      const ContactPoint& d = contacts[di];
      const int da[2] = {ws.slot[d.node_a - first_free], d.node_b >= 0 ? ws.slot[d.node_b - first_free] : -1};
      const double dwt[2] = {d.wa, d.wb};
      x.setZero();
      for (int p = 0; p < 2; ++p) {
        if (ca[p] < 0) continue;
        for (int qn = 0; qn < 2; ++qn) {
          if (da[qn] < 0) continue;
          x.noalias() += (cw[p] * dwt[qn]) * xblock(ws, ca[p], da[qn]);
        }
      }
      bx.noalias() = ws.basis[ci] * x;
      const Eigen::Matrix3d wcd = bx * ws.basis[di].transpose();
      ws.w.block<3, 3>(3 * ci, 3 * di) = wcd;
      ws.w.block<3, 3>(3 * di, 3 * ci) = wcd.transpose();
    }
    const ContactPoint& cc = contacts[ci];
    const Eigen::Vector3d& vc = cc.v_free;
    // End-of-step normal velocity must keep the gap: gap / dt + n.(v_free + dv_c) >= 0.
    // A penetration (gap < 0) is pushed out over a few steps (Baumgarte factor), not in one: a full
    // one-step correction of a deep point throws soft parts of the wire across the vessel.
    const double gap_rate = cc.gap >= 0 ? cc.gap / dt : kPenetrationRecovery * cc.gap / dt;
    ws.bias.segment<3>(3 * ci) << gap_rate + cc.n.dot(vc), cc.t1.dot(vc), cc.t2.dot(vc);
  }

  // Projected Gauss-Seidel, warm-started with the caller's normal impulses.
  auto p = ws.impulse.head(dim);
  for (int ci = 0; ci < m; ++ci) {
    p[3 * ci] = warm_start ? std::max(0.0, p[3 * ci]) : 0.0;
    p.segment<2>(3 * ci + 1).setZero();  // tangent bases may have changed
  }
  const auto w = ws.w.topLeftCorner(dim, dim);
  for (int it = 0; it < iterations; ++it) {
    double change = 0, largest = 1e-300;
    for (int ci = 0; ci < m; ++ci) {
      const int r = 3 * ci;
      // W is symmetric: read its columns (contiguous in column-major storage) instead of its rows.
      const Eigen::Vector3d u = w.middleCols<3>(r).transpose() * p + ws.bias.segment<3>(r);
      const Eigen::Vector3d old = p.segment<3>(r);
      double pn = std::max(0.0, old[0] - u[0] / w(r, r));
      Eigen::Vector2d pt(old[1] - u[1] / w(r + 1, r + 1), old[2] - u[2] / w(r + 2, r + 2));
      const double limit = mu * pn;
      const double norm = pt.norm();
      if (norm > limit) pt *= (norm > 0 ? limit / norm : 0.0);
      p.segment<3>(r) << pn, pt;
      change = std::max(change, (p.segment<3>(r) - old).cwiseAbs().maxCoeff());
      largest = std::max(largest, p.segment<3>(r).cwiseAbs().maxCoeff());
    }
    res.iterations = it + 1;
    res.residual = change / largest;
    if (res.residual < 1e-6) break;
  }
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
