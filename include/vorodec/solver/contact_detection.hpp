#pragma once
// Cell-grid broad phase and rounded corner-edge narrow phase (docs/theory.md §5.5). Keeps the state
// of persisting contacts, drops separated ones (never intact bonded ones), creates new ones.
#include <array>
#include <memory>
#include <unordered_map>
#include <vector>

#include "vorodec/laws/contact_law.hpp"
#include "vorodec/model/model.hpp"
#include "vorodec/model/weibull.hpp"

namespace vorodec::solver {

// Grain-based specimens: a specimen-specimen contact takes the law of its grains' minerals,
// transgranular inside one grain, intergranular between two. Decided once per contact when it is
// created, so the step loop pays nothing.
struct GrainLaws {
  std::vector<std::int32_t> grain_of_block;    // specimen blocks [0, n); empty: no grains
  std::vector<std::int32_t> mineral_of_grain;  // index into the minerals
  std::size_t minerals = 0;
  std::vector<int> transgranular;  // law group per mineral
  std::vector<int> intergranular;  // law group per mineral pair: a * minerals + b (symmetric)
};

// Which law group a pair of body groups uses (-1: the pair never interacts).
struct LawTable {
  using Row = std::array<int, model::kGroups>;
  static constexpr Row none{-1, -1, -1, -1, -1, -1};
  std::array<Row, model::kGroups> law{none, none, none, none, none, none};
  // Which group pairs bond where they touch in the initial state (specimen-specimen; and
  // specimen-platen for bonded platens; within a block bar).
  std::array<std::array<bool, model::kGroups>, model::kGroups> bond{{{true}}};
  int for_pair(model::Group a, model::Group b) const {
    return law[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)];
  }
  bool bonds(model::Group a, model::Group b) const {
    return bond[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)];
  }
  GrainLaws grains;
  // Specimen joints of a non-grain specimen given to a second law: a block pair takes `law` when
  // its keyed uniform variate is below `fraction` (every point contact of the joint alike).
  struct Mix {
    int law = -1;
    double fraction = 0;
    std::uint64_t seed = 0;
  } mix;
  // Jointed specimens: a block pair (key joint_key(a, b)) whose shared edge lies on a joint takes
  // its set's law group.
  std::unordered_map<std::uint64_t, int> joints;
  int joint_set_law = -1;  // the law group of the first [[joint_set]]; set k has this + k
  static std::uint64_t joint_key(std::uint32_t a, std::uint32_t b) {
    return std::uint64_t{std::min(a, b)} << 32 | std::max(a, b);
  }
  // The law group of blocks a and b.
  int for_blocks(const model::Blocks& bl, std::uint32_t a, std::uint32_t b) const {
    const int l = for_pair(bl.group[a], bl.group[b]);
    if (!joints.empty() && bl.group[a] == model::Group::specimen &&
        bl.group[b] == model::Group::specimen) {
      const auto it = joints.find(joint_key(a, b));
      return it == joints.end() ? l : it->second;
    }
    if (mix.law >= 0 && bl.group[a] == model::Group::specimen &&
        bl.group[b] == model::Group::specimen)
      return model::keyed_uniform(mix.seed, std::min(a, b), std::max(a, b)) < mix.fraction ? mix.law
                                                                                           : l;
    if (grains.grain_of_block.empty() || bl.group[a] != model::Group::specimen ||
        bl.group[b] != model::Group::specimen)
      return l;
    const std::int32_t ga = grains.grain_of_block[a], gb = grains.grain_of_block[b];
    const auto ma = static_cast<std::size_t>(grains.mineral_of_grain[static_cast<std::size_t>(ga)]);
    const auto mb = static_cast<std::size_t>(grains.mineral_of_grain[static_cast<std::size_t>(gb)]);
    return ga == gb ? grains.transgranular[ma] : grains.intergranular[ma * grains.minerals + mb];
  }
};

struct DetectionStats {
  std::size_t created = 0, deleted = 0, kept = 0;
};

class ContactDetector {
 public:
  ContactDetector(double tolerance, LawTable table) : tolerance_(tolerance), table_(table) {}
  const LawTable& law_table() const { return table_; }

  // Refreshes model.contacts (sorted by law, then corner owner) and every law's arrays. With
  // `bond_new` the contacts it creates are bonded (the initial tessellation).
  DetectionStats detect(model::Model& model, std::vector<std::unique_ptr<laws::LawGroup>>& laws,
                        bool bond_new);

  double tolerance() const { return tolerance_; }
  // The id the next created contact takes (checkpoints).
  std::uint64_t next_id() const { return next_id_; }
  void set_next_id(std::uint64_t id) { next_id_ = id; }

 private:
  double tolerance_;
  LawTable table_;
  std::uint64_t next_id_ = 0;
};

}  // namespace vorodec::solver
