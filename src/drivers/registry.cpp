// The drivers' table: a new load path is its driver's files and one row here.
#include "vorodec/drivers/registry.hpp"

#include <array>

#include "quasi_static_driver.hpp"
#include "shpb_driver.hpp"
#include "stage_mode.hpp"

namespace vorodec::run {

namespace {

struct DriverRow {
  const char* name;
  bool (*asked_for)(const io::ModelConfig&);
  std::unique_ptr<Driver> (*make)(const DriverContext&);
};

template <class D>
std::unique_ptr<Driver> make(const DriverContext& c) {
  return std::make_unique<D>(c);
}

// In order: the first row a model file asks for drives it; the last asks for every file.
constexpr std::array kDrivers{
    DriverRow{"shpb", [](const io::ModelConfig& cfg) { return cfg.shpb.has_value(); },
              make<ShpbDriver>},
    DriverRow{"quasi_static", [](const io::ModelConfig&) { return true; }, make<QuasiStaticDriver>},
};

const DriverRow& row_for(const io::ModelConfig& cfg) {
  for (const DriverRow& row : kDrivers)
    if (row.asked_for(cfg)) return row;
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
  return io::read_model_file(file, overrides, stage_mode_keys());
}

}  // namespace vorodec::run
