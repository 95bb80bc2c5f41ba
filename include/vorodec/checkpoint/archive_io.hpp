#pragma once
// cereal itself, for the sources that write or read state, plus pod(): a vector of trivially
// copyable records as one block of bytes (bit-exact and fast, where cereal would visit each
// record's members).
#include <cereal/archives/binary.hpp>
#include <cereal/types/array.hpp>
#include <cereal/types/optional.hpp>
#include <cereal/types/string.hpp>
#include <cereal/types/vector.hpp>
#include <type_traits>
#include <vector>

#include "vorodec/checkpoint/archive.hpp"

namespace vorodec::checkpoint {

template <class T>
struct Pod {
  static_assert(std::is_trivially_copyable_v<T>);
  std::vector<T>& v;
  template <class Archive>
  void serialize(Archive& ar) {
    cereal::size_type n = v.size();
    ar(cereal::make_size_tag(n));
    if constexpr (Archive::is_loading::value) v.resize(static_cast<std::size_t>(n));
    ar(cereal::binary_data(v.data(), static_cast<std::size_t>(n) * sizeof(T)));
  }
};

template <class T>
Pod<T> pod(std::vector<T>& v) {
  return {v};
}
// Saving takes const state: the wrapper only reads it then.
template <class T>
Pod<T> pod(const std::vector<T>& v) {
  return {const_cast<std::vector<T>&>(v)};
}

// One trivially copyable record as its bytes.
template <class T>
auto bytes(T& record) {
  static_assert(std::is_trivially_copyable_v<std::remove_const_t<T>>);
  return cereal::binary_data(const_cast<std::remove_const_t<T>*>(&record), sizeof(T));
}

}  // namespace vorodec::checkpoint
