#pragma once
// In-situ stress (docs/loading.md, "In-situ stress"): a stress field, compression positive, linear
// in depth below a datum, set into the initial contacts (run/prepare_model) so that the model
// starts in equilibrium, and held on the lateral sides as their traction.
#include <array>
#include <limits>

#include "vorodec/model/model.hpp"

namespace vorodec::loading {

struct StressTensor {
  double xx, yy, xy;  // Pa, compression positive
};

struct InSituStress {
  StressTensor stress{0, 0, 0};    // Pa, at the datum
  StressTensor gradient{0, 0, 0};  // Pa/m, increase per metre of depth below the datum
  double datum_y = std::numeric_limits<double>::quiet_NaN();  // m; NaN: the specimen's top

  StressTensor at(double y) const {
    const double depth = datum_y - y;
    return {stress.xx + gradient.xx * depth, stress.yy + gradient.yy * depth,
            stress.xy + gradient.xy * depth};
  }
};

// m, the highest corner of the specimen blocks.
double specimen_top(const model::Model& model);
// The field with its datum resolved (NaN: the specimen's top).
InSituStress resolved(InSituStress field, const model::Model& model);

}  // namespace vorodec::loading
