#pragma once
// The specimen's boundary: platens, lateral edges for confinement and strain gauges.
#include <cstdint>
#include <vector>

#include "vorodec/loading/in_situ.hpp"
#include "vorodec/model/model.hpp"

namespace vorodec::loading {

// An edge of the initial lateral outline: block and the corner where the edge starts.
struct BoundaryEdge {
  std::uint32_t block;
  std::uint32_t corner;
};

class SpecimenBoundary {
 public:
  // Finds platens, the lateral outline edges (left and right of the initial box) and the gauge
  // blocks (lateral boundary blocks in the middle third of the height).
  explicit SpecimenBoundary(const model::Model& model);

  // Confining traction on the lateral edges, recomputed from the current geometry (follower load).
  void apply_confinement(model::Model& model, double sigma3) const;
  // The in-situ stress's traction on the lateral edges, at each edge's midpoint (follower load).
  void apply_stress(model::Model& model, const InSituStress& field) const;
  // v: the closing speed (m/s, shortening +), all on the top platen or half on each.
  void set_platen_velocity(model::Model& model, double v, bool both = false) const;

  double width() const { return width_; }    // m, initial
  double height() const { return height_; }  // m, initial
  int top_platen() const { return top_; }
  int bottom_platen() const { return bottom_; }
  // The platens are the first blocks of block bars: the specimen's force on them is only part
  // of their contact forces.
  bool platens_in_bars() const { return in_bars_; }
  const std::vector<BoundaryEdge>& lateral_edges() const { return edges_; }
  const std::vector<std::uint32_t>& left_gauges() const { return left_; }
  const std::vector<std::uint32_t>& right_gauges() const { return right_; }

 private:
  double width_ = 0, height_ = 0;
  int top_ = -1, bottom_ = -1;
  bool in_bars_ = false;
  std::vector<BoundaryEdge> edges_;
  std::vector<std::uint32_t> left_, right_;
};

}  // namespace vorodec::loading
