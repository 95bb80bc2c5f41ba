#pragma once
// ParaView output: one .vtp per output time for blocks, contacts and cracks (and one .vti for a
// damage grid), tied together by .pvd collections. VTK stays inside src/io/vtk_writer.cpp.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "vorodec/geometry/point.hpp"

namespace vorodec::io {

// Cell data on a regular grid of square cells (written as VTK image data).
struct VtkGrid {
  geometry::Point origin;  // m, lower-left corner
  double cell = 0.0;       // m, cell side
  std::size_t nx = 0, ny = 0;
  struct Field {
    std::string name;
    std::vector<double> values;  // nx * ny, cell (i, j) at i + nx * j
  };
  std::vector<Field> fields;
};

// Everything a writer needs of one output time, already in world coordinates; writers never read
// the model itself.
struct VtkFrame {
  double time = 0.0;  // s
  // Blocks as polygons: block b has corners block_points[block_offsets[b] .. block_offsets[b+1]).
  std::vector<geometry::Point> block_points;
  std::vector<std::uint32_t> block_offsets;
  std::vector<std::int32_t> block_id, block_group;
  std::vector<geometry::Point> block_velocity;      // m/s
  std::vector<geometry::Point> block_displacement;  // m
  std::vector<double> block_failed_fraction;        // per block, or empty: not written
  // Grain-based specimens: grain and mineral index per block (-1 platens), or empty.
  std::vector<std::int32_t> block_grain, block_mineral;
  // Optional, per block: 1 leaves it out of the file (a block an excavation removed).
  std::vector<std::uint8_t> block_hidden;
  // Contacts as line segments from block A's centroid to block B's centroid through the contact
  // point.
  std::vector<geometry::Point> contact_point;         // m
  std::vector<geometry::Point> contact_a, contact_b;  // centroids of the two blocks, m
  std::vector<double> contact_normal_force,
      contact_shear_force;  // N (per m thickness), compression +
  std::vector<std::int32_t>
      contact_state;  // ContactState as int: 0 intact, 1 slipping, 2 tensile, 3 shear
  // Cracks (failed contacts) as segments centred on the failure point.
  std::vector<geometry::Point> crack_begin, crack_end;
  std::vector<std::int32_t> crack_type;  // 1 tensile, 2 shear
  std::vector<double> crack_time;        // s
  // Grain-based specimens, or empty: 1 intergranular tensile, 2 intergranular shear,
  // 3 transgranular tensile, 4 transgranular shear.
  std::vector<std::int32_t> crack_class;
  // Damage grid; nx = 0: none. Either every frame of a series has one or none has.
  VtkGrid grid;
  // Zones of the deformable blocks as triangles, corners zone_points[3 z .. 3 z + 2]; empty: none
  // (then no zones series is written). Stress tension positive (Pa), strain tensorial.
  std::vector<geometry::Point> zone_points;
  std::vector<std::int32_t> zone_block;
  std::vector<std::array<double, 4>> zone_stress;  // xx, yy, xy, zz
  std::vector<std::array<double, 3>> zone_strain;  // xx, yy, xy (= gamma_xy / 2)
};

// Writes <dir>/blocks_<n>.vtp, contacts_<n>.vtp, cracks_<n>.vtp (and damage_<n>.vti when the frame
// has a grid, zones_<n>.vtp when it has zones) per frame and rewrites blocks.pvd, contacts.pvd,
// cracks.pvd (damage.pvd) after every frame, so an interrupted run stays readable.
class VtkSeriesWriter {
 public:
  // What a checkpoint keeps of a series: the frames written so far.
  struct Written {
    std::vector<double> times;  // s, per frame
    bool grid = false, zones = false;
  };
  explicit VtkSeriesWriter(std::filesystem::path dir);
  // Continues a series at its checkpoint: the collections are cut back to its frames at once
  // (later frame files are written again as the run reaches them).
  VtkSeriesWriter(std::filesystem::path dir, Written written);
  void write(const VtkFrame& frame);
  std::size_t frames() const { return times_.size(); }
  Written written() const { return {times_, grid_, zones_}; }

 private:
  void write_collections() const;
  std::filesystem::path dir_;
  std::vector<double> times_;
  bool grid_ = false;   // the series has a damage grid
  bool zones_ = false;  // the series has deformable-block zones
};

// Points with named scalars (the acoustic-emission catalogue), one .vtp written whole: under a
// temporary name, then renamed.
struct VtkPointSet {
  std::vector<geometry::Point> points;  // m
  struct Field {
    std::string name;
    std::vector<double> values;  // one per point
  };
  std::vector<Field> fields;
};
void write_point_set(const VtkPointSet& set, const std::filesystem::path& file);

}  // namespace vorodec::io
