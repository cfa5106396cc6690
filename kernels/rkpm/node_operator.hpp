// The operators of one RKPM node in the current configuration (rkpm.md 8.1,
// `coefficients` storage): its smoothing cell's faces and the RK
// coefficients b at its 2d face points and at the node, from which any
// partner I evaluates Psi_I there; and its NSNI data. OperatorFunctor
// builds them per node L as a gather over row L (rkpm.md 5.2 stage 5), and
// shape_at() is what the stress and force gathers call per pair.
#pragma once
#include "kernels/neighbors/pair_list.hpp"
#include "kernels/rkpm/reproducing_kernel.hpp"
#include "kernels/rkpm/smoothing_cell.hpp"

namespace mfsd::rkpm {

constexpr Index kNoKronecker = -1;

template <int D, class Real>
struct NodeOperator {
  static constexpr int kPoints = 2 * D + 1;  // faces 0 .. 2D-1, then the node
  Vec<D, Real> offset[2 * D];                // xbar_f - x_L
  Vec<D, Real> area[2 * D];                  // a_f
  Vec<D + 1, Real> b[kPoints];               // RK coefficients (seed 004 eq. 18)
  Index kronecker[kPoints];                  // a singular node at the point, else kNoKronecker (kronecker_ids.hpp)
  Real volume;                               // V_L = J V0
  Real inv_abar;                             // 1/abar, abar = a_L (basis scaling, rkpm.md 1.3)
};

// What the per-node fields give a pair loop: positions, supports and flags.
template <int D, class Real>
struct NodeFields {
  const Vec<D, Real>* position;   // x at the operators' configuration
  const Real* support;            // a_I
  const unsigned char* singular;  // 1: boundary singular kernel (rkpm.md 1.7); null: none
  bool box = false;               // box supports (rkpm.md 1.2), else spheres
  MFSD_HD bool is_singular(Index i) const { return singular && singular[i]; }
};

// Psi_I at point p of node L's operator, y = x_p - x_I (rkpm.md 1.3, 1.7).
template <int D, class Real>
MFSD_HD inline double shape_at(const NodeOperator<D, Real>& op, int p, Index I, const Vec<D, double>& y, double a_I,
                               bool singular_I, bool box) {
  const Index k = op.kronecker[p];
  if (k != kNoKronecker) return k == I ? 1.0 : 0.0;
  const KernelSample<D> s = kernel(y, a_I, singular_I, box);
  if (!(s.w > 0.0)) return 0.0;
  return shape_value<D, Real>(op.b[p], y, double(op.inv_abar), s.w);
}

// V_L grad~Psi_I(x_L) = sum_f Psi_I(xbar_f) a_f (seed 004 eq. 23-24), with
// the part on the body's surface faces (bits of `surface`) in `boundary`.
template <int D, class Real>
MFSD_HD inline Vec<D, double> smoothed_gradient_volume(const NodeOperator<D, Real>& op, Index I,
                                                       const Vec<D, double>& d, double a_I, bool singular_I, bool box,
                                                       unsigned char surface, Vec<D, double>* boundary) {
  Vec<D, double> g = Vec<D, double>::zero();
  for (int f = 0; f < 2 * D; ++f) {
    const double psi = shape_at(op, f, I, cast<double>(op.offset[f]) + d, a_I, singular_I, box);
    const Vec<D, double> part = cast<double>(op.area[f]) * psi;
    g += part;
    if (boundary && (surface >> f & 1u)) *boundary += part;
  }
  return g;
}

// Builds node L's operator and NSNI data from row L (rkpm.md 5.2 stage 5).
template <int D, class Real>
struct OperatorFunctor {
  PairList<D, Real> rows;  // symmetric list, each row holding its node
  NodeFields<D, Real> nodes;
  const Mat<D, Real>* cell_map;  // F_cell
  const Vec<D, Real>* cell_lo;   // initial extents lo, hi
  const Vec<D, Real>* cell_hi;
  bool box_cells;
  int quasi_linear;  // 0 regularize, 1 shepard, 2 off
  double tau;
  NodeOperator<D, Real>* op;
  ImplicitGradient<D, Real>* nsni;  // null: SNNI only
  Real* reach;                      // a_L + max_f |xbar_f - x_L|, for the list's skin
  Real* nearest;                    // the distance to the nearest other node of row L (time step)
  unsigned char* status;  // bits: 1 a point regularized or Shepard, 2 a point failed, 4 fewer than d + 1 kernels

  MFSD_HD void operator()(Index L) const {
    const Vec<D, Real> xL = nodes.position[L];
    Mat<D, double> F = cast<double>(cell_map[L]);
    if (box_cells) F = box_map<D>(F);
    const CellFaces<D> faces = mapped_faces<D>(F, cast<double>(cell_lo[L]), cast<double>(cell_hi[L]));
    NodeOperator<D, Real> o;
    const double aL = double(nodes.support[L]);
    const double inv_abar = 1.0 / aL;
    o.inv_abar = Real(inv_abar);
    o.volume = Real(faces.volume);
    double r_max = 0.0;
    for (int f = 0; f < 2 * D; ++f) {
      o.offset[f] = cast<Real>(faces.offset[f]);
      o.area[f] = cast<Real>(faces.area[f]);
      r_max = math::max(r_max, norm(faces.offset[f]));
    }
    reach[L] = Real(aL * kernel_reach_factor<D>(nodes.box) + r_max);
    const PairRow row = rows.row(L);
    unsigned char flags = 0;
    double r2_min = INFINITY;
    for (Index k = 0; k < row.count; ++k) {
      const Index I = rows.neighbor[row.at(k)];
      if (I != L) r2_min = math::min(r2_min, squared_norm(cast<double>(xL - nodes.position[I])));
    }
    nearest[L] = Real(math::sqrt(r2_min));
    for (int p = 0; p < NodeOperator<D, Real>::kPoints; ++p) {
      const Vec<D, double> to_point = p < 2 * D ? faces.offset[p] : Vec<D, double>::zero();
      MomentSum<D> ms, regular;  // regular: the regular kernels' moments where a singular one covers the point
      bool any_singular = false;
      Index kron = kNoKronecker;
      for (Index k = 0; k < row.count; ++k) {
        const Index I = rows.neighbor[row.at(k)];
        const Vec<D, double> y = to_point + cast<double>(xL - nodes.position[I]);
        const double aI = double(nodes.support[I]);
        const bool sing = nodes.is_singular(I);
        if (sing && squared_norm(y) < kSingularGuard * kSingularGuard * aI * aI) kron = I;
        const Vec<D + 1, double> h = basis<D>(y, inv_abar);
        const double w = kernel<D>(y, aI, sing, nodes.box).w;
        ms.add(h, w);
        if (sing && w > 0.0) {
          any_singular = true;
          regular.add(h, w * math::pow(norm(y) / aI, kSingularExponent));  // phi = phi^ z^alpha
        } else {
          regular.add(h, w);
        }
      }
      o.kronecker[p] = kron;
      if (ms.covering < D + 1 && kron == kNoKronecker) flags |= 4u;
      Vec<D + 1, double> b = Vec<D + 1, double>::zero();
      if (kron == kNoKronecker) {
        const Solve how =
            solve_moments<D>(ms.M, ms.covering, quasi_linear, tau, b, any_singular ? &regular.M : nullptr);
        if (how == Solve::regularized || how == Solve::shepard) flags |= 1u;
        if (how == Solve::failed) flags |= 2u;
      }
      for (int q = 0; q < D + 1; ++q) o.b[p].v[q] = Real(b.v[q]);
    }
    op[L] = o;
    status[L] = flags;
    if (nsni) {
      // NSNI coefficients use the regular kernel for every node (rkpm.md 1.7).
      MomentSum<D> ms;
      MomentDerivativeSum<D> dm;
      for (Index k = 0; k < row.count; ++k) {
        const Index I = rows.neighbor[row.at(k)];
        const Vec<D, double> y = cast<double>(xL - nodes.position[I]);
        const KernelSample<D> s = kernel<D>(y, double(nodes.support[I]), false, nodes.box);
        const Vec<D + 1, double> h = basis<D>(y, inv_abar);
        ms.add(h, s.w);
        if (s.w > 0.0) dm.add(h, s, inv_abar);
      }
      ImplicitGradient<D, Real> g;
      if (ms.M.m[0][0] > 0.0) {
        if (quasi_linear == 0) regularize<D>(ms.M, tau);
        implicit_gradient<D, Real>(ms.M, dm, g);
      } else {
        implicit_gradient<D, Real>(Mat<D + 1, double>::zero(), dm, g);
      }
      nsni[L] = g;
    }
  }
};

}  // namespace mfsd::rkpm
