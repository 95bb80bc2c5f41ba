#pragma once
// The implicit elastic start of a velocity stage (stage key implicit_start): the specimen's static
// linear response to the confining stress and to the top platen's displacement
// (solver::elastic_response, one CHOLMOD factorisation), scaled to a fraction of the displacement
// at which the first contact would crack, slip, open or close, and applied in one jump. The
// explicit steps go on from there, with the blocks moving as the linear response does at the
// stage's platen speed, so the crack-free part of a quasi-static test costs one solve instead of
// thousands of steps.
#include <string>

#include "vorodec/engine/prepared_model.hpp"
#include "vorodec/io/json_fwd.hpp"
#include "vorodec/loading/boundary.hpp"
#include "vorodec/loading/load_path.hpp"

namespace vorodec::run {

// What the implicit elastic start of the first stage did (stage key implicit_start).
struct ImplicitStart {
  double reach = 0;  // m, platen displacement at the first contact's elastic limit (first solve)
  double displacement = 0;  // m, platen displacement of the jump
  double stress = 0;        // Pa, axial stress of the linear response after the jump
  double modulus = 0;       // Pa, Young's modulus of the linear response (plane-strain apparent)
  double time = 0;          // s, stage time at which the platen program reaches the displacement
  std::size_t dofs = 0, active_contacts = 0;
  int solves = 0;    // solve steps: the increments plus one per closing
  int closings = 0;  // steps cut short where an open contact closed
  int passes = 0;    // factorisations (a solve refactorises when it drops a pulled contact)
  double solve_seconds = 0;
  std::string limit;  // what ends the elastic regime, or which end condition capped the jump
  template <class Archive>
  void serialize(Archive& ar) {
    ar(reach, displacement, stress, modulus, time, dofs, active_contacts, solves, closings, passes,
       solve_seconds, limit);
  }
};

// Its summary.json section.
io::Json implicit_start_json(const ImplicitStart& i);

// `confining_stress` (Pa) is applied whole along the jump, as the explicit steps apply it.
// Throws solver::ElasticResponseError when the response cannot be computed.
ImplicitStart implicit_start(model::Model& model, solver::Solver& solver,
                             const loading::SpecimenBoundary& boundary, const loading::Stage& stage,
                             double confining_stress);

}  // namespace vorodec::run
