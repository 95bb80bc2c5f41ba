#pragma once
// Quiet (viscous, Lysmer-Kuhlemeyer) boundaries on chosen outline edges of rigid blocks, and a
// stress history applied through them (docs/theory.md §15.1, 15.2): dashpots rho c_p and rho c_s
// per unit area absorb the waves that reach the edge; an input particle velocity v_in(t) enters as
// the traction 2 rho c v_in, the factor 2 offsetting the dashpot, so the edge drives and absorbs.
#include <functional>
#include <vector>

#include "vorodec/loading/boundary.hpp"
#include "vorodec/model/model.hpp"

namespace vorodec::loading {

struct QuietSettings {
  double density;       // kg/m^3 of the medium beyond the edge
  double p_wave_speed;  // m/s
  double s_wave_speed;  // m/s
};

// Input particle velocity (m/s) at time t (s): along the edge's inward normal and along its
// tangent (counter-clockwise along the outline).
struct InputVelocity {
  double normal, shear;
};
using InputHistory = std::function<InputVelocity(double)>;

// The specimen blocks' edges on one side of the specimen's bounding box (platens excluded).
enum class Side { left, right, bottom, top };
std::vector<BoundaryEdge> outline_edges(const model::Model& m, Side side);

class QuietBoundary {
 public:
  QuietBoundary(std::vector<BoundaryEdge> edges, QuietSettings s);
  // These edges carry the input history and absorb as well (do not list them among the
  // absorbing edges too).
  void set_input(std::vector<BoundaryEdge> edges, InputHistory input);
  // Sets the applied loads (Blocks::fx, fy, moment) of every block with a quiet edge to zero;
  // call before other loads are added, then apply().
  void clear_loads(model::Model& m) const;
  // Adds each edge's dashpot force, from the velocity at its midpoint at the half step (what the
  // coming step integrates with), and the input traction at time t s, to its block's loads.
  void apply(model::Model& m, double t) const;

 private:
  std::vector<BoundaryEdge> edges_, input_edges_;
  QuietSettings s_;
  InputHistory input_;
};

}  // namespace vorodec::loading
