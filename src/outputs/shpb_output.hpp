#pragma once
// A pressure-bar test's results (measure/three_wave.hpp) on their way out: gauges.csv (each
// gauge's strain as it records it), bars.csv (the waves shifted to the specimen faces and the
// three-wave analysis, with the stress straight from the face forces) and the summary's "shpb".
#include <filesystem>
#include <string>
#include <vector>

#include "vorodec/engine/driver.hpp"
#include "vorodec/io/json_fwd.hpp"
#include "vorodec/measure/three_wave.hpp"

namespace vorodec::run {

// s, the face times over which the first gauge of each bar sees one wave at a time: up to the
// test's duration, and before the reflected wave meets the incident gauge's incident wave or a
// wave from a free far end returns to a gauge.
double analysis_window(const BarsView& bars);

// The three-wave analysis on the face times 0, record_interval, ... up to the window.
std::vector<measure::ThreeWavePoint> analyse(const BarsView& bars);

// Both files, each written whole.
void write_bars(const BarsView& bars, const std::filesystem::path& out);

// fragments.csv: each fragment's area (m^2, in the plane) and equivalent
// diameter, largest first, at the end of the test.
void write_fragments(const model::Model& model, const std::filesystem::path& out);

// The "shpb" section of summary.json: dynamic measures, the energy partition, fragments.
io::Json shpb_json(const BarsView& bars, const solver::Solver& solver, const model::Model& model);

}  // namespace vorodec::run
