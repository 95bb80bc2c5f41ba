// T-junction splitting: a vertex lying inside another block's edge is inserted into that edge.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "tessellation_internal.hpp"

namespace vorodec::geometry::detail {

void split_t_junctions(const std::vector<Point>& vertices, Blocks& blocks, double tolerance) {
  if (vertices.empty() || blocks.empty()) return;
  // Uniform grid of about one vertex per cell: each edge looks only at the cells it crosses.
  Point lo = vertices.front(), hi = vertices.front();
  for (const Point p : vertices) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  const double h =
      std::max(std::sqrt((hi.x - lo.x) * (hi.y - lo.y) / static_cast<double>(vertices.size())),
               1e3 * tolerance);
  const auto cell = [&](double t, double origin) {
    return static_cast<std::int64_t>(std::floor((t - origin) / h));
  };
  const std::int64_t nx = cell(hi.x, lo.x) + 1;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> grid;
  for (std::uint32_t v = 0; v < vertices.size(); ++v)
    grid[cell(vertices[v].y, lo.y) * nx + cell(vertices[v].x, lo.x)].push_back(v);

  std::vector<std::pair<double, std::uint32_t>> inside;
  for (Block& block : blocks) {
    Block split;
    split.reserve(block.size());
    for (std::size_t i = 0; i < block.size(); ++i) {
      const std::uint32_t a = block[i], b = block[(i + 1) % block.size()];
      split.push_back(a);
      const Point pa = vertices[a], d = vertices[b] - pa;
      const double len2 = dot(d, d);
      inside.clear();
      const std::int64_t i0 = cell(std::min(pa.x, pa.x + d.x) - tolerance, lo.x);
      const std::int64_t i1 = cell(std::max(pa.x, pa.x + d.x) + tolerance, lo.x);
      const std::int64_t j0 = cell(std::min(pa.y, pa.y + d.y) - tolerance, lo.y);
      const std::int64_t j1 = cell(std::max(pa.y, pa.y + d.y) + tolerance, lo.y);
      for (std::int64_t j = j0; j <= j1; ++j) {
        for (std::int64_t k = i0; k <= i1; ++k) {
          const auto found = grid.find(j * nx + k);
          if (found == grid.end()) continue;
          for (const std::uint32_t v : found->second) {
            if (v == a || v == b) continue;
            const Point r = vertices[v] - pa;
            const double t = dot(r, d) / len2;
            if (t <= 0 || t >= 1) continue;
            if (std::abs(cross(d, r)) <= tolerance * std::sqrt(len2)) inside.push_back({t, v});
          }
        }
      }
      std::sort(inside.begin(), inside.end());
      for (const auto& [t, v] : inside) split.push_back(v);
    }
    block = std::move(split);
  }
}

}  // namespace vorodec::geometry::detail
