#pragma once
// Cell-grid broad phase and rounded corner-edge narrow phase (PHYSICS 2.4). Keeps the state of
// persisting contacts, drops separated ones (never intact bonded ones), creates new ones.
#include <array>
#include <memory>
#include <vector>

#include "vorodec/laws/contact_law.hpp"
#include "vorodec/model/model.hpp"

namespace vorodec::solver {

// Which law group a pair of body groups uses (-1: the pair never interacts).
struct LawTable {
  std::array<std::array<int, 3>, 3> law{{{-1, -1, -1}, {-1, -1, -1}, {-1, -1, -1}}};
  // Which group pairs bond where they touch in the initial state (specimen-specimen; and
  // specimen-platen for bonded platens).
  std::array<std::array<bool, 3>, 3> bond{
      {{true, false, false}, {false, false, false}, {false, false, false}}};
  int for_pair(model::Group a, model::Group b) const {
    return law[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)];
  }
  bool bonds(model::Group a, model::Group b) const {
    return bond[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)];
  }
};

struct DetectionStats {
  std::size_t created = 0, deleted = 0, kept = 0;
};

class ContactDetector {
 public:
  ContactDetector(double tolerance, LawTable table) : tolerance_(tolerance), table_(table) {}

  // Refreshes model.contacts (sorted by law, then corner owner) and every law's arrays. With
  // `bond_new` the contacts it creates are bonded (the initial tessellation).
  DetectionStats detect(model::Model& model, std::vector<std::unique_ptr<laws::LawGroup>>& laws,
                        bool bond_new);

  double tolerance() const { return tolerance_; }

 private:
  double tolerance_;
  LawTable table_;
  std::uint64_t next_id_ = 0;
};

// Candidate block pairs (a < b) whose boxes, enlarged by `margin`, overlap.
std::vector<std::pair<std::uint32_t, std::uint32_t>> broad_phase(const model::Blocks& blocks,
                                                                 double margin);

}  // namespace vorodec::solver
