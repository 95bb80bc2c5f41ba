#include "vorodec/measure/cycles.hpp"

#include <algorithm>

namespace vorodec::measure {

double work_along(std::span<const HistoryPoint> rows) {
  double w = 0;
  for (std::size_t i = 1; i < rows.size(); ++i)
    w += 0.5 * (rows[i].axial_stress + rows[i - 1].axial_stress) *
         (rows[i].axial_strain - rows[i - 1].axial_strain);
  return w;
}

namespace {
// The rows of one stage: its start row through its end row (contiguous in the history).
std::span<const HistoryPoint> stage_rows(std::span<const HistoryPoint> rows, int stage) {
  const auto first = std::find_if(rows.begin(), rows.end(),
                                  [&](const HistoryPoint& p) { return p.stage == stage; });
  const auto last =
      std::find_if(first, rows.end(), [&](const HistoryPoint& p) { return p.stage != stage; });
  return {first, last};
}
}  // namespace

std::vector<CycleMeasures> cycle_measures(std::span<const HistoryPoint> rows,
                                          std::span<const loading::Stage> stages,
                                          const std::vector<bool>& stalled) {
  std::vector<CycleMeasures> out;
  double total = 0;
  for (std::size_t s = 0; s + 1 < stages.size(); ++s) {
    const loading::Stage& load = stages[s];
    if (load.phase != loading::CyclePhase::loading) continue;
    const auto up = stage_rows(rows, static_cast<int>(s));
    const auto down = stage_rows(rows, static_cast<int>(s + 1));
    if (up.size() < 2 || down.size() < 2) break;  // the run ended inside this cycle
    CycleMeasures m;
    m.cycle = load.cycle;
    m.upper_target = load.end.axial_stress;
    m.stalled = stalled[s];
    const auto top = std::max_element(up.begin(), up.end(), [](const auto& a, const auto& b) {
      return a.axial_stress < b.axial_stress;
    });
    m.upper_reached = top->axial_stress;
    const HistoryPoint& a = up.front();
    const double de = top->axial_strain - a.axial_strain;
    if (de != 0) {
      m.secant_modulus = (top->axial_stress - a.axial_stress) / de;
      m.poisson_ratio = -(top->lateral_strain - a.lateral_strain) / de;
    }
    m.input_work = work_along(up);
    m.recovered_work = -work_along(down);
    m.dissipated_work = m.input_work - m.recovered_work;
    total += m.dissipated_work;
    m.dissipated_total = total;
    m.residual_strain = down.back().axial_strain;
    out.push_back(m);
  }
  return out;
}

}  // namespace vorodec::measure
