#include "engine/sim/assemble_system.hpp"

#include "engine/wire/node_rotational_inertia.hpp"

namespace gw {

namespace {

using Mat12x6 = Eigen::Matrix<double, 12, 6>;

// Element stiffness (scaled by s = dt beta + dt^2) and right-hand side contribution
// dt f_e - s K_e v_e. `held_a` adds the introducer coupling -s K_ba dv_H to the b rows.
struct ElementLinearisation {
  Mat12 k;
  Vec12 rhs;
};

// The element's force resultant n = (EA, kGA, kGA) Gamma [mN] turns with its chord: a string's stiffness
// |n| / l (I - t t^T) on the ends' translations (t the chord's direction), added to K for both signs of n.
// The Gauss-Newton K leaves this geometric part out, so a wire loaded hard (a tip pushed into a jam at
// 10-100 N) met it explicitly and chattered: a 0.5 mm tip element at 10 N has |n| / l = 2e4 mN/mm against a
// half-element mass of 1.6e-7 kg, stable explicitly below ~6 us. Added to both sides of the linearised
// step (to A and to the -s K v of the right-hand side), it is a force -(beta + dt) |n| / l (I - t t^T) v_new
// on the ends' relative transverse velocity: no change to any static equilibrium, damping where the wire is
// loaded. In compression it is the true geometric stiffness with its sign turned (which would make A
// indefinite), so it over-damps there; docs/physics.md "A jammed wire" has its measured effect.
void add_resultant_stiffness(const WireState& st, int e, const Vec6& c, const BeamElementEval& ev, double s, Mat12& k) {
  const double resultant = Eigen::Vector3d(c[0] * ev.strain[0], c[1] * ev.strain[1], c[2] * ev.strain[2]).norm();
  const Eigen::Vector3d chord = st.x[e + 1] - st.x[e];
  const double len = chord.norm();
  const Eigen::Vector3d t = chord / len;
  const Eigen::Matrix3d pk = (s * resultant / len) * (Eigen::Matrix3d::Identity() - t * t.transpose());
  k.block<3, 3>(0, 0) += pk;
  k.block<3, 3>(6, 6) += pk;
  k.block<3, 3>(0, 6) -= pk;
  k.block<3, 3>(6, 0) -= pk;
}

void linearise_element(const WireModel& model, const WireState& st, int e, const BeamElementEval& ev,
                       const Vec6& held_dv, bool held_a, double dt, ElementLinearisation& out) {
  const double s = dt * model.params.damping_stiffness + dt * dt;
  const double l = model.length[e];
  const Vec6& c = model.stiffness[e];
  Mat12x6 jtc = ev.jac.transpose();
  for (int r = 0; r < 6; ++r) jtc.col(r) *= c[r];
  out.k.noalias() = (s * l) * jtc.lazyProduct(ev.jac);  // small fixed sizes: skip the GEMM kernel
  Vec12 ve;
  ve << st.v[e], st.w[e], st.v[e + 1], st.w[e + 1];
  out.rhs.noalias() = (-dt * l) * jtc * ev.strain;  // dt * force
  add_resultant_stiffness(st, e, c, ev, s, out.k);
  out.rhs.noalias() -= out.k * ve;
  if (held_a) out.rhs.tail<6>().noalias() -= out.k.block<6, 6>(6, 0) * held_dv;
}

Vec6 held_velocity_change(const WireState& st, int h, double push, double rotate) {
  Vec6 dv;
  dv << push * st.direction - st.v[h], rotate * st.direction - st.w[h];
  return dv;
}

// `inertia`: the node's rotational inertia tensor (per-axis model), or null for the paper's model
// (rho J about every axis, model.rot_inertia[i]).
Vec6 node_rhs(const WireModel& model, const WireState& st, int i, double dt, const Eigen::Matrix3d* inertia) {
  const double alpha = model.params.damping_mass;
  Vec6 r;
  if (!inertia) {
    r << dt * st.external_force[i] - dt * alpha * model.mass[i] * st.v[i],
        dt * st.external_torque[i] - dt * alpha * model.rot_inertia[i] * st.w[i];
    return r;
  }
  // Per-axis tensor: Euler's equations in the world frame, I dw/dt = torque - w x (I w) (explicit).
  const Eigen::Vector3d iw = *inertia * st.w[i];
  r << dt * st.external_force[i] - dt * alpha * model.mass[i] * st.v[i],
      dt * st.external_torque[i] - dt * alpha * iw - dt * st.w[i].cross(iw);
  return r;
}

}  // namespace

void assemble_system(const WireModel& model, const WireState& st, double push, double rotate, double h,
                     DynamicsSystem& sys) {
  const int n = model.nodes;
  const int k = first_free_node(model, st);
  const int nf = n - k;
  sys.first_free = k;
  sys.a.resize(nf);
  if (sys.rhs.size() < 6 * nf) sys.rhs.resize(6 * model.nodes);
  sys.rhs.head(6 * nf).setZero();
  if (static_cast<int>(sys.rot.size()) < n) sys.rot.resize(n);
  if (static_cast<int>(sys.elem.size()) < n) sys.elem.resize(n);
  sys.elastic_energy = 0;
  if (nf == 0) return;

  for (int i = k - 1; i < n; ++i) sys.rot[i] = st.q[i].toRotationMatrix();
  const double dt = h;
  const double mscale = 1.0 + dt * model.params.damping_mass;
  for (int i = k; i < n; ++i) {
    Mat6& d = sys.a.diag[i - k];
    d.diagonal().head<3>().setConstant(mscale * model.mass[i]);
    if (model.params.per_axis_rotational_inertia) {
      const Eigen::Matrix3d inertia = node_rotational_inertia(model, i, sys.rot[i]);
      d.block<3, 3>(3, 3) = mscale * inertia;
      sys.rhs.segment<6>(6 * (i - k)) = node_rhs(model, st, i, dt, &inertia);
    } else {
      d.diagonal().tail<3>().setConstant(mscale * model.rot_inertia[i]);
      sys.rhs.segment<6>(6 * (i - k)) = node_rhs(model, st, i, dt, nullptr);
    }
  }
  const Vec6 held_dv = held_velocity_change(st, k - 1, push, rotate);
  ElementLinearisation lin;
  for (int e = k - 1; e + 1 < n; ++e) {
    BeamElementEval& ev = sys.elem[e];
    eval_beam_element(model, e, st.x[e], sys.rot[e], st.x[e + 1], sys.rot[e + 1], ev);
    sys.elastic_energy += ev.energy;
    const bool held_a = e == k - 1;
    linearise_element(model, st, e, ev, held_dv, held_a, dt, lin);
    const int lb = e + 1 - k;
    sys.a.diag[lb] += lin.k.block<6, 6>(6, 6);
    sys.rhs.segment<6>(6 * lb) += lin.rhs.tail<6>();
    if (!held_a) {
      const int la = e - k;
      sys.a.diag[la] += lin.k.block<6, 6>(0, 0);
      sys.a.lower[la] += lin.k.block<6, 6>(6, 0);
      sys.rhs.segment<6>(6 * la) += lin.rhs.head<6>();
    }
  }
}

void assemble_system_sparse(const WireModel& model, const WireState& st, double push, double rotate,
                            Eigen::SparseMatrix<double>& a, Eigen::VectorXd& rhs) {
  const int n = model.nodes;
  const int k = first_free_node(model, st);
  const int nf = n - k;
  const int dim = 6 * nf;
  std::vector<Eigen::Triplet<double>> trip;
  rhs = Eigen::VectorXd::Zero(dim);
  const double dt = model.h;
  const double mscale = 1.0 + dt * model.params.damping_mass;
  for (int i = k; i < n; ++i) {
    const int r = 6 * (i - k);
    const Eigen::Matrix3d inertia = node_rotational_inertia(model, i, st.q[i].toRotationMatrix());
    for (int j = 0; j < 3; ++j) {
      trip.emplace_back(r + j, r + j, mscale * model.mass[i]);
      for (int c = 0; c < 3; ++c)
        if (inertia(j, c) != 0) trip.emplace_back(r + 3 + j, r + 3 + c, mscale * inertia(j, c));
    }
    rhs.segment<6>(r) += node_rhs(model, st, i, dt, model.params.per_axis_rotational_inertia ? &inertia : nullptr);
  }
  const Vec6 held_dv = held_velocity_change(st, k - 1, push, rotate);
  BeamElementEval ev;
  ElementLinearisation lin;
  for (int e = k - 1; e + 1 < n; ++e) {
    eval_beam_element(model, e, st.x[e], st.q[e].toRotationMatrix(), st.x[e + 1], st.q[e + 1].toRotationMatrix(), ev);
    linearise_element(model, st, e, ev, held_dv, e == k - 1, dt, lin);
    // Scatter every (node, node) block whose both nodes are unknowns.
    const int nodes_of[2] = {e, e + 1};
    for (int p = 0; p < 2; ++p) {
      if (nodes_of[p] < k) continue;
      const int rp = 6 * (nodes_of[p] - k);
      rhs.segment<6>(rp) += lin.rhs.segment<6>(6 * p);
      for (int qn = 0; qn < 2; ++qn) {
        if (nodes_of[qn] < k) continue;
        const int rq = 6 * (nodes_of[qn] - k);
        for (int r = 0; r < 6; ++r)
          for (int c = 0; c < 6; ++c) trip.emplace_back(rp + r, rq + c, lin.k(6 * p + r, 6 * qn + c));
      }
    }
  }
  a.resize(dim, dim);
  a.setFromTriplets(trip.begin(), trip.end());
}

}  // namespace gw
