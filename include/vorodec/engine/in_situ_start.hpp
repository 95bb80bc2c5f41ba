#pragma once
// In-situ stress at the start (docs/theory.md §6.7): the initial contacts carry the field's
// traction and the zones its stress, so that the model starts in equilibrium under it.
#include "vorodec/loading/in_situ.hpp"
#include "vorodec/model/model.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::run {

// The blocks of each pair push on each other with the field's traction on their shared boundary,
// shared among the pair's contacts in proportion to their lengths (pairs that touch at a point
// only start unloaded), and each zone starts with the field at its centroid. Throws
// std::logic_error if a contact's law cannot start loaded (the model file's reader refuses such
// laws first).
void preload_in_situ(model::Model& model, solver::Solver& solver,
                     const loading::InSituStress& field);

}  // namespace vorodec::run
