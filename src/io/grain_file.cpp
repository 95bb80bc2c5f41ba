#include "vorodec/io/grain_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <string_view>

#include "vorodec/io/csv_fields.hpp"
#include "vorodec/io/input_error.hpp"

namespace vorodec::io {
namespace {

double twice_area(const std::vector<geometry::Point>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) a += cross(p[i], p[(i + 1) % p.size()]);
  return a;
}

bool segments_cross(geometry::Point a, geometry::Point b, geometry::Point c, geometry::Point d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

bool self_intersecting(const std::vector<geometry::Point>& p) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (segments_cross(p[i], p[(i + 1) % n], p[j], p[(j + 1) % n])) return true;
    }
  return false;
}

}  // namespace

std::vector<geometry::Grain> read_grain_file(const std::filesystem::path& file,
                                             std::span<const std::string> minerals) {
  std::ifstream in(file);
  if (!in) throw ModelFileError(fmt::format("{}: cannot open grain file", file.string()));
  std::vector<geometry::Grain> grains;
  std::vector<int> first_line;
  std::string current_id, line;
  std::set<std::string, std::less<>> seen;
  int line_no = 0;
  const auto fail = [&](int at, const std::string& what) {
    throw ModelFileError(fmt::format("{}:{}: {}", file.string(), at, what));
  };
  const auto close_grain = [&] {
    if (grains.empty()) return;
    auto& c = grains.back().corners;
    if (c.size() < 3)
      fail(first_line.back(), fmt::format("grain '{}' has fewer than 3 corners", current_id));
    if (std::abs(twice_area(c)) <= 0)
      fail(first_line.back(), fmt::format("grain '{}' has no area", current_id));
    if (self_intersecting(c))
      fail(first_line.back(), fmt::format("grain '{}': its boundary crosses itself", current_id));
  };
  while (std::getline(in, line)) {
    ++line_no;
    const std::string_view row = trim(line);
    if (row.empty() || row.front() == '#') continue;
    const auto f = split_fields(row);
    if (f.size() != 4)
      fail(line_no, fmt::format("expected 4 fields 'grain_id,mineral,x,y', got {}", f.size()));
    if (grains.empty() && f[0] == "grain_id") continue;  // header row
    geometry::Point p;
    if (!parse_double(f[2], p.x) || !parse_double(f[3], p.y))
      fail(line_no, fmt::format("x and y must be numbers in m (got '{}', '{}')", f[2], f[3]));
    const auto mineral = std::find(minerals.begin(), minerals.end(), f[1]);
    if (mineral == minerals.end()) {
      std::string known;
      for (const auto& m : minerals) known += fmt::format(" '{}'", m);
      fail(line_no, fmt::format("unknown mineral '{}' (the model file's [[mineral]] names:{})",
                                f[1], known));
    }
    const auto m = static_cast<std::int32_t>(mineral - minerals.begin());
    if (grains.empty() || f[0] != current_id) {
      close_grain();
      if (!seen.insert(std::string(f[0])).second)
        fail(line_no,
             fmt::format("grain '{}' appears again: list each grain's corners together", f[0]));
      current_id = std::string(f[0]);
      grains.push_back({{}, m});
      first_line.push_back(line_no);
    } else if (grains.back().mineral != m) {
      fail(line_no, fmt::format("grain '{}' changes its mineral", current_id));
    }
    grains.back().corners.push_back(p);
  }
  close_grain();
  if (grains.size() < 1) fail(line_no, "no grains in the file");
  return grains;
}

}  // namespace vorodec::io
