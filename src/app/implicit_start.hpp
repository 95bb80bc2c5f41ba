#pragma once
// The implicit elastic start of a velocity stage (stage key implicit_start): the specimen's static
// linear response to the confining stress and to the top platen's displacement
// (solver::elastic_response, one CHOLMOD factorisation), scaled to a fraction of the displacement
// at which the first contact would crack, slip, open or close, and applied in one jump. The
// explicit steps go on from there, with the blocks moving as the linear response does at the
// stage's platen speed, so the crack-free part of a quasi-static test costs one solve instead of
// thousands of steps.
#include "vorodec/app/simulation.hpp"
#include "vorodec/loading/boundary.hpp"
#include "vorodec/loading/load_path.hpp"

namespace vorodec::app {

// `confining_stress` (Pa) is applied whole along the jump, as the explicit steps apply it.
// Throws solver::ElasticResponseError when the response cannot be computed.
ImplicitStart implicit_start(model::Model& model, solver::Solver& solver,
                             const loading::SpecimenBoundary& boundary, const loading::Stage& stage,
                             double confining_stress);

}  // namespace vorodec::app
