#pragma once
// The archives a checkpoint's state passes through (cereal's binary archives), declared only:
// headers that expose save/load pairs need no cereal include.
namespace cereal {
class BinaryOutputArchive;
class BinaryInputArchive;
}  // namespace cereal

namespace vorodec::checkpoint {

using OutArchive = cereal::BinaryOutputArchive;
using InArchive = cereal::BinaryInputArchive;

}  // namespace vorodec::checkpoint
