#pragma once
// Fragments at the end of a test: the specimen's blocks joined by bonds that have not failed
// (a union-find over the bonded contacts), each fragment's area the sum of its blocks'.
#include <vector>

#include "vorodec/model/model.hpp"

namespace vorodec::measure {

// m^2 per fragment, largest first.
std::vector<double> fragment_areas(const model::Model& m);

}  // namespace vorodec::measure
