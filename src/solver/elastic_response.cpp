#include "vorodec/solver/elastic_response.hpp"

#include <fmt/format.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "vorodec/model/contact_geometry.hpp"

namespace vorodec::solver {

namespace {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
constexpr double regularisation = 1e-10;  // of the Jacobi-scaled diagonal (which is 1)

// B maps a block's (ux, uy, theta) to the displacement of the contact point, which lies at
// lever (rx, ry) from its centroid: B = [[1, 0, -ry], [0, 1, rx]].
struct Lever {
  double rx, ry;
};

// 3 x 3 block B_pᵀ D B_q of the contact stiffness, D = kn n nᵀ + ks s sᵀ (2 x 2, symmetric).
std::array<std::array<double, 3>, 3> coupling(Lever p, Lever q, double dxx, double dxy,
                                              double dyy) {
  const double bp[2][3] = {{1, 0, -p.ry}, {0, 1, p.rx}};
  const double bq[2][3] = {{1, 0, -q.ry}, {0, 1, q.rx}};
  const double d[2][2] = {{dxx, dxy}, {dxy, dyy}};
  std::array<std::array<double, 3>, 3> k{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) k[r][c] += bp[i][r] * d[i][j] * bq[j][c];
  return k;
}

// A plain loop: Eigen's vectorised norm trips GCC 12's -Wmaybe-uninitialized under AVX-512.
double norm(const Eigen::VectorXd& v) {
  double s = 0.0;
  for (Eigen::Index i = 0; i < v.size(); ++i) s += v[i] * v[i];
  return std::sqrt(s);
}

struct Linearised {
  model::ContactFrame frame;
  laws::LinearSprings springs;
  std::size_t law, local;
  Lever la, lb;
};

// Per contact: its frame, springs, law and local index, and its levers to both centroids.
std::vector<Linearised> linearise(const model::Model& model,
                                  const std::vector<std::unique_ptr<laws::LawGroup>>& laws) {
  const auto& bl = model.blocks;
  const std::size_t nc = model.contacts.size();
  std::vector<Linearised> lin(nc);
  std::vector<std::size_t> first(laws.size(), nc);
  for (std::size_t i = 0; i < nc; ++i) {
    const model::Contact& c = model.contacts[i];
    Linearised& e = lin[i];
    e.law = c.law;
    first[e.law] = std::min(first[e.law], i);  // the contacts are grouped by law
    e.local = i - first[e.law];
    if (!laws[e.law]->linear_springs(e.local, e.springs))
      throw ElasticResponseError(fmt::format(
          "contact law '{}' has no linear elastic regime for the implicit elastic start",
          laws[e.law]->name()));
    model::Contact copy = c;
    e.frame = model::contact_frame(bl.corners(), copy);
    const auto a = static_cast<std::size_t>(c.a), b = static_cast<std::size_t>(c.b);
    // The force acts at the arm, and the shear coordinate moves by gain times the arm's
    // displacement along s (ContactFrame): the shear spring acts as gain^2 ks there.
    e.la = {e.frame.arm.x - bl.x[a], e.frame.arm.y - bl.y[a]};
    e.lb = {e.frame.arm.x - bl.x[b], e.frame.arm.y - bl.y[b]};
  }
  return lin;
}

// K over the free blocks' DOFs and the right-hand sides of both cases: -K_fp u_p of the unit
// case, the applied loads of the load case.
struct System {
  SparseMatrix k;
  std::array<Eigen::VectorXd, 2> rhs;
};

System assemble(const model::Model& model, const std::vector<Linearised>& lin,
                const std::vector<char>& active, const std::vector<int>& dof, int n,
                const std::vector<std::array<double, 3>>& unit,
                const std::vector<std::array<double, 3>>& load) {
  const std::size_t nb = model.blocks.size(), nc = model.contacts.size();
  System sys{SparseMatrix(n, n), {Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)}};
  auto& rhs = sys.rhs;
  std::vector<Eigen::Triplet<double, int>> triplets;
  triplets.reserve(36 * nc + static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) triplets.emplace_back(i, i, 0.0);  // every diagonal is stored
  for (std::size_t b = 0; b < nb; ++b)
    if (dof[b] >= 0)
      for (int k = 0; k < 3; ++k) rhs[1][dof[b] + k] = load[b][static_cast<std::size_t>(k)];
  for (std::size_t i = 0; i < nc; ++i) {
    if (!active[i]) continue;
    const Linearised& e = lin[i];
    const model::Point nv = e.frame.n, s{-nv.y, nv.x};
    const double kn = e.springs.kn, ks = e.frame.gain * e.frame.gain * e.springs.ks;
    const double dxx = kn * nv.x * nv.x + ks * s.x * s.x;
    const double dxy = kn * nv.x * nv.y + ks * s.x * s.y;
    const double dyy = kn * nv.y * nv.y + ks * s.y * s.y;
    const std::size_t blk[2] = {static_cast<std::size_t>(model.contacts[i].a),
                                static_cast<std::size_t>(model.contacts[i].b)};
    const Lever lever[2] = {e.la, e.lb};
    for (int p = 0; p < 2; ++p) {
      if (dof[blk[p]] < 0) continue;
      for (int qs = 0; qs < 2; ++qs) {
        const auto k = coupling(lever[p], lever[qs], dxx, dxy, dyy);
        const double sign = p == qs ? 1.0 : -1.0;  // delta = B_a u_a - B_b u_b
        for (int rr = 0; rr < 3; ++rr)
          for (int cc = 0; cc < 3; ++cc) {
            const double v = sign * k[static_cast<std::size_t>(rr)][static_cast<std::size_t>(cc)];
            if (dof[blk[qs]] >= 0)
              triplets.emplace_back(dof[blk[p]] + rr, dof[blk[qs]] + cc, v);
            else
              rhs[0][dof[blk[p]] + rr] -= v * unit[blk[qs]][static_cast<std::size_t>(cc)];
          }
      }
    }
  }
  sys.k.setFromTriplets(triplets.begin(), triplets.end());
  return sys;
}

// Solves K q = rhs for the first `cases` right-hand sides into q: Jacobi-scaled, CHOLMOD.
void solve(const System& sys, int cases, std::array<std::vector<double>, 2>& q) {
  const SparseMatrix& k = sys.k;
  const auto& rhs = sys.rhs;
  const auto n = static_cast<int>(k.rows());
  // Jacobi scaling: rotations (rad) and translations (m) differ by a block size squared.
  Eigen::VectorXd scale(n);
  for (int i = 0; i < n; ++i) {
    const double d = k.coeff(i, i);
    scale[i] = d > 0.0 ? 1.0 / std::sqrt(d) : 1.0;
  }
  SparseMatrix ks = scale.asDiagonal() * k * scale.asDiagonal();
  // A shift of the scaled diagonal keeps the free rigid motions of the specimen (frictionless
  // platens leave its sideways translation free) from making K singular. The load does no
  // work on such a motion, so its amplitude stays at round-off and it moves no force.
  for (int i = 0; i < n; ++i)
    ks.coeffRef(i, i) = k.coeff(i, i) > 0.0 ? ks.coeff(i, i) + regularisation : 1.0;
  Eigen::CholmodDecomposition<SparseMatrix, Eigen::Lower> chol;
  // Simplicial: no BLAS, whose threads could change the round-off with the thread count.
  chol.setMode(Eigen::CholmodSimplicialLLt);
  chol.compute(ks);
  if (chol.info() != Eigen::Success)
    throw ElasticResponseError(
        "the contact stiffness is not positive definite: some block is not held by its "
        "contacts (a mechanism), so it has no static elastic response");
  for (int lc = 0; lc < cases; ++lc) {
    const Eigen::VectorXd y = chol.solve(scale.cwiseProduct(rhs[static_cast<std::size_t>(lc)]));
    const Eigen::VectorXd x = scale.cwiseProduct(y);
    const Eigen::VectorXd res = k * x - rhs[static_cast<std::size_t>(lc)];
    const double residual = norm(res);
    const double size = std::max(norm(rhs[static_cast<std::size_t>(lc)]), 1e-300);
    double largest = 0.0;
    for (int i = 0; i < n; ++i) {
      q[static_cast<std::size_t>(lc)][static_cast<std::size_t>(i)] = x[i];
      largest = std::max(largest, std::abs(x[i]));  // NaN compares false: caught below
    }
    // A loaded mechanism moves by load / regularisation: far beyond anything elastic.
    if (!(residual <= 1e-6 * size) || !(largest <= 1e3) || !std::isfinite(largest))
      throw ElasticResponseError(fmt::format(
          "the contact stiffness is singular (relative residual {:.2g}, largest displacement "
          "{:.2g} m): some block is not held by its contacts (a mechanism), so it has no "
          "static elastic response",
          residual / size, largest));
  }
}

}  // namespace

ElasticResponse elastic_response(const model::Model& model,
                                 const std::vector<std::unique_ptr<laws::LawGroup>>& laws,
                                 const std::vector<std::array<double, 3>>& unit,
                                 const std::vector<std::array<double, 3>>& load, double load_left) {
  const auto& bl = model.blocks;
  const std::size_t nb = bl.size(), nc = model.contacts.size();
  std::vector<int> dof(nb, -1);
  int n = 0;
  for (std::size_t b = 0; b < nb; ++b) {
    if (bl.deformable[b])
      throw ElasticResponseError(
          "the implicit elastic start handles rigid blocks only (the specimen has deformable "
          "ones)");
    if (!bl.prescribed[b]) {
      dof[b] = n;
      n += 3;
    }
  }
  // A touching contact with no tension (an unbonded platen) is closed within this gap.
  const double touch = 1e-6 * model.rounding_length;
  const std::vector<Linearised> lin = linearise(model, laws);
  std::vector<char> active(nc);
  for (std::size_t i = 0; i < nc; ++i)
    active[i] = !lin[i].springs.unilateral || model.contacts[i].gap <= touch;

  ElasticResponse r;
  r.dofs = static_cast<std::size_t>(n);
  bool loaded = false;
  for (std::size_t b = 0; b < nb; ++b)
    loaded |= dof[b] >= 0 && (load[b][0] != 0.0 || load[b][1] != 0.0 || load[b][2] != 0.0);
  const int cases = loaded ? 2 : 1;
  // Case 0: the unit displacement of the held blocks; case 1: the applied loads, held blocks still.
  std::array<std::vector<double>, 2> q;
  q[0].assign(static_cast<std::size_t>(n), 0.0);
  q[1].assign(static_cast<std::size_t>(n), 0.0);
  // Displacement (ux, uy, theta) of block b in a case: solved or prescribed.
  const auto u = [&](int lc, std::size_t b, int k) {
    if (dof[b] >= 0) return q[static_cast<std::size_t>(lc)][static_cast<std::size_t>(dof[b] + k)];
    return lc == 0 ? unit[b][static_cast<std::size_t>(k)] : 0.0;
  };
  // Relative displacement of a's contact point with respect to b's, along n and along s.
  const auto relative = [&](int lc, std::size_t i) {
    const model::Contact& c = model.contacts[i];
    const Linearised& e = lin[i];
    const auto a = static_cast<std::size_t>(c.a), b = static_cast<std::size_t>(c.b);
    const double dx = (u(lc, a, 0) - e.la.ry * u(lc, a, 2)) - (u(lc, b, 0) - e.lb.ry * u(lc, b, 2));
    const double dy = (u(lc, a, 1) + e.la.rx * u(lc, a, 2)) - (u(lc, b, 1) + e.lb.rx * u(lc, b, 2));
    const model::Point nv = e.frame.n;
    return std::array<double, 2>{dx * nv.x + dy * nv.y, e.frame.gain * (-dx * nv.y + dy * nv.x)};
  };
  const auto t0 = std::chrono::steady_clock::now();
  for (bool again = true; again && r.passes < 50;) {
    ++r.passes;
    solve(assemble(model, lin, active, dof, n, unit, load), cases, q);
    // A unilateral contact that the case being applied would pull leaves the system; solve again.
    again = false;
    const int applied = loaded && load_left > 0.0 ? 1 : 0;
    for (std::size_t i = 0; i < nc; ++i)
      if (active[i] && lin[i].springs.unilateral && relative(applied, i)[0] > 0.0) {
        active[i] = 0;
        again = true;
      }
  }
  r.factorise_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  for (ElasticCase* ec : {&r.unit, &r.load}) {
    const int lc = ec == &r.unit ? 0 : 1;
    ec->ux.resize(nb);
    ec->uy.resize(nb);
    ec->utheta.resize(nb);
    for (std::size_t b = 0; b < nb; ++b) {
      ec->ux[b] = u(lc, b, 0);
      ec->uy[b] = u(lc, b, 1);
      ec->utheta[b] = u(lc, b, 2);
    }
    ec->dfn.assign(nc, 0.0);
    ec->dfs.assign(nc, 0.0);
    ec->dn.assign(nc, 0.0);
    ec->force.assign(nb, {0.0, 0.0, 0.0});
    for (std::size_t i = 0; i < nc; ++i) {
      if (!active[i]) continue;
      const model::Contact& c = model.contacts[i];
      const auto [dn, ds] = relative(lc, i);
      ec->dfn[i] = -lin[i].springs.kn * dn;  // opening (dn > 0) lowers the compression
      ec->dfs[i] = -lin[i].springs.ks * ds;
      const model::Point nv = lin[i].frame.n;
      const double gs = lin[i].frame.gain * ec->dfs[i];
      const double fx = ec->dfn[i] * nv.x - gs * nv.y;
      const double fy = ec->dfn[i] * nv.y + gs * nv.x;
      const auto a = static_cast<std::size_t>(c.a), b = static_cast<std::size_t>(c.b);
      ec->force[a][0] += fx;
      ec->force[a][1] += fy;
      ec->force[a][2] += lin[i].la.rx * fy - lin[i].la.ry * fx;
      ec->force[b][0] -= fx;
      ec->force[b][1] -= fy;
      ec->force[b][2] -= lin[i].lb.rx * fy - lin[i].lb.ry * fx;
    }
  }
  // The elastic reaches: of what is left of the load case from the current forces, then of the
  // unit case from the current forces plus that.
  for (std::size_t i = 0; i < nc; ++i) {
    r.unit.dn[i] = relative(0, i)[0];
    r.load.dn[i] = loaded ? relative(1, i)[0] : 0.0;
    if (!active[i]) continue;
    ++r.active_contacts;
    const model::Contact& c = model.contacts[i];
    const laws::LawGroup& law = *laws[lin[i].law];
    const std::size_t j = lin[i].local;
    const double fn = load_left * r.load.dfn[i], fs = load_left * r.load.dfs[i];
    if (loaded) r.load_reach = std::min(r.load_reach, law.elastic_reach(j, c.fn, c.fs, fn, fs));
    const double reach = law.elastic_reach(j, c.fn + fn, c.fs + fs, r.unit.dfn[i], r.unit.dfs[i]);
    if (reach < r.reach) {
      r.reach = reach;
      r.limiting_contact = i;
    }
  }
  r.active = std::move(active);
  r.touch = touch;
  return r;
}

}  // namespace vorodec::solver
