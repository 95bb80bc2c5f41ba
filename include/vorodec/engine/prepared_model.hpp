#pragma once
// A model file made ready to step: its specimen (tessellated or read from a specimen file), the
// blocks, contact laws and platens, and the solver with its initial contacts.
#include <memory>
#include <string>

#include "vorodec/geometry/tessellation.hpp"
#include "vorodec/input/model_file.hpp"
#include "vorodec/model/model.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::run {

// The specimen of a model file: tessellated, or loaded from a prepared specimen file. An
// impossible geometry is bad input (io::ModelFileError naming the file and [specimen]'s line).
geometry::Tessellation make_specimen(const io::ModelConfig& cfg);

// The specimen's geometry report for a person (blocks, edges, angles, grains and minerals), without
// its warnings (t.report.warnings).
std::string specimen_report(const io::ModelConfig& cfg, const geometry::Tessellation& t);

// A model ready to step: blocks, platens and initial contacts detected.
struct PreparedModel {
  std::unique_ptr<model::Model> model;
  std::unique_ptr<solver::Solver> solver;
};
PreparedModel prepare_model(const io::ModelConfig& cfg, const geometry::Tessellation& specimen);

// The initial contacts of a model with their sampled properties, as text (for `vorodec build`).
std::string describe_contacts(const io::ModelConfig& cfg, const geometry::Tessellation& specimen);

}  // namespace vorodec::run
