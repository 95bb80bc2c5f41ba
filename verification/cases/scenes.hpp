#pragma once
// Small hand-built scenes for the analytic tests: squares joined by one law.
#include <memory>
#include <vector>

#include "vorodec/laws/contact_law.hpp"
#include "vorodec/model/build.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::verification {

inline std::vector<model::Point> square(double x0, double y0, double size) {
  return {{x0, y0}, {x0 + size, y0}, {x0 + size, y0 + size}, {x0, y0 + size}};
}

inline laws::LawParams params(std::initializer_list<std::pair<const char*, double>> values) {
  laws::LawParams p;
  for (const auto& [k, v] : values) p[k] = model::Distribution::constant(v);
  return p;
}

// A solver over `model` where every pair of groups uses `law` (index 0).
inline std::unique_ptr<solver::Solver> make_solver(model::Model& m, const char* law,
                                                   const laws::LawParams& p,
                                                   solver::SolverSettings s) {
  std::vector<std::unique_ptr<laws::LawGroup>> groups;
  groups.push_back(laws::find_law(law)->make(p, 7));
  solver::LawTable table;
  for (auto& row : table.law) row.fill(0);
  table.law[1][1] = table.law[1][2] = table.law[2][1] = table.law[2][2] = -1;
  const auto gone = static_cast<std::size_t>(model::Group::excavated);
  for (std::size_t g = 0; g < model::kGroups; ++g) table.law[g][gone] = table.law[gone][g] = -1;
  if (s.contact_tolerance <= 0) s.contact_tolerance = m.rounding_length;
  auto solver = std::make_unique<solver::Solver>(m, std::move(groups), table, s);
  solver->initialise();
  return solver;
}

}  // namespace vorodec::verification
