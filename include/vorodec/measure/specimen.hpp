#pragma once
// Specimen-scale stress and strain from platen reactions and boundary gauges
// (docs/theory.md §11.1), in the rock-mechanics convention: compression and shortening positive.
#include <span>

#include "vorodec/loading/boundary.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::measure {

struct SpecimenState {
  double axial_strain = 0;       // shortening positive
  double axial_stress = 0;       // Pa, from the platen reactions
  double lateral_strain = 0;     // expansion negative
  double volumetric_strain = 0;  // axial + lateral (2D)
};

// Pa, compression positive: the mean of the vertical contact forces on the top and bottom platens
// (N per m of thickness; the specimen pushes the top one up, the bottom one down) over the width.
double platen_stress(double top_fy, double bottom_fy, const loading::SpecimenBoundary& boundary,
                     double thickness);

SpecimenState measure_specimen(const model::Model& model, const loading::SpecimenBoundary& boundary,
                               const solver::Solver& solver);

struct ElasticConstants {
  double youngs_modulus = 0;  // Pa, tangent modulus at 50 % of peak (fit over 40-60 %)
  double poisson_ratio = 0;
  // The linear range's: fit over 10-30 % of peak, before cracks open (a cyclic test's first
  // loading to 20 % sees it).
  double initial_poisson_ratio = 0;
  bool valid = false;
};

// Fits the loading branch before the peak between 40 % and 60 % of the peak stress (ISRM 1979),
// and between 10 % and 30 % for the initial ratio.
ElasticConstants elastic_constants(std::span<const double> axial_strain,
                                   std::span<const double> axial_stress,
                                   std::span<const double> lateral_strain);

}  // namespace vorodec::measure
