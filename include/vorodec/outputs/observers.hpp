#pragma once
// The observers of a run: history.csv, the crack catalogue (cracks.csv, rows appended as cracks
// occur), the VTK series with rose.csv, the acoustic-emission events. Each writes whole rows and
// whole files, so a killed run leaves files that parse; each saves where its files stand for a
// checkpoint and continues them from there when the run resumes.
#include <filesystem>
#include <memory>
#include <vector>

#include "vorodec/engine/observer.hpp"
#include "vorodec/input/model_file.hpp"
#include "vorodec/io/csv_writer.hpp"
#include "vorodec/measure/ae_catalogue.hpp"
#include "vorodec/measure/cycles.hpp"
#include "vorodec/outputs/damage_output.hpp"

namespace vorodec::run {

// The specimen's stress-strain curve as the summary fits it, gathered from the history rows.
struct Curve {
  std::vector<double> strain, stress, lateral, failure_rate;
  std::vector<measure::HistoryPoint> rows;
};

// The observers of a quasi-static run, fresh (resume == nullptr) or continued from a checkpoint
// whose archive stands at their state. `curve` is filled by the history observer.
Observers make_observers(const RunView& view, const DamageOutput& damage,
                         const measure::AeSettings& ae, const std::filesystem::path& out,
                         bool write_vtk, Curve& curve, checkpoint::InArchive* resume);

}  // namespace vorodec::run
