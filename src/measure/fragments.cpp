#include "vorodec/measure/fragments.hpp"

#include <algorithm>
#include <functional>
#include <numeric>

namespace vorodec::measure {

std::vector<double> fragment_areas(const model::Model& m) {
  const auto& bl = m.blocks;
  std::vector<std::uint32_t> root(bl.size());
  std::iota(root.begin(), root.end(), 0u);
  const auto find = [&](std::uint32_t b) {
    while (root[b] != b) b = root[b] = root[root[b]];
    return b;
  };
  using model::ContactState;
  for (const model::Contact& c : m.contacts) {
    if (!c.bonded || c.state == ContactState::tensile_failed ||
        c.state == ContactState::shear_failed)
      continue;
    const auto a = static_cast<std::uint32_t>(c.a), b = static_cast<std::uint32_t>(c.b);
    if (bl.group[a] != model::Group::specimen || bl.group[b] != model::Group::specimen) continue;
    root[std::max(find(a), find(b))] = std::min(find(a), find(b));
  }
  std::vector<double> area(bl.size(), 0.0);
  for (std::uint32_t b = 0; b < bl.size(); ++b) {
    if (bl.group[b] != model::Group::specimen) continue;
    double a = 0;
    for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c)
      a += 0.5 * cross(bl.corner[c], bl.corner[bl.next_corner(b, c)]);
    area[find(b)] += a;
  }
  std::vector<double> out;
  for (const double a : area)
    if (a > 0) out.push_back(a);
  std::sort(out.begin(), out.end(), std::greater<>());
  return out;
}

}  // namespace vorodec::measure
