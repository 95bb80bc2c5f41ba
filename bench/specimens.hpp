#pragma once
// The specimens the benchmarks step: the default model and larger ones of its block size.
#include <cmath>
#include <string>

#include "vorodec/drivers/registry.hpp"

namespace vorodec::bench {

inline io::ModelConfig default_model() {
  return run::read_model_file(std::string(VORODEC_SOURCE_DIR) + "/models/ucs_marble.toml");
}

// The default model's material on a specimen twice as high as wide with `blocks` blocks of the
// default model's size.
inline io::ModelConfig scaled_model(int blocks) {
  io::ModelConfig cfg = default_model();
  const double area_per_block = 0.05 * 0.1 / 1302.0;
  const double width = std::sqrt(area_per_block * blocks / 2.0);
  cfg.tessellation.outline.width = width;
  cfg.tessellation.outline.height = 2.0 * width;
  cfg.tessellation.block_count = blocks;
  return cfg;
}

}  // namespace vorodec::bench
