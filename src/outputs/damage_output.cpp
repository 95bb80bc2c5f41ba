#include "vorodec/outputs/damage_output.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace vorodec::run {

namespace {

// About 5 mean block sizes, so that a cell holds ~25 blocks, adjusted to a whole number of cells
// across the specimen's width (no sliver column of noisy, partly covered cells).
double default_cell(const measure::DamageBaseline& base) {
  const double width = base.hi.x - base.lo.x, target = 5.0 * base.mean_block_size;
  if (!(width > 0.0) || !(target > 0.0)) return 0.0;
  return width / std::max(1.0, std::round(width / target));
}

}  // namespace

std::vector<std::string> DamageOutput::rose_header() {
  std::vector<std::string> h{"time", "axial_stress", "p21", "p21_tensile", "p21_shear"};
  for (const char* kind : {"p21", "tensile", "shear"})
    for (std::size_t k = 0; k < measure::kRoseBins; ++k)
      h.push_back(fmt::format("{}_{}_{}", kind, 10 * k, 10 * (k + 1)));
  h.push_back("stage");
  return h;
}

DamageOutput::DamageOutput(const model::Model& m, double grid_cell)
    : base_(measure::damage_baseline(m)),
      cell_(grid_cell > 0.0 ? grid_cell : default_cell(base_)) {}

measure::DamageState DamageOutput::measure(const model::Model& m,
                                           const solver::Solver& solver) const {
  return measure::measure_damage(m, solver.cracks(), base_);
}

std::vector<double> DamageOutput::rose_row(const model::Model& m, const solver::Solver& solver,
                                           double axial_stress) const {
  const measure::DamageState s = measure(m, solver);
  std::vector<double> row{solver.time(), axial_stress, s.p21, s.p21_tensile, s.p21_shear};
  for (const measure::Rose* rose : {&s.rose, &s.rose_tensile, &s.rose_shear})
    row.insert(row.end(), rose->begin(), rose->end());
  return row;
}

void DamageOutput::add_fields(const model::Model& m, const solver::Solver& solver,
                              io::VtkFrame& frame) const {
  if (!(cell_ > 0.0)) return;
  frame.block_failed_fraction = measure::block_failed_fraction(solver.cracks(), base_);
  measure::DamageGrid g = measure::damage_grid(m, solver.cracks(), base_, cell_);
  frame.grid = {g.origin, g.cell, g.nx, g.ny, {}};
  frame.grid.fields = {{"p21", std::move(g.p21)},
                       {"damage_density", std::move(g.damage_density)},
                       {"crack_length", std::move(g.crack_length)},
                       {"crack_area", std::move(g.crack_area)},
                       {"specimen_area", std::move(g.specimen_area)}};
}

}  // namespace vorodec::run
