#pragma once
// The damage measures of a run (measure/damage.hpp) on their way out: history values, the
// rose.csv row of a VTK output time, and the damage fields of each VTK frame.
#include <vector>

#include "vorodec/io/vtk_writer.hpp"
#include "vorodec/measure/damage.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::run {

class DamageOutput {
 public:
  // Takes the baseline from the model's initial contacts. grid_cell <= 0: about 5 mean block sizes,
  // a whole number of cells across the specimen's width.
  DamageOutput(const model::Model& m, double grid_cell);

  measure::DamageState measure(const model::Model& m, const solver::Solver& solver) const;
  // time, axial stress, P21 (total, tensile, shear) and the three roses: one rose.csv row.
  std::vector<double> rose_row(const model::Model& m, const solver::Solver& solver,
                               double axial_stress) const;
  // Adds each block's failed fraction and the damage grid to a VTK frame.
  void add_fields(const model::Model& m, const solver::Solver& solver, io::VtkFrame& frame) const;

  static std::vector<std::string> rose_header();
  double grid_cell() const { return cell_; }
  double mean_block_size() const { return base_.mean_block_size; }  // m

 private:
  measure::DamageBaseline base_;
  double cell_;
};

}  // namespace vorodec::run
