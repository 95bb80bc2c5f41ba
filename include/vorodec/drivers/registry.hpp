#pragma once
// The load paths a model file can describe. Each driver is one row of the table in
// src/drivers/registry.cpp: its name, whether a model file asks for it, and how it is made.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "vorodec/engine/driver.hpp"
#include "vorodec/loading/boundary.hpp"

namespace vorodec::run {

// What every driver is made from.
struct DriverContext {
  const io::ModelConfig& cfg;
  model::Model& model;
  solver::Solver& solver;
  const loading::SpecimenBoundary& boundary;
  const geometry::Tessellation& specimen;
  long step_limit;         // steps at most
  bool limit_from_option;  // the limit is --max-steps (a short mode), not the model file's
};

// The driver of the first row whose model-file section is present.
std::unique_ptr<Driver> make_driver(const DriverContext& c);

// The name of that row ("shpb", "quasi_static"), for messages.
std::string driver_name(const io::ModelConfig& cfg);

// The model file read with the keys of every registered stage mode: what runs, batches,
// calibrations and `vorodec check` read (io::read_model_file).
io::ModelConfig read_model_file(const std::filesystem::path& file,
                                const std::vector<io::Override>& overrides = {});

}  // namespace vorodec::run
