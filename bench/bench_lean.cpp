// The ceiling vorodec's rigid step is measured against (issue 43: the rigid step >= 0.6 of it): a
// lean rigid-block step on vorodec's own specimen, blocks and contacts, in the same binary as
// BM_ScaledStepFixed so that the two run side by side. Per contact: a's corner and b's edge from
// the blocks' poses, gap, normal force from the overlap, shear force by increments, Mohr-Coulomb
// with a bond, a force record; per block: its contacts' records gathered through a block -> contact
// index (1 and 2 threads agree bit for bit, as in vorodec), local damping and central difference.
// What vorodec does and this leaves out: contact detection, rounded corners, energy sums, the load
// path, state flags and crack records. It is a speed reference only, not a model.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <cmath>

#include "specimens.hpp"
#include "vorodec/drivers/registry.hpp"
#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/loading/boundary.hpp"

using namespace vorodec;

namespace {

struct LeanModel {
  // Blocks: pose, velocity, inverse mass and inertia (0: prescribed), corners in the block frame.
  std::vector<double> x, y, theta, vx, vy, omega, inv_mass, inv_inertia, cs, sn;
  std::vector<double> cx, cy;  // m, corner relative to the centroid at theta = 0
  // Contacts: blocks, a's corner, b's edge (its start and end corner), properties, shear force.
  std::vector<std::uint32_t> a, b, corner, edge, edge_end;
  std::vector<double> kn, ks, tan_phi, cohesion, tension, inv_length, fs;
  std::vector<std::uint8_t> bonded;
  std::vector<double> rfx, rfy, rma, rmb;  // force record: force on a, moments on a and b
  // Per block, its contacts as contact * 2 + side (0: a, 1: b), in contact order.
  std::vector<std::uint32_t> gather_begin, gather;
  double dt = 0.0, damping = 0.8;
};

LeanModel lean_copy(const run::PreparedModel& pm) {
  const model::Blocks& bl = pm.model->blocks;
  const auto& contacts = pm.model->contacts;
  LeanModel m;
  m.x = bl.x;
  m.y = bl.y;
  m.theta = bl.theta;
  m.vx = bl.vx;
  m.vy = bl.vy;
  m.omega = bl.omega;
  m.cs.resize(bl.size());
  m.sn.resize(bl.size());
  for (std::size_t i = 0; i < bl.size(); ++i) {
    m.inv_mass.push_back(bl.prescribed[i] ? 0.0 : 1.0 / bl.mass[i]);
    m.inv_inertia.push_back(bl.prescribed[i] ? 0.0 : 1.0 / bl.inertia[i]);
  }
  for (const model::Point& p : bl.corner) {
    m.cx.push_back(p.x);
    m.cy.push_back(p.y);
  }
  // Each law group's contacts are one range: a contact's index in its group counts from there.
  std::vector<std::size_t> group_first(pm.solver->laws().size(), contacts.size());
  for (std::size_t i = contacts.size(); i-- > 0;) group_first[contacts[i].law] = i;
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const model::Contact& c = contacts[i];
    m.a.push_back(c.a);
    m.b.push_back(c.b);
    m.corner.push_back(c.corner);
    m.edge.push_back(c.edge);
    m.edge_end.push_back(bl.shape[c.edge].next);
    const double k = pm.solver->laws()[c.law]->max_stiffness(i - group_first[c.law]);
    m.kn.push_back(k);
    m.ks.push_back(0.4 * k);
    m.tan_phi.push_back(0.7);
    m.cohesion.push_back(20e6 * c.length);  // strong enough that the timed steps stay elastic
    m.tension.push_back(10e6 * c.length);
    m.inv_length.push_back(bl.shape[c.edge].inv_length);
    m.fs.push_back(c.fs);
    m.bonded.push_back(c.bonded);
  }
  const std::size_t nc = contacts.size();
  for (auto* v : {&m.rfx, &m.rfy, &m.rma, &m.rmb}) v->assign(nc, 0.0);
  std::vector<std::uint32_t> count(bl.size() + 1, 0);
  for (std::size_t i = 0; i < nc; ++i) {
    ++count[m.a[i] + 1];
    ++count[m.b[i] + 1];
  }
  for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
  m.gather_begin = count;
  m.gather.resize(2 * nc);
  for (std::size_t i = 0; i < nc; ++i) {
    m.gather[count[m.a[i]]++] = static_cast<std::uint32_t>(2 * i);
    m.gather[count[m.b[i]]++] = static_cast<std::uint32_t>(2 * i + 1);
  }
  m.dt = pm.solver->dt();
  return m;
}

double sign(double v) {
  return (v > 0.0) - (v < 0.0);
}

void lean_step(LeanModel& m) {
  const auto nb = static_cast<std::int64_t>(m.x.size());
  const auto nc = static_cast<std::int64_t>(m.a.size());
  const double dt = m.dt;
#pragma omp parallel
  {
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < nb; ++i) {
      m.cs[i] = std::cos(m.theta[i]);
      m.sn[i] = std::sin(m.theta[i]);
    }
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < nc; ++i) {
      const std::uint32_t a = m.a[i], b = m.b[i];
      const std::uint32_t c = m.corner[i], e0 = m.edge[i], e1 = m.edge_end[i];
      const double px = m.x[a] + m.cs[a] * m.cx[c] - m.sn[a] * m.cy[c];
      const double py = m.y[a] + m.sn[a] * m.cx[c] + m.cs[a] * m.cy[c];
      const double qx = m.x[b] + m.cs[b] * m.cx[e0] - m.sn[b] * m.cy[e0];
      const double qy = m.y[b] + m.sn[b] * m.cx[e0] + m.cs[b] * m.cy[e0];
      const double rx = m.x[b] + m.cs[b] * m.cx[e1] - m.sn[b] * m.cy[e1];
      const double ry = m.y[b] + m.sn[b] * m.cx[e1] + m.cs[b] * m.cy[e1];
      const double tx = (rx - qx) * m.inv_length[i], ty = (ry - qy) * m.inv_length[i];
      const double nx = ty, ny = -tx;  // out of b (counter-clockwise corners)
      const double gap = (px - qx) * nx + (py - qy) * ny;
      // Relative velocity of a's corner against b at the corner, along the edge.
      const double vax = m.vx[a] - m.omega[a] * (py - m.y[a]);
      const double vay = m.vy[a] + m.omega[a] * (px - m.x[a]);
      const double vbx = m.vx[b] - m.omega[b] * (py - m.y[b]);
      const double vby = m.vy[b] + m.omega[b] * (px - m.x[b]);
      double fn = -m.kn[i] * gap;  // compression positive
      double fs = m.fs[i] - m.ks[i] * ((vax - vbx) * tx + (vay - vby) * ty) * dt;
      if (m.bonded[i] && (fn < -m.tension[i] || std::abs(fs) > m.cohesion[i] + fn * m.tan_phi[i]))
        m.bonded[i] = 0;
      if (!m.bonded[i]) {
        fn = std::max(fn, 0.0);
        fs = std::clamp(fs, -fn * m.tan_phi[i], fn * m.tan_phi[i]);
      }
      m.fs[i] = fs;
      const double fx = fn * nx + fs * tx, fy = fn * ny + fs * ty;
      m.rfx[i] = fx;
      m.rfy[i] = fy;
      m.rma[i] = (px - m.x[a]) * fy - (py - m.y[a]) * fx;
      m.rmb[i] = -((px - m.x[b]) * fy - (py - m.y[b]) * fx);
    }
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < nb; ++i) {
      double fx = 0.0, fy = 0.0, mz = 0.0;
      for (std::uint32_t k = m.gather_begin[i]; k < m.gather_begin[i + 1]; ++k) {
        const std::uint32_t c = m.gather[k] >> 1;
        const double s = (m.gather[k] & 1) ? -1.0 : 1.0;
        fx += s * m.rfx[c];
        fy += s * m.rfy[c];
        mz += (m.gather[k] & 1) ? m.rmb[c] : m.rma[c];
      }
      fx -= m.damping * std::abs(fx) * sign(m.vx[i]);
      fy -= m.damping * std::abs(fy) * sign(m.vy[i]);
      mz -= m.damping * std::abs(mz) * sign(m.omega[i]);
      m.vx[i] += fx * m.inv_mass[i] * dt;
      m.vy[i] += fy * m.inv_mass[i] * dt;
      m.omega[i] += mz * m.inv_inertia[i] * dt;
      m.x[i] += m.vx[i] * dt;
      m.y[i] += m.vy[i] * dt;
      m.theta[i] += m.omega[i] * dt;
    }
  }
}

// Exactly 200 lean steps after vorodec's 300 loading steps, as BM_ScaledStepFixed: cu/s per core.
void BM_LeanStepFixed(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  const io::ModelConfig cfg = bench::scaled_model(static_cast<int>(state.range(0)));
  run::PreparedModel pm = run::prepare_model(cfg, run::make_specimen(cfg));
  loading::SpecimenBoundary(*pm.model).set_platen_velocity(*pm.model, 0.05);
  for (int i = 0; i < 300; ++i) pm.solver->step();
  const LeanModel start = lean_copy(pm);
  std::size_t updates = 0;
  double speed = 0.0, intact = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    LeanModel m = start;
    state.ResumeTiming();
    for (int i = 0; i < 200; ++i) lean_step(m);
    updates += 200 * m.a.size();
    benchmark::DoNotOptimize(m.x.data());
    state.PauseTiming();
    // That the copy stays a specimen: its fastest block (m/s) and its bonds still intact.
    speed = 0.0;
    for (std::size_t i = 0; i < m.vx.size(); ++i)
      speed = std::max(speed, std::hypot(m.vx[i], m.vy[i]));
    intact = static_cast<double>(std::count(m.bonded.begin(), m.bonded.end(), 1));
    state.ResumeTiming();
  }
  const double threads = static_cast<double>(state.range(1));
  state.counters["contacts"] = static_cast<double>(start.a.size());
  state.counters["bonded_before"] =
      static_cast<double>(std::count(start.bonded.begin(), start.bonded.end(), 1));
  state.counters["bonded_after"] = intact;
  state.counters["max_speed"] = speed;
  state.counters["cu/s"] =
      benchmark::Counter(static_cast<double>(updates), benchmark::Counter::kIsRate);
  state.counters["cu/s/core"] =
      benchmark::Counter(static_cast<double>(updates) / threads, benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_LeanStepFixed)
    ->Args({1000, 1})
    ->Args({10000, 1})
    ->Args({100000, 1})
    ->Args({1000, 2})
    ->Args({10000, 2})
    ->Args({100000, 2})
    ->Unit(benchmark::kMillisecond);
