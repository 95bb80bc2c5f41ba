#pragma once
// The end of a run: the measures fitted to its whole history (elastic constants, failure stages,
// cycles, strengths) into summary.json and cycles.csv, each written whole (temporary name and
// rename).
#include <filesystem>

#include "vorodec/engine/driver.hpp"
#include "vorodec/input/model_file.hpp"
#include "vorodec/measure/ae_catalogue.hpp"
#include "vorodec/outputs/observers.hpp"

namespace vorodec::run {

// `driver` adds its own sections to summary.json (Driver::summarise).
RunSummary write_results(const io::ModelConfig& cfg, const Driver& driver, Curve curve,
                         const measure::AeSettings& ae, double wall_seconds,
                         const std::filesystem::path& out);

}  // namespace vorodec::run
