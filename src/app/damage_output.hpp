#pragma once
// The damage measures of a run (measure/damage.hpp) on their way out: history values, one
// rose.csv row per VTK output time, and the damage fields of each VTK frame.
#include <filesystem>
#include <string>

#include "vorodec/io/csv_writer.hpp"
#include "vorodec/io/vtk_writer.hpp"
#include "vorodec/measure/damage.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::app {

class DamageOutput {
 public:
  // Takes the baseline from the model's initial contacts. grid_cell <= 0: about 5 mean block sizes,
  // a whole number of cells across the specimen's width.
  DamageOutput(const model::Model& m, double grid_cell, const std::filesystem::path& out_dir);

  measure::DamageState measure(const model::Model& m, const solver::Solver& solver) const;

  // At a VTK output time: writes a rose.csv row and, if frame is given, adds each block's failed
  // fraction and the damage grid to it.
  void output_time(const model::Model& m, const solver::Solver& solver, const std::string& stage,
                   double axial_stress, io::VtkFrame* frame);

  double grid_cell() const { return cell_; }

 private:
  measure::DamageBaseline base_;
  double cell_;
  io::CsvWriter rose_;
};

}  // namespace vorodec::app
