#pragma once
// The acoustic-emission catalogue of a run (measure/ae_catalogue.hpp) on its way out:
// ae_events.csv, ae_events.vtp and the summary's "acoustic_emission" entry.
#include <filesystem>
#include <span>
#include <string>

#include "vorodec/input/model_file.hpp"
#include "vorodec/io/json_fwd.hpp"
#include "vorodec/measure/ae_catalogue.hpp"

namespace vorodec::run {

// The model file's [output] ae_radius and ae_shear_wave_speed, or their defaults from the mean
// block size (m) and the joints' mean jks and the density (docs/theory.md §15.4).
measure::AeSettings ae_settings(const io::ModelConfig& cfg, double mean_block_size,
                                double thickness);

// Both files, each written whole (a killed run leaves the last complete catalogue).
void write_ae_events(std::span<const measure::AeEvent> events, const std::filesystem::path& out);

// The "acoustic_emission" section of summary.json.
io::Json ae_json(std::span<const measure::AeEvent> events, const measure::AeSettings& s);

}  // namespace vorodec::run
