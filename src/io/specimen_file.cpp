#include "vorodec/io/specimen_file.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "vorodec/io/input_error.hpp"

namespace vorodec::io {

namespace {
constexpr const char* magic = "vorodec-specimen 1";
}

void write_specimen(const std::filesystem::path& file, const geometry::Tessellation& tess,
                    const std::string& contacts_table) {
  std::ofstream out(file);
  if (!out) throw std::runtime_error(fmt::format("cannot write specimen file '{}'", file.string()));
  out << magic << "\n# vertices: x y (m, hexadecimal floating point)\nvertices "
      << tess.vertices.size() << "\n";
  for (const auto& v : tess.vertices) out << fmt::format("{:a} {:a}\n", v.x, v.y);
  out << "# blocks: corner count, then vertex indices counter-clockwise\nblocks "
      << tess.blocks.size() << "\n";
  for (const auto& b : tess.blocks) {
    out << b.size();
    for (auto i : b) out << ' ' << i;
    out << '\n';
  }
  std::istringstream table(contacts_table);
  for (std::string line; std::getline(table, line);) out << "# " << line << '\n';
}

geometry::Tessellation read_specimen(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw ModelFileError(fmt::format("{}: cannot open specimen file", file.string()));
  int line_no = 0;
  std::string line;
  const auto fail = [&](const std::string& what) {
    throw ModelFileError(fmt::format("{}:{}: {}", file.string(), line_no, what));
  };
  const auto next = [&]() {
    while (std::getline(in, line)) {
      ++line_no;
      if (!line.empty() && line[0] != '#') return true;
    }
    return false;
  };
  if (!next() || line != magic)
    fail(fmt::format("not a vorodec specimen file (expected '{}')", magic));
  geometry::Tessellation t;
  std::size_t n = 0;
  if (!next() || std::sscanf(line.c_str(), "vertices %zu", &n) != 1) fail("expected 'vertices N'");
  t.vertices.resize(n);
  for (auto& v : t.vertices) {
    if (!next()) fail("unexpected end of file in vertices");
    char* end = nullptr;
    v.x = std::strtod(line.c_str(), &end);
    const char* rest = end;
    v.y = std::strtod(rest, &end);
    if (end == rest) fail("expected two coordinates");
  }
  if (!next() || std::sscanf(line.c_str(), "blocks %zu", &n) != 1) fail("expected 'blocks N'");
  t.blocks.resize(n);
  for (auto& b : t.blocks) {
    if (!next()) fail("unexpected end of file in blocks");
    std::istringstream row(line);
    std::size_t k = 0;
    row >> k;
    b.resize(k);
    for (auto& i : b) {
      if (!(row >> i) || i >= t.vertices.size()) fail("bad vertex index");
    }
    if (k < 3) fail("a block needs at least 3 corners");
  }
  t.report = geometry::describe_specimen(t);
  return t;
}

}  // namespace vorodec::io
