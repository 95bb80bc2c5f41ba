#pragma once
// Voronoi tessellation of a specimen outline. CGAL stays inside src/geometry/voronoi_builder.cpp.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "vorodec/geometry/point.hpp"

namespace vorodec::geometry {

enum class OutlineKind { rectangle, disc };

struct Outline {
  OutlineKind kind = OutlineKind::rectangle;
  double width = 0.0;       // m, rectangle: lower-left corner at (0, 0)
  double height = 0.0;      // m
  double diameter = 0.0;    // m, disc: centre at (diameter/2, diameter/2)
  int disc_segments = 0;    // straight segments approximating the disc; 0 = chosen from block size
  double flat_angle = 0.0;  // rad, disc: angle each loading flat (top, bottom) subtends; 0 = round
};

struct TessellationSettings {
  Outline outline;
  double mean_edge_length =
      0.0;              // m, target measured mean Voronoi edge length (0 = use block_count)
  int block_count = 0;  // target number of blocks (0 = use mean_edge_length)
  std::uint64_t seed = 1;
  int lloyd_iterations = 0;      // centroidal (Lloyd) relaxation sweeps
  double min_edge_length = 0.0;  // m, shorter edges are collapsed to a point
};

struct SpecimenReport {
  std::size_t blocks = 0;
  std::size_t shared_edges = 0;    // edges between two blocks (each gives two point contacts)
  std::size_t boundary_edges = 0;  // edges on the outline
  double edge_min = 0, edge_mean = 0, edge_max = 0;  // m
  double area_min = 0, area_mean = 0, area_max = 0;  // m^2
  double smallest_angle_deg = 0;                     // smallest interior angle of any block
  std::size_t edges_collapsed = 0;
  double outline_area = 0;            // m^2, of the (polygonal) outline
  std::vector<std::string> warnings;  // one line per alteration or suspicious feature
};

// Blocks as counter-clockwise index lists into a shared vertex table: neighbouring blocks share
// vertex indices exactly, so shared edges are found by index. Blocks are numbered along a
// Hilbert curve of their centroids (memory locality in the solver).
struct Tessellation {
  std::vector<Point> vertices;
  std::vector<std::vector<std::uint32_t>> blocks;
  SpecimenReport report;
  // Grain-based specimens only (empty otherwise): the grain of each block, the mineral of each
  // grain (index into the model file's minerals) and the area of each mineral (m^2).
  std::vector<std::int32_t> block_grain;
  std::vector<std::int32_t> grain_mineral;
  std::vector<double> mineral_area;
  // Jointed specimens only (geometry/joints.hpp): each block pair a < b whose shared edge lies on
  // a joint trace, with the trace's set and the edge's length (m).
  struct JointEdge {
    std::uint32_t a = 0, b = 0;
    std::int32_t set = 0;
    double length = 0;
  };
  std::vector<JointEdge> joint_edges;
};

class GeometryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws GeometryError for impossible input (non-positive size, fewer than 2 blocks, edge limits
// that cannot be met).
Tessellation tessellate(const TessellationSettings& settings);

// The report of an existing tessellation (e.g. a prepared specimen file); the outline area is
// taken as the sum of the block areas.
SpecimenReport describe_specimen(const Tessellation& tess);

// Multi-line, human-readable specimen report (printed after building).
std::string format_report(const SpecimenReport& report);

}  // namespace vorodec::geometry
