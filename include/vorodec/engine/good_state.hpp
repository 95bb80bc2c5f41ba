#pragma once
// The last state that passed the stability check: a run that goes unstable ends there.
#include <vector>

#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/model/model.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::run {

struct GoodState {
  std::vector<double> x, y, theta, gx, gy;  // blocks, then gridpoints

  void keep(const model::Model& m) {
    x = m.blocks.x;
    y = m.blocks.y;
    theta = m.blocks.theta;
    gx = m.zoning.x;
    gy = m.zoning.y;
  }
  // Every 100 steps: the stability check (throws solver::InstabilityError), then this state kept.
  void check(const solver::Solver& solver, const model::Model& m) {
    if (solver.steps() % 100 != 0) return;
    solver.check_stability();
    keep(m);
  }
  // Nothing kept yet: the model stays as it is.
  void restore(model::Model& m) const {
    if (x.empty()) return;
    m.blocks.x = x;
    m.blocks.y = y;
    m.blocks.theta = theta;
    m.zoning.x = gx;
    m.zoning.y = gy;
    model::refresh_world(m);  // the frame and the damage measures read world positions
  }
  template <class Archive>
  void serialize(Archive& ar) {
    ar(checkpoint::pod(x), checkpoint::pod(y), checkpoint::pod(theta), checkpoint::pod(gx),
       checkpoint::pod(gy));
  }
};

}  // namespace vorodec::run
