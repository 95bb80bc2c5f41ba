#include "vorodec/loading/in_situ.hpp"

#include <algorithm>
#include <cmath>

namespace vorodec::loading {

double specimen_top(const model::Model& model) {
  const auto& bl = model.blocks;
  double top = -std::numeric_limits<double>::infinity();
  for (std::uint32_t b = 0; b < bl.size(); ++b) {
    if (bl.group[b] != model::Group::specimen) continue;
    for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c)
      top = std::max(top, bl.y[b] + bl.corner[c].y);
  }
  return top;
}

InSituStress resolved(InSituStress field, const model::Model& model) {
  if (std::isnan(field.datum_y)) field.datum_y = specimen_top(model);
  return field;
}

}  // namespace vorodec::loading
