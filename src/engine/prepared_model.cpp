#include "vorodec/engine/prepared_model.hpp"

#include <fmt/format.h>

#include <cmath>

#include "vorodec/engine/in_situ_start.hpp"
#include "vorodec/geometry/grains.hpp"
#include "vorodec/io/input_error.hpp"
#include "vorodec/io/specimen_file.hpp"
#include "vorodec/model/build.hpp"
#include "vorodec/solver/solver.hpp"

namespace vorodec::run {

using model::Group;

namespace {

// The intact blocks cut by the joint sets.
geometry::Tessellation cut_by_joint_sets(const io::ModelConfig& cfg,
                                         const geometry::Tessellation& intact) {
  std::vector<geometry::JointTrace> traces;
  for (std::size_t i = 0; i < cfg.joint_sets.size(); ++i) {
    const auto& set = cfg.joint_sets[i];
    if (set.statistics) {
      const auto lines = geometry::joint_set_traces(*set.statistics, cfg.tessellation.outline,
                                                    static_cast<std::int32_t>(i), cfg.seed);
      traces.insert(traces.end(), lines.begin(), lines.end());
    }
    traces.insert(traces.end(), set.fractures.begin(), set.fractures.end());
  }
  return geometry::cut_by_joints(intact, traces, cfg.tessellation);
}

}  // namespace

geometry::Tessellation make_specimen(const io::ModelConfig& cfg) {
  if (cfg.specimen_file) return io::read_specimen(*cfg.specimen_file);
  try {
    if (cfg.grains) return geometry::tessellate_grains(cfg.tessellation, cfg.grains->settings);
    if (!cfg.joint_sets.empty())
      return cut_by_joint_sets(cfg, geometry::tessellate(cfg.tessellation));
    return geometry::tessellate(cfg.tessellation);
  } catch (const geometry::GeometryError& e) {
    throw io::ModelFileError(fmt::format("{}:{}: [specimen]: impossible geometry: {}",
                                         cfg.file.string(), cfg.specimen_line, e.what()));
  }
}

std::string specimen_report(const io::ModelConfig& cfg, const geometry::Tessellation& t) {
  std::string text;
  if (cfg.specimen_file)
    text += fmt::format("specimen loaded from {}\n", cfg.specimen_file->string());
  text += geometry::format_report(t.report);
  if (!cfg.joint_sets.empty()) {
    std::vector<std::size_t> edges(cfg.joint_sets.size(), 0);
    std::vector<double> length(cfg.joint_sets.size(), 0.0);
    for (const auto& j : t.joint_edges) {
      ++edges[static_cast<std::size_t>(j.set)];
      length[static_cast<std::size_t>(j.set)] += j.length;
    }
    for (std::size_t i = 0; i < edges.size(); ++i)
      text += fmt::format("  joint set {}: {} block pairs, {:.4g} m of joint ({})\n",
                          cfg.joint_sets[i].name, edges[i], length[i], cfg.joint_sets[i].law.name);
  }
  if (cfg.grains) {
    double total = 0;
    for (const double a : t.mineral_area) total += a;
    text += fmt::format(
        "  grains: {}, {} sub-blocks ({})\n", t.grain_mineral.size(), t.blocks.size(),
        cfg.grains->settings.sub_blocks == geometry::SubBlocks::trigon ? "trigon" : "voronoi");
    for (std::size_t m = 0; m < cfg.grains->minerals.size(); ++m)
      text += fmt::format("  mineral {}: area fraction {:.4f} (requested {:.4f})\n",
                          cfg.grains->minerals[m].name, t.mineral_area[m] / total,
                          cfg.grains->minerals[m].fraction);
  }
  return text;
}

namespace {

double mean_edge(const geometry::Tessellation& t) {
  double sum = 0;
  std::size_t n = 0;
  for (const auto& b : t.blocks)
    for (std::size_t i = 0; i < b.size(); ++i) {
      const auto d = t.vertices[b[(i + 1) % b.size()]] - t.vertices[b[i]];
      sum += std::sqrt(dot(d, d));
      ++n;
    }
  return n ? sum / static_cast<double>(n) : 0.0;
}

// Law groups after the joints (0) and platens (1) of a grain-based specimen: the default
// transgranular law, each mineral's own, each mineral pair's own; and the table choosing them.
void add_grain_laws(const io::GrainConfig& g, const geometry::Tessellation& tess,
                    std::uint64_t seed, std::vector<std::unique_ptr<laws::LawGroup>>& groups,
                    solver::GrainLaws& table) {
  const auto add = [&](const io::LawChoice& choice) {
    groups.push_back(laws::find_law(choice.name)->make(choice.params, seed));
    return static_cast<int>(groups.size() - 1);
  };
  const std::size_t n = g.minerals.size();
  table.minerals = n;
  table.grain_of_block = tess.block_grain;
  table.mineral_of_grain = tess.grain_mineral;
  const int trans = add(g.transgranular);
  table.transgranular.assign(n, trans);
  for (std::size_t m = 0; m < n; ++m)
    if (g.inside[m]) table.transgranular[m] = add(*g.inside[m]);
  table.intergranular.assign(n * n, 0);
  for (const auto& p : g.pairs)
    table.intergranular[p.a * n + p.b] = table.intergranular[p.b * n + p.a] = add(p.law);
}

const io::Mineral& block_mineral(const io::GrainConfig& g, const geometry::Tessellation& t,
                                 std::size_t block) {
  const auto grain = static_cast<std::size_t>(t.block_grain[block]);
  return g.minerals[static_cast<std::size_t>(t.grain_mineral[grain])];
}

std::vector<double> block_densities(const io::GrainConfig& g, const geometry::Tessellation& t) {
  std::vector<double> density;
  for (std::size_t b = 0; b < t.block_grain.size(); ++b)
    density.push_back(block_mineral(g, t, b).density);
  return density;
}

// Block bars: linear springs jkn = E / h between a bar's blocks (a column of blocks of length h
// on springs per unit length k carries waves at sqrt(k h / rho) = c0) and jks = G / h with
// G = E / 2, the shear modulus at Poisson's ratio 0 (rigid blocks have no Poisson effect; without
// shear stiffness the column kinks sideways under a crushed specimen's push).
void add_bar_laws(const loading::ShpbConfig& b,
                  std::vector<std::unique_ptr<laws::LawGroup>>& groups, solver::LawTable& table) {
  const auto spring = [&](double e) {
    laws::LawParams p;
    p["jkn"] = model::Distribution::constant(e / b.bar_block_length);
    p["jks"] = model::Distribution::constant(0.5 * e / b.bar_block_length);
    groups.push_back(laws::find_law("linear_elastic")->make(p, 0));
    return static_cast<int>(groups.size() - 1);
  };
  const int incident = spring(b.incident.youngs_modulus);
  const int transmitted = spring(b.transmitted.youngs_modulus);
  const auto set = [&](Group x, Group y, int law, bool bond) {
    const auto i = static_cast<std::size_t>(x), j = static_cast<std::size_t>(y);
    table.law[i][j] = table.law[j][i] = law;
    table.bond[i][j] = table.bond[j][i] = bond;
  };
  set(Group::top_platen, Group::incident_bar, incident, true);
  set(Group::incident_bar, Group::incident_bar, incident, true);
  set(Group::bottom_platen, Group::transmitted_bar, transmitted, true);
  set(Group::transmitted_bar, Group::transmitted_bar, transmitted, true);
}

}  // namespace

PreparedModel prepare_model(const io::ModelConfig& cfg, const geometry::Tessellation& tess) {
  PreparedModel s;
  const double d = cfg.rounding_length > 0 ? cfg.rounding_length : 0.05 * mean_edge(tess);
  std::optional<model::DeformableBuild> deformable;
  if (cfg.deformable.enabled) {
    deformable = model::DeformableBuild{
        cfg.deformable.zone_size, {cfg.deformable.youngs_modulus, cfg.deformable.poisson_ratio}};
    if (cfg.grains)  // each zone takes its mineral's elasticity
      for (std::size_t b = 0; b < tess.block_grain.size(); ++b) {
        const io::Mineral& m = block_mineral(*cfg.grains, tess, b);
        deformable->block_material.push_back({m.youngs_modulus, m.poisson_ratio});
      }
  }
  const std::vector<double> density =
      cfg.grains ? block_densities(*cfg.grains, tess) : std::vector<double>{};
  // A pressure-bar test's bars built from blocks are bodies of the model.
  const auto* shpb = io::table_settings<loading::ShpbConfig>(cfg, "shpb");
  std::optional<model::BlockBars> bars;
  if (shpb && shpb->block_bars) {
    const loading::ShpbConfig& b = *shpb;
    const double h = b.bar_block_length;
    const auto blocks = [&](double length) {
      return std::max(2, static_cast<int>(std::lround(length / h)));
    };
    bars = model::BlockBars{b.incident.width,          h,
                            blocks(b.incident.length), blocks(b.transmitted.length),
                            b.incident.density,        b.transmitted.density};
  }
  s.model = std::make_unique<model::Model>(
      model::build_model(tess, {cfg.density, d, true, density, bars}, deformable));
  std::vector<std::unique_ptr<laws::LawGroup>> groups;
  for (const io::LawChoice* choice : {&cfg.joints, &cfg.platens})
    groups.push_back(laws::find_law(choice->name)->make(choice->params, cfg.seed));
  solver::LawTable table;
  if (cfg.grains) add_grain_laws(*cfg.grains, tess, cfg.seed, groups, table.grains);
  if (cfg.joint_mix) {
    groups.push_back(
        laws::find_law(cfg.joint_mix->law.name)->make(cfg.joint_mix->law.params, cfg.seed));
    // A seed of its own, so the split and the contacts' property draws are independent.
    table.mix = {static_cast<int>(groups.size() - 1), cfg.joint_mix->fraction,
                 cfg.seed ^ 0x9e3779b97f4a7c15ull};
  }
  for (const auto& set : cfg.joint_sets)
    groups.push_back(laws::find_law(set.law.name)->make(set.law.params, cfg.seed));
  const int first_set = static_cast<int>(groups.size() - cfg.joint_sets.size());
  table.joint_set_law = first_set;
  for (const auto& j : tess.joint_edges)
    table.joints[solver::LawTable::joint_key(j.a, j.b)] = first_set + j.set;
  const auto set = [&](Group a, Group b, int law) {
    table.law[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] = law;
    table.law[static_cast<std::size_t>(b)][static_cast<std::size_t>(a)] = law;
  };
  set(Group::specimen, Group::specimen, 0);
  set(Group::specimen, Group::bottom_platen, 1);
  set(Group::specimen, Group::top_platen, 1);
  for (Group p : {Group::bottom_platen, Group::top_platen}) {
    table.bond[static_cast<std::size_t>(p)][0] = cfg.platens_bonded;
    table.bond[0][static_cast<std::size_t>(p)] = cfg.platens_bonded;
  }
  if (bars) add_bar_laws(*shpb, groups, table);
  solver::SolverSettings settings = cfg.solver;
  if (settings.contact_tolerance <= 0) settings.contact_tolerance = d;
  s.solver = std::make_unique<solver::Solver>(*s.model, std::move(groups), table, settings);
  s.solver->initialise();
  if (cfg.in_situ) preload_in_situ(*s.model, *s.solver, loading::resolved(*cfg.in_situ, *s.model));
  return s;
}

std::string describe_contacts(const io::ModelConfig& cfg, const geometry::Tessellation& specimen) {
  PreparedModel s = prepare_model(cfg, specimen);
  std::string out = "contacts: id block_a block_b length_m law";
  const auto& groups = s.solver->laws();
  for (auto n : groups[0]->property_names()) out += fmt::format(" {}", n);
  out += '\n';
  std::vector<std::size_t> local(groups.size(), 0);
  for (const auto& c : s.model->contacts) {
    const auto props = groups[c.law]->properties(local[c.law]++);
    out += fmt::format("{} {} {} {:.9g} {}", c.id, c.a, c.b, c.length, groups[c.law]->name());
    for (double p : props) out += fmt::format(" {:.9g}", p);
    out += '\n';
  }
  return out;
}

}  // namespace vorodec::run
