#pragma once
// Static linear elastic response of rigid blocks to a prescribed displacement of the held blocks:
// the contact stiffness K (3 DOFs per block) assembled from the laws' springs, factorised once
// with CHOLMOD, solved for the free blocks (PHYSICS 3, linearised about the current geometry). The
// implicit elastic start of a loading stage (app/implicit_start) scales this unit response up to
// where the first contact would leave its elastic regime.
#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "vorodec/laws/contact_law.hpp"
#include "vorodec/model/model.hpp"

namespace vorodec::solver {

// The response cannot be computed: a law without linear springs, deformable blocks, or a
// singular stiffness (a block not held). The message says which.
class ElasticResponseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ElasticResponse {
  // Per block: displacement (m) and rotation (rad) for the unit case; held blocks as prescribed.
  std::vector<double> ux, uy, utheta;
  // Per contact: force increments (N per m thickness, fn compression positive) of the unit case.
  std::vector<double> dfn, dfs;
  // Per block: sum of the contact force increments on it (N, N, N m per m), for the held blocks'
  // reactions (the specimen's stress).
  std::vector<std::array<double, 3>> force;
  // Largest factor of the unit case for which every contact stays elastic (law elastic_reach),
  // no open contact closes and no active one opens; the contact that sets it.
  double reach = std::numeric_limits<double>::infinity();
  std::size_t limiting_contact = std::numeric_limits<std::size_t>::max();
  bool limit_is_closing = false;  // the limiting contact is an open one that closes
  std::size_t dofs = 0;
  std::size_t active_contacts = 0;
  int passes = 0;                // solves: open contacts that would pull are dropped, then again
  double factorise_seconds = 0;  // wall time of the CHOLMOD analysis + factorisations
};

// `unit[b]` is the displacement (x, y, theta) of held (prescribed) block b in the unit case; free
// blocks follow from equilibrium. The contacts' current forces (Contact::fn, fs) are the start of
// the linear path. Reads the world arrays: call model::refresh_world first.
ElasticResponse elastic_response(const model::Model& model,
                                 const std::vector<std::unique_ptr<laws::LawGroup>>& laws,
                                 const std::vector<std::array<double, 3>>& unit);

}  // namespace vorodec::solver
