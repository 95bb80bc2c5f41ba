#pragma once
// Static linear elastic response of rigid blocks to a prescribed displacement of the held blocks:
// the contact stiffness K (3 DOFs per block) assembled from the laws' springs, factorised once
// with CHOLMOD, solved for the free blocks (docs/theory.md §5.6, linearised about the current
// geometry). The implicit elastic start of a loading stage (drivers/implicit_start) scales this
// unit response up to where the first contact would leave its elastic regime.
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

// One load case's solution.
struct ElasticCase {
  // Per block: displacement (m) and rotation (rad); held blocks as prescribed.
  std::vector<double> ux, uy, utheta;
  // Per contact: force increments (N per m thickness, fn compression positive), zero for open
  // contacts, and the opening (m) of every contact.
  std::vector<double> dfn, dfs, dn;
  // Per block: sum of the contact force increments on it (N, N, N m per m), for the held blocks'
  // reactions (the specimen's stress).
  std::vector<std::array<double, 3>> force;
};

struct ElasticResponse {
  ElasticCase unit;  // the held blocks' unit displacement, no load
  ElasticCase load;  // the applied loads, held blocks still (zero without loads)
  // Largest factor of the rest of the load case (load_left x it) for which every closed contact
  // stays elastic from its current forces; must be >= 1 for the loads to be elastic.
  double load_reach = std::numeric_limits<double>::infinity();
  // Largest factor of the unit case, on top of the rest of the load case, for which every closed
  // contact stays elastic (law elastic_reach); the contact that sets it.
  double reach = std::numeric_limits<double>::infinity();
  std::size_t limiting_contact = std::numeric_limits<std::size_t>::max();
  // Per contact: in K (closed). An open one enters when its gap falls to `touch` (m); the caller
  // stops a jump there and solves again.
  std::vector<char> active;
  double touch = 0;
  std::size_t dofs = 0;
  std::size_t active_contacts = 0;
  int passes = 0;  // factorisations: one more each time open contacts that would pull are dropped
  double factorise_seconds = 0;  // wall time of the CHOLMOD analysis + factorisations
};

// `unit[b]` is the displacement (x, y, theta) of held (prescribed) block b in the unit case,
// `load[b]` the force (x, y, moment; N, N, N m per m) applied to free block b in the load case;
// free blocks follow from equilibrium. Both cases share one factorisation. The contacts' current
// forces (Contact::fn, fs) are the start of the linear path, of which `load_left` (0..1) of the
// load case is still to come. Open contacts are those the applied case pulls: the load case while
// some of it is left, else the unit case. Reads the world arrays: call model::refresh_world first.
ElasticResponse elastic_response(const model::Model& model,
                                 const std::vector<std::unique_ptr<laws::LawGroup>>& laws,
                                 const std::vector<std::array<double, 3>>& unit,
                                 const std::vector<std::array<double, 3>>& load, double load_left);

}  // namespace vorodec::solver
