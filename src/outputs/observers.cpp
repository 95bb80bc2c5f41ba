#include "vorodec/outputs/observers.hpp"

#include "shpb_output.hpp"
#include "vorodec/checkpoint/archive_io.hpp"
#include "vorodec/measure/grain_cracks.hpp"
#include "vorodec/model/contact_geometry.hpp"
#include "vorodec/outputs/ae_output.hpp"

namespace vorodec::run {

namespace {

using model::Group;

// A CSV file, new or cut back to the size the checkpoint archive gives.
std::unique_ptr<io::CsvWriter> open_csv(const std::filesystem::path& file,
                                        const std::vector<std::string>& header,
                                        checkpoint::InArchive* resume) {
  if (!resume) return std::make_unique<io::CsvWriter>(file, header);
  std::uint64_t bytes = 0;
  (*resume)(bytes);
  return std::make_unique<io::CsvWriter>(file, bytes);
}

class HistoryObserver final : public Observer {
 public:
  HistoryObserver(const RunView& v, const DamageOutput& damage, const std::filesystem::path& out,
                  Curve& curve, checkpoint::InArchive* resume)
      : damage_(damage),
        zoned_(!v.model.zoning.empty()),
        grains_(!v.specimen.block_grain.empty()),
        viscous_(v.solver.viscous()),
        extra_(v.columns ? v.columns->column_names() : std::vector<std::string>{}),
        curve_(curve) {
    csv_ = open_csv(out / "history.csv", header(), resume);
    if (resume)
      (*resume)(checkpoint::pod(curve_.strain), checkpoint::pod(curve_.stress),
                checkpoint::pod(curve_.lateral), checkpoint::pod(curve_.failure_rate),
                checkpoint::pod(curve_.rows));
  }

  void sample(const RunView& v, const Sample& s) override {
    if (s.row) record(v, s.label);
  }
  void flush() override { csv_->flush(); }
  void save(checkpoint::OutArchive& ar) const override {
    ar(csv_->size(), checkpoint::pod(curve_.strain), checkpoint::pod(curve_.stress),
       checkpoint::pod(curve_.lateral), checkpoint::pod(curve_.failure_rate),
       checkpoint::pod(curve_.rows));
  }

 private:
  std::vector<std::string> header() const {
    std::vector<std::string> h{"step",
                               "time",
                               "axial_strain",
                               "axial_stress",
                               "lateral_strain",
                               "volumetric_strain",
                               "cracks_tensile",
                               "cracks_shear",
                               "failure_rate",
                               "damage_density",
                               "p21",
                               "boundary_work",
                               "strain_energy",
                               "kinetic_energy",
                               "damping_energy",
                               "friction_energy",
                               "breakage_energy"};
    // Viscous contacts (Burger's): their dashpots' work, J/m; then the load path's own columns.
    if (viscous_) h.emplace_back("viscous_energy");
    h.insert(h.end(), extra_.begin(), extra_.end());
    // Deformable specimens: the zones' area-weighted mean stress (compression positive, Pa).
    if (zoned_) h.insert(h.end(), {"zone_stress_xx", "zone_stress_yy", "zone_stress_xy"});
    if (grains_) {
      for (const auto name : measure::kCrackClassNames) h.emplace_back(name);
      for (const auto name : measure::kCrackClassNames) h.push_back(std::string(name) + "_length");
    }
    // What an adaptive velocity stage did (any stage: the applied speed and the ratio it steers
    // by).
    h.insert(h.end(), {"platen_velocity", "unbalanced_force_ratio"});
    h.emplace_back("stage");
    return h;
  }

  void record(const RunView& v, const std::string& label) {
    const solver::Solver& solver = v.solver;
    std::size_t n_tensile = 0, n_shear = 0;
    for (const auto& e : solver.cracks())
      (e.type == laws::ContactEvent::tensile_failure ? n_tensile : n_shear)++;
    const auto& e = solver.energy();
    const auto& state = v.state;
    const double broken = double(n_tensile + n_shear);
    const measure::DamageState dmg = damage_.measure(v.model, solver);
    const double row[] = {
        double(solver.steps()),
        solver.time(),
        state.axial_strain,
        state.axial_stress,
        state.lateral_strain,
        state.volumetric_strain,
        double(n_tensile),
        double(n_shear),
        solver.initial_bonded_contacts() ? broken / double(solver.initial_bonded_contacts()) : 0.0,
        dmg.damage_density,
        dmg.p21,
        e.boundary_work,
        solver.contact_strain_energy() + (zoned_ ? solver.zone_strain_energy() : 0.0),
        solver.kinetic_energy(),
        e.damping,
        e.slip,
        e.breakage};
    std::vector<double> full(std::begin(row), std::end(row));
    if (viscous_) full.push_back(e.viscous);
    if (!extra_.empty()) v.columns->column_values(full);
    if (zoned_) {
      const model::ZoneStress m = model::mean_stress(v.model, Group::specimen);
      full.insert(full.end(), {-m.xx, -m.yy, -m.xy});
    }
    if (grains_) {
      const measure::GrainCracks g = measure::grain_cracks(solver.cracks(), v.specimen.block_grain);
      for (const std::size_t n : g.count) full.push_back(double(n));
      full.insert(full.end(), g.length.begin(), g.length.end());
    }
    full.insert(full.end(), {v.platen_velocity, solver.unbalanced_force_ratio()});
    csv_->row(full, label);
    csv_->flush();  // whole rows, as they come: a long run can be watched, a killed one read
    curve_.strain.push_back(state.axial_strain);
    curve_.stress.push_back(state.axial_stress);
    curve_.lateral.push_back(state.lateral_strain);
    curve_.failure_rate.push_back(row[8]);
    curve_.rows.push_back({state.axial_strain, state.axial_stress, state.lateral_strain, v.stage});
  }

  const DamageOutput& damage_;
  bool zoned_, grains_, viscous_;
  std::vector<std::string> extra_;  // the load path's columns
  Curve& curve_;
  std::unique_ptr<io::CsvWriter> csv_;
};

// cracks.csv, one row per failed contact in the order they failed, written as they occur.
// Grain-based specimens add the crack class (1-4, measure::kCrackClassNames) before the type.
class CrackObserver final : public Observer {
 public:
  CrackObserver(const RunView& v, const std::filesystem::path& out, checkpoint::InArchive* resume)
      : grains_(!v.specimen.block_grain.empty()) {
    std::vector<std::string> header{"time",   "x",       "y",      "orientation_deg",
                                    "length", "block_a", "block_b"};
    if (grains_) header.push_back("class");
    header.push_back("type");
    csv_ = open_csv(out / "cracks.csv", header, resume);
    if (resume) (*resume)(written_);
  }

  void after_advance(const RunView& v) override {
    const auto& cracks = v.solver.cracks();
    if (cracks.size() == written_) return;
    for (; written_ < cracks.size(); ++written_) {
      const laws::CrackEvent& e = cracks[written_];
      double row[] = {e.time,   e.x,         e.y,         measure::crack_orientation_deg(e),
                      e.length, double(e.a), double(e.b), 0.0};
      std::size_t n = 7;
      if (grains_) row[n++] = double(measure::crack_class(e, v.specimen.block_grain) + 1);
      csv_->row(std::span<const double>(row, n),
                e.type == laws::ContactEvent::tensile_failure ? "tensile" : "shear");
    }
    csv_->flush();
  }
  void flush() override { csv_->flush(); }
  void save(checkpoint::OutArchive& ar) const override { ar(csv_->size(), written_); }

 private:
  bool grains_;
  std::unique_ptr<io::CsvWriter> csv_;
  std::size_t written_ = 0;
};

io::VtkFrame make_frame(const RunView& v) {
  const model::Model& m = v.model;
  const geometry::Tessellation& tess = v.specimen;
  io::VtkFrame f;
  f.time = v.solver.time();
  const auto& bl = m.blocks;
  for (std::uint32_t b = 0; b < bl.size(); ++b) {
    f.block_offsets.push_back(static_cast<std::uint32_t>(f.block_points.size()));
    for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c) {
      if (bl.deformable[b]) {
        const auto g = static_cast<std::size_t>(m.zoning.corner_gp[c]);
        f.block_points.push_back({m.zoning.x[g], m.zoning.y[g]});
      } else {
        f.block_points.push_back(bl.to_world(b, bl.corner[c]));
      }
    }
    f.block_id.push_back(static_cast<std::int32_t>(b));
    f.block_group.push_back(static_cast<std::int32_t>(bl.group[b]));
    if (bl.group[b] == model::Group::excavated) {
      f.block_hidden.resize(bl.size(), 0);
      f.block_hidden[b] = 1;
    }
    f.block_velocity.push_back({bl.vx[b], bl.vy[b]});
    f.block_displacement.push_back({bl.x[b] - bl.x0[b], bl.y[b] - bl.y0[b]});
  }
  f.block_offsets.push_back(static_cast<std::uint32_t>(f.block_points.size()));
  for (model::Contact c : m.contacts) {
    const auto a = static_cast<std::size_t>(c.a), b = static_cast<std::size_t>(c.b);
    f.contact_point.push_back(model::contact_frame(bl, c).point);
    f.contact_a.push_back({bl.x[a], bl.y[a]});
    f.contact_b.push_back({bl.x[b], bl.y[b]});
    f.contact_normal_force.push_back(c.fn);
    f.contact_shear_force.push_back(c.fs);
    f.contact_state.push_back(static_cast<std::int32_t>(c.state));
  }
  const model::Zoning& z = m.zoning;
  for (std::size_t i = 0; i < z.zones.size(); ++i) {
    if (bl.group[z.zone_block[i]] == model::Group::excavated) continue;  // not drawn
    for (const std::uint32_t g : z.zones[i].gp) f.zone_points.push_back({z.x[g], z.y[g]});
    f.zone_block.push_back(static_cast<std::int32_t>(z.zone_block[i]));
    const model::ZoneStress s = z.stress(i);
    const std::array<double, 3> e = z.strain(i);
    f.zone_stress.push_back({s.xx, s.yy, s.xy, s.zz});
    f.zone_strain.push_back({e[0], e[1], 0.5 * e[2]});
  }
  for (const laws::CrackEvent& e : v.solver.cracks()) {
    const model::Point mid{e.x, e.y}, t{-e.ny * 0.5 * e.length, e.nx * 0.5 * e.length};
    f.crack_begin.push_back(mid - t);
    f.crack_end.push_back(mid + t);
    f.crack_type.push_back(e.type == laws::ContactEvent::tensile_failure ? 1 : 2);
    f.crack_time.push_back(e.time);
    if (!tess.block_grain.empty())
      f.crack_class.push_back(static_cast<std::int32_t>(measure::crack_class(e, tess.block_grain)) +
                              1);
  }
  if (!tess.block_grain.empty()) {
    for (std::size_t b = 0; b < bl.size(); ++b) {
      const bool specimen = b < tess.block_grain.size();
      const std::int32_t g = specimen ? tess.block_grain[b] : -1;
      f.block_grain.push_back(g);
      f.block_mineral.push_back(specimen ? tess.grain_mineral[static_cast<std::size_t>(g)] : -1);
    }
  }
  return f;
}

// An output time: a rose.csv row always, a VTK frame (with the damage fields) unless --no-vtk.
class FrameObserver final : public Observer {
 public:
  FrameObserver(const DamageOutput& damage, const std::filesystem::path& out, bool write_vtk,
                checkpoint::InArchive* resume)
      : damage_(damage) {
    rose_ = open_csv(out / "rose.csv", DamageOutput::rose_header(), resume);
    if (!write_vtk) return;
    if (!resume) {
      vtk_ = std::make_unique<io::VtkSeriesWriter>(out / "vtk");
      return;
    }
    io::VtkSeriesWriter::Written w;
    (*resume)(checkpoint::pod(w.times), w.grid, w.zones);
    vtk_ = std::make_unique<io::VtkSeriesWriter>(out / "vtk", std::move(w));
  }

  void sample(const RunView& v, const Sample& s) override {
    if (!s.frame) return;
    rose_->row(damage_.rose_row(v.model, v.solver, v.state.axial_stress), s.label);
    rose_->flush();
    if (!vtk_) return;
    io::VtkFrame frame = make_frame(v);
    damage_.add_fields(v.model, v.solver, frame);
    vtk_->write(frame);
  }
  void flush() override { rose_->flush(); }
  void save(checkpoint::OutArchive& ar) const override {
    ar(rose_->size());
    if (!vtk_) return;
    const io::VtkSeriesWriter::Written w = vtk_->written();
    ar(checkpoint::pod(w.times), w.grid, w.zones);
  }

 private:
  const DamageOutput& damage_;
  std::unique_ptr<io::CsvWriter> rose_;
  std::unique_ptr<io::VtkSeriesWriter> vtk_;
};

// ae_events.csv and .vtp: the events of every crack so far, rewritten whole at each flush (a
// checkpoint and the end), as they follow from the crack list alone.
class AeObserver final : public Observer {
 public:
  // Keeps the solver, not the view: make_observers' view is a temporary.
  AeObserver(const RunView& v, const measure::AeSettings& s, std::filesystem::path out)
      : solver_(v.solver), settings_(s), out_(std::move(out)) {}
  void flush() override {
    write_ae_events(measure::cluster_events(solver_.cracks(), settings_), out_);
  }
  void save(checkpoint::OutArchive&) const override {}

 private:
  const solver::Solver& solver_;
  measure::AeSettings settings_;
  std::filesystem::path out_;
};

// gauges.csv and bars.csv of a pressure-bar test, rewritten whole at each flush from the bars'
// histories (the driver's state).
class BarsObserver final : public Observer {
 public:
  BarsObserver(const BarsView& bars, std::filesystem::path out)
      : bars_(bars), out_(std::move(out)) {}
  void flush() override { write_bars(bars_, out_); }
  void save(checkpoint::OutArchive&) const override {}

 private:
  const BarsView& bars_;  // the driver's, which outlives the observers' run
  std::filesystem::path out_;
};

}  // namespace

Observers make_observers(const RunView& view, const DamageOutput& damage,
                         const measure::AeSettings& ae, const std::filesystem::path& out,
                         bool write_vtk, Curve& curve, checkpoint::InArchive* resume) {
  Observers o;
  o.add(std::make_unique<HistoryObserver>(view, damage, out, curve, resume));
  o.add(std::make_unique<CrackObserver>(view, out, resume));
  o.add(std::make_unique<FrameObserver>(damage, out, write_vtk, resume));
  o.add(std::make_unique<AeObserver>(view, ae, out));
  if (view.bars) o.add(std::make_unique<BarsObserver>(*view.bars, out));
  return o;
}

}  // namespace vorodec::run
