#pragma once
// The end of a run: the measures fitted to its whole history (elastic constants, failure stages,
// cycles, strengths) into summary.json and cycles.csv, each written whole (temporary name and
// rename).
#include <filesystem>

#include "driver.hpp"
#include "observers.hpp"
#include "vorodec/io/model_file.hpp"
#include "vorodec/measure/ae_catalogue.hpp"

namespace vorodec::app {

RunSummary write_results(const io::ModelConfig& cfg, const RunView& view, Curve curve,
                         const DriverOutcome& outcome, const measure::AeSettings& ae,
                         double wall_seconds, const std::filesystem::path& out);

}  // namespace vorodec::app
