#include <stdexcept>

#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/model/model.hpp"

namespace vorodec::model {

// A member added to the model is either state a checkpoint carries (save and load it in state()
// below) or comes again from the model file or the loaded state (say so there); then update these
// sizes.
static_assert(sizeof(Blocks) == 624, "Blocks changed: see state()");
static_assert(sizeof(Zoning) == 1176, "Zoning changed: see state()");
static_assert(sizeof(Model) == 1840, "Model changed: see state()");
static_assert(sizeof(Contact) == 88, "Contact changed: see state()");

namespace {

// One list for both directions, so a saved field is a loaded field.
template <class Archive, class M>
void state(Archive& ar, M& m) {
  using checkpoint::pod;
  auto& b = m.blocks;
  ar(pod(b.x), pod(b.y), pod(b.theta), pod(b.vx), pod(b.vy), pod(b.omega), pod(b.mass),
     pod(b.inertia), pod(b.fx), pod(b.fy), pod(b.moment), pod(b.prescribed));
  ar(pod(b.group));  // an excavation stage moves blocks to Group::excavated
  // The world arrays are those of the last step's start, which outputs read: saved, not redone.
  ar(pod(b.cos_t), pod(b.sin_t), pod(b.world), pod(b.kin));
  // Deformable blocks' corner arcs and edge constants follow their gridpoints.
  ar(pod(b.shape));
  ar(pod(m.contacts));
  // The zones' and corners' arrays (the in-situ stress too) come again from the model file, and
  // their scratch is redone in every step; the displacements of the last force pass hold the
  // zones' stress and strain.
  auto& z = m.zoning;
  ar(pod(z.x), pod(z.y), pod(z.vx), pod(z.vy), pod(z.mass), pod(z.fx), pod(z.fy), pod(z.cfx),
     pod(z.cfy), pod(z.prescribed), pod(z.arrays.ux), pod(z.arrays.uy));
}

}  // namespace

void save_state(checkpoint::OutArchive& ar, const Model& m) {
  state(ar, m);
}

void load_state(checkpoint::InArchive& ar, Model& m) {
  const std::size_t blocks = m.blocks.size(), gridpoints = m.zoning.gridpoints();
  state(ar, m);
  if (m.blocks.size() != blocks || m.zoning.gridpoints() != gridpoints)
    throw std::runtime_error("the checkpoint's model has other blocks or gridpoints");
}

}  // namespace vorodec::model
