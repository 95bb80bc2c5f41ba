// The drivers' table: a new load path is its driver's files and one row here.
#include "vorodec/drivers/registry.hpp"

#include <array>

#include "quasi_static_driver.hpp"
#include "shpb_driver.hpp"
#include "stage_mode.hpp"

namespace vorodec::run {

namespace {

// A driver with a table of its own runs when the model file has it; one without (keys.table
// nullptr) runs the [[stage]]s.
struct DriverRow {
  const char* name;
  io::DriverKeys keys;
  std::unique_ptr<Driver> (*make)(const DriverContext&);
};

template <class D>
std::unique_ptr<Driver> make(const DriverContext& c) {
  return std::make_unique<D>(c);
}

// The first row whose table the model file has drives it; the last drives every other file.
constexpr std::array kDrivers{
    DriverRow{"shpb", ShpbDriver::keys, make<ShpbDriver>},
    DriverRow{"quasi_static", {nullptr, nullptr}, make<QuasiStaticDriver>},
};

constexpr auto kDriverKeys = [] {
  std::array<io::DriverKeys, kDrivers.size() - 1> keys{};
  for (std::size_t i = 0; i + 1 < kDrivers.size(); ++i) keys[i] = kDrivers[i].keys;
  return keys;
}();

const DriverRow& row_for(const io::ModelConfig& cfg) {
  for (const DriverRow& row : kDrivers)
    if (row.keys.table && cfg.tables.count(row.keys.table)) return row;
  return kDrivers.back();
}

}  // namespace

std::unique_ptr<Driver> make_driver(const DriverContext& c) {
  return row_for(c.cfg).make(c);
}

std::string driver_name(const io::ModelConfig& cfg) {
  return row_for(cfg).name;
}

io::ModelConfig read_model_file(const std::filesystem::path& file,
                                const std::vector<io::Override>& overrides) {
  return io::read_model_file(file, overrides, {stage_mode_keys(), kDriverKeys});
}

}  // namespace vorodec::run
