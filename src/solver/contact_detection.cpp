#include "vorodec/solver/contact_detection.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "vorodec/model/contact_geometry.hpp"

namespace vorodec::solver {

using model::Blocks;
using model::Contact;
using model::ContactFrame;
using model::Point;

namespace {

struct Box {
  double x0, y0, x1, y1;
};

// What the narrow phase reads of every block and corner, computed once per detection: each
// corner-block test would otherwise redo the block's box and a square root per edge.
struct DetectionGeometry {
  std::vector<Box> box;          // of the block's unrounded corners; its outline is within d
  std::vector<double> edge_len;  // m, length of the edge that starts at each corner

  explicit DetectionGeometry(const Blocks& bl) {
    const auto n = static_cast<std::int64_t>(bl.size());
    box.resize(bl.size());
    edge_len.resize(bl.world.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t bi = 0; bi < n; ++bi) {
      const auto b = static_cast<std::uint32_t>(bi);
      Box bx{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
             -std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()};
      for (std::uint32_t c = bl.corner_begin[b]; c < bl.corner_begin[b + 1]; ++c) {
        const Point p = bl.world[c].corner;
        bx = {std::min(bx.x0, p.x), std::min(bx.y0, p.y), std::max(bx.x1, p.x),
              std::max(bx.y1, p.y)};
        const Point t = bl.world[bl.shape[c].next].corner - p;
        edge_len[c] = std::sqrt(dot(t, t));
      }
      box[b] = bx;
    }
  }
};

// Nearest feature of block b to corner `corner` of block a; the frame's edge is returned in `edge`.
ContactFrame nearest_feature(const Blocks& bl, const DetectionGeometry& geo, std::uint32_t corner,
                             std::uint32_t b, std::uint32_t& edge) {
  const Point cA = bl.world[corner].centre;
  const double rA = bl.shape[corner].radius;
  const std::uint32_t first = bl.corner_begin[b], end = bl.corner_begin[b + 1];
  ContactFrame best{};
  best.gap = std::numeric_limits<double>::max();
  double deepest = -std::numeric_limits<double>::max();
  std::uint32_t deepest_edge = first;
  bool outside = false;
  for (std::uint32_t e0 = first; e0 < end; ++e0) {
    const std::uint32_t e1 = bl.next_corner(b, e0);
    const Point v0 = bl.world[e0].corner;
    const double h = cross(bl.world[e1].corner - v0, cA - v0) / -geo.edge_len[e0];  // outside
    if (h > deepest) {
      deepest = h;
      deepest_edge = e0;
    }
    if (h <= 0) continue;
    outside = true;
    const ContactFrame f = model::corner_edge_frame(
        cA, rA, bl.world[e0].corner, bl.world[e1].corner, geo.edge_len[e0], bl.world[e0].centre,
        bl.shape[e0].radius, bl.world[e1].centre, bl.shape[e1].radius);
    if (f.gap < best.gap) {
      best = f;
      edge = e0;
    }
  }
  if (!outside) {  // the corner's centre is inside b's polygon: take the least penetrated edge
    const std::uint32_t e0 = deepest_edge, e1 = bl.next_corner(b, e0);
    edge = e0;
    best = model::corner_edge_frame(cA, rA, bl.world[e0].corner, bl.world[e1].corner,
                                    geo.edge_len[e0], bl.world[e0].centre, bl.shape[e0].radius,
                                    bl.world[e1].centre, bl.shape[e1].radius);
  }
  return best;
}

// Whether the contact normal n (pointing into corner k's block) meets corner k's arc: between the
// outward normals of the corner's two edges. Otherwise the nearest part of that block is an edge,
// and the contact belongs to the other block's corner.
bool faces_arc(const Blocks& bl, std::uint32_t a, std::uint32_t k, Point n) {
  const Point c = bl.world[k].corner;
  const Point e_in = c - bl.world[bl.prev_corner(a, k)].corner;
  const Point e_out = bl.world[bl.shape[k].next].corner - c;
  const Point m{-n.x, -n.y};  // from the arc's centre towards the contact
  const Point n_in{e_in.y, -e_in.x}, n_out{e_out.y, -e_out.x};
  const double tol = 1e-6;
  const double l_in = std::sqrt(dot(n_in, n_in)), l_out = std::sqrt(dot(n_out, n_out));
  // The two cross products alone also pass -m when the corner is straight up to round-off (its
  // normals parallel): a back corner of a thin block then "faces" the far side, and its arc's
  // virtual circle, poking through the block, is taken for an overlap. m must lie on the arc's
  // side of it: positive against the normals' bisector.
  return cross(n_in, m) >= -tol * l_in && cross(m, n_out) >= -tol * l_out &&
         dot(m, n_in) * l_out + dot(m, n_out) * l_in > 0.0;
}

struct Candidate {
  Contact contact;
  Point point;
};

// A contact's sort key packed into two integers, so that sorting compares keys in place instead of
// chasing indices into the contact array.
struct SortKey {
  std::uint64_t hi, lo;
  std::size_t index;
  bool operator<(const SortKey& o) const {
    return hi != o.hi ? hi < o.hi : (lo != o.lo ? lo < o.lo : index < o.index);
  }
};

// Memory order of the step loop: law, rigid before deformable (touching a deformable block),
// then corner owner a, corner, b.
SortKey step_key(const Contact& c, std::size_t index, bool deformable) {
  return {std::uint64_t{c.law} << 33 | std::uint64_t{deformable} << 32 |
              static_cast<std::uint32_t>(c.a),
          std::uint64_t{c.corner} << 32 | static_cast<std::uint32_t>(c.b), index};
}

// Block pair (lower, higher), then the step order within the pair (a is the lower or the higher
// block, which with the law and the corner fixes the rest).
SortKey pair_key(const Contact& c, std::size_t index) {
  const auto lo = static_cast<std::uint32_t>(std::min(c.a, c.b));
  const auto hi = static_cast<std::uint32_t>(std::max(c.a, c.b));
  return {std::uint64_t{lo} << 32 | hi,
          std::uint64_t{c.law} << 33 |
              std::uint64_t{c.a != c.b && c.a == static_cast<std::int32_t>(hi)} << 32 | c.corner,
          index};
}

// Indices of the contacts in key order. `bucket` (< buckets) must order as the key's leading
// fields do: a counting sort into buckets, then a sort of each bucket's few contacts, is linear
// where one sort of all keys is n log n.
template <class Key, class Bucket>
std::vector<std::size_t> sorted_order(const std::vector<Contact>& contacts, Key key, Bucket bucket,
                                      std::size_t buckets) {
  std::vector<std::uint32_t> start(buckets + 1, 0);
  for (const Contact& c : contacts) ++start[bucket(c) + 1];
  for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  std::vector<SortKey> keys(contacts.size());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < keys.size(); ++i)
    keys[fill[bucket(contacts[i])]++] = key(contacts[i], i);
  for (std::size_t b = 0; b < buckets; ++b)
    std::sort(keys.begin() + start[b], keys.begin() + start[b + 1]);
  std::vector<std::size_t> order(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) order[i] = keys[i].index;
  return order;
}

// Lengths of new contacts from the spacing of all contacts between the same two blocks: each
// contact represents the joint up to halfway to its neighbours, plus the rounding length at the
// ends (so an intact shared edge gives each end contact half its length, as in UDEC). Lengths
// are at least `min_length`.
void assign_lengths(std::vector<Candidate>& pair_contacts, double d, double min_length) {
  const std::size_t k = pair_contacts.size();
  if (k == 1) {  // a corner pressing on a face: half a typical edge (d is 5 % of the mean edge)
    if (pair_contacts[0].contact.length == 0.0) pair_contacts[0].contact.length = 10.0 * d;
    return;
  }
  const Point p0 = pair_contacts.front().point;
  Point dir{0, 0};
  for (const auto& c : pair_contacts) {
    const Point r = c.point - p0;
    dir = dot(r, dir) < 0 ? dir - r : dir + r;
  }
  const double dl = std::sqrt(dot(dir, dir));
  dir = dl > 0 ? (1.0 / dl) * dir : Point{1, 0};
  std::vector<std::pair<double, std::size_t>> s(k);
  for (std::size_t i = 0; i < k; ++i) s[i] = {dot(pair_contacts[i].point - p0, dir), i};
  std::sort(s.begin(), s.end());
  for (std::size_t j = 0; j < k; ++j) {
    const double lo = j == 0 ? s[j].first - d : 0.5 * (s[j - 1].first + s[j].first);
    const double hi = j + 1 == k ? s[j].first + d : 0.5 * (s[j].first + s[j + 1].first);
    Contact& c = pair_contacts[s[j].second].contact;
    if (c.length == 0.0) c.length = std::max(hi - lo, min_length);
  }
}

// Candidate block pairs (a < b) whose boxes, enlarged by `margin`, overlap.
std::vector<std::pair<std::uint32_t, std::uint32_t>> broad_phase(const Blocks& bl,
                                                                 const DetectionGeometry& geo,
                                                                 double margin) {
  const auto n = static_cast<std::uint32_t>(bl.size());
  std::vector<Box> boxes(n);
  double size = 0;
  std::size_t counted = 0;
  Box all{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
          -std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()};
  for (std::uint32_t b = 0; b < n; ++b) {
    const Box& g = geo.box[b];
    boxes[b] = {g.x0 - margin, g.y0 - margin, g.x1 + margin, g.y1 + margin};
    all = {std::min(all.x0, boxes[b].x0), std::min(all.y0, boxes[b].y0),
           std::max(all.x1, boxes[b].x1), std::max(all.y1, boxes[b].y1)};
    if (bl.group[b] == model::Group::specimen) {
      size += std::max(boxes[b].x1 - boxes[b].x0, boxes[b].y1 - boxes[b].y0);
      ++counted;
    }
  }
  // Cells about two mean block sizes wide: a block overlaps at most a few cells.
  const double h = counted ? 2.0 * size / static_cast<double>(counted) : (all.x1 - all.x0);
  const auto nx = static_cast<std::int64_t>(std::ceil((all.x1 - all.x0) / h)) + 1;
  const auto ny = static_cast<std::int64_t>(std::ceil((all.y1 - all.y0) / h)) + 1;
  const auto cell_of = [&](double x, double y) {
    const auto i = std::clamp<std::int64_t>(static_cast<std::int64_t>((x - all.x0) / h), 0, nx - 1);
    const auto j = std::clamp<std::int64_t>(static_cast<std::int64_t>((y - all.y0) / h), 0, ny - 1);
    return std::pair{i, j};
  };
  // (cell, block) for every cell a block's box overlaps, sorted: sparse, so a block flung far
  // from the specimen costs no memory for the empty cells between.
  std::vector<std::pair<std::int64_t, std::uint32_t>> entries;
  for (std::uint32_t b = 0; b < n; ++b) {
    const auto [i0, j0] = cell_of(boxes[b].x0, boxes[b].y0);
    const auto [i1, j1] = cell_of(boxes[b].x1, boxes[b].y1);
    for (auto j = j0; j <= j1; ++j)
      for (auto i = i0; i <= i1; ++i) entries.push_back({j * nx + i, b});
  }
  std::sort(entries.begin(), entries.end());
  // Pairs as (lower << 32 | higher): sorting plain integers is several times cheaper than pairs.
  std::vector<std::uint64_t> keys;
  for (std::size_t lo = 0; lo < entries.size();) {
    std::size_t hi = lo;
    while (hi < entries.size() && entries[hi].first == entries[lo].first) ++hi;
    for (std::size_t p = lo; p < hi; ++p) {
      for (std::size_t q = p + 1; q < hi; ++q) {
        const std::uint32_t a = entries[p].second, b = entries[q].second;  // a < b: sorted
        const Box &A = boxes[a], &B = boxes[b];
        if (A.x1 < B.x0 || B.x1 < A.x0 || A.y1 < B.y0 || B.y1 < A.y0) continue;
        // Report each pair once: in the cell holding the lower-left corner of the overlap.
        const auto [ci, cj] = cell_of(std::max(A.x0, B.x0), std::max(A.y0, B.y0));
        if (cj * nx + ci != entries[lo].first) continue;
        keys.push_back(std::uint64_t{a} << 32 | b);
      }
    }
    lo = hi;
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i)
    pairs[i] = {static_cast<std::uint32_t>(keys[i] >> 32), static_cast<std::uint32_t>(keys[i])};
  return pairs;
}

using BlockPair = std::pair<std::uint32_t, std::uint32_t>;

BlockPair pair_of(const Contact& c) {
  return {static_cast<std::uint32_t>(std::min(c.a, c.b)),
          static_cast<std::uint32_t>(std::max(c.a, c.b))};
}

// The contacts of a run of block pairs, in pair order, as the serial sweep would list them.
struct PairRun {
  std::vector<Candidate> result;
  std::vector<std::int64_t> origin;  // old index, or -1: new, its id is given afterwards
  DetectionStats stats;
};

// Narrow phase of the pairs [begin, end) of the broad phase's sorted list, merged with the old
// contacts (sorted by pair) from old_pos on. Pairs are independent, so runs of them can go to
// different threads and be joined in order.
struct NarrowPhase {
  const model::Model& model;
  const LawTable& table;
  const std::vector<BlockPair>& pairs;
  const std::vector<std::size_t>& old_order;
  const DetectionGeometry& geo;
  double tolerance;
  bool bond_new;

  PairRun run(std::size_t begin, std::size_t end) const {
    const Blocks& bl = model.blocks;
    const double d = model.rounding_length;
    PairRun out;
    // Reused from pair to pair: allocating them per pair cost more than the searches.
    std::vector<Candidate> pair_list, fresh, kept;
    std::vector<std::int64_t> pair_origin, kept_origin;
    std::size_t old_pos = 0;
    if (begin > 0)
      old_pos = static_cast<std::size_t>(
          std::lower_bound(
              old_order.begin(), old_order.end(), pairs[begin],
              [&](std::size_t i, const BlockPair& p) { return pair_of(model.contacts[i]) < p; }) -
          old_order.begin());
    const auto flush_old_until = [&](const BlockPair& p, bool inclusive) {
      // Old contacts of pairs that the broad phase no longer reports: keep only intact bonded
      // ones.
      while (old_pos < old_order.size()) {
        const Contact& c = model.contacts[old_order[old_pos]];
        const BlockPair q = pair_of(c);
        if (inclusive ? q > p : q >= p) break;
        // (Never across a pair that no longer interacts: a block an excavation removed.)
        if (c.bonded && c.state <= model::ContactState::slipping &&
            table.for_blocks(model.blocks, static_cast<std::uint32_t>(c.a),
                             static_cast<std::uint32_t>(c.b)) >= 0) {
          out.result.push_back({c, {}});
          out.origin.push_back(static_cast<std::int64_t>(old_order[old_pos]));
          ++out.stats.kept;
        } else {
          ++out.stats.deleted;
        }
        ++old_pos;
      }
    };
    for (std::size_t p = begin; p < end; ++p) {
      const auto [pa, pb] = pairs[p];
      const int law = table.for_blocks(bl, pa, pb);
      if (law < 0) continue;
      flush_old_until(pairs[p], false);
      // Old contacts of this pair.
      pair_list.clear();
      pair_origin.clear();
      while (old_pos < old_order.size() &&
             pair_of(model.contacts[old_order[old_pos]]) == pairs[p]) {
        const Contact& c = model.contacts[old_order[old_pos]];
        pair_list.push_back({c, {}});
        pair_origin.push_back(static_cast<std::int64_t>(old_order[old_pos]));
        ++old_pos;
      }
      // Narrow phase: every corner of each block against the other block.
      fresh.clear();
      for (const auto& [a, b] : {std::pair{pa, pb}, std::pair{pb, pa}}) {
        const Box& box = geo.box[b];
        for (std::uint32_t k = bl.corner_begin[a]; k < bl.corner_begin[a + 1]; ++k) {
          bool existing = false;
          for (const Candidate& old : pair_list)
            existing = existing ||
                       (old.contact.a == static_cast<std::int32_t>(a) && old.contact.corner == k);
          // b's rounded outline lies within d of its corner box: an arc meets its edges at most
          // d from its corner, and bulges towards it (on an edge shorter than 2 d it reaches past
          // the polygon). A corner farther from the box than the tolerance plus its radius plus
          // d has a gap beyond the tolerance: skip the search.
          const Point cA = bl.world[k].centre;
          const double reach = tolerance + bl.shape[k].radius + 1.001 * d;
          if (!existing && (cA.x < box.x0 - reach || cA.x > box.x1 + reach ||
                            cA.y < box.y0 - reach || cA.y > box.y1 + reach))
            continue;
          std::uint32_t edge = 0;
          const ContactFrame f = nearest_feature(bl, geo, k, b, edge);
          for (Candidate& old : pair_list) {
            if (old.contact.a == static_cast<std::int32_t>(a) && old.contact.corner == k) {
              old.contact.edge = edge;
              old.point = f.point;
            }
          }
          if (existing || f.gap > tolerance || !faces_arc(bl, a, k, f.n)) continue;
          Contact c;
          c.a = static_cast<std::int32_t>(a);
          c.b = static_cast<std::int32_t>(b);
          c.corner = k;
          c.edge = edge;
          c.gap = f.gap;
          c.law = static_cast<std::uint16_t>(law);
          // Bonds join blocks that share an edge (gap zero up to round-off); blocks that only
          // approach each other at a vertex get an unbonded, frictional contact.
          c.bonded =
              bond_new && table.bonds(bl.group[a], bl.group[b]) && std::abs(f.gap) <= 1e-3 * d;
          fresh.push_back({c, f.point});
        }
      }
      // Keep old contacts that are still close (or bonded and intact); drop the rest.
      kept.clear();
      kept_origin.clear();
      for (std::size_t i = 0; i < pair_list.size(); ++i) {
        const Contact& c = pair_list[i].contact;
        if (c.gap <= tolerance || (c.bonded && c.state <= model::ContactState::slipping)) {
          kept.push_back(pair_list[i]);
          kept_origin.push_back(pair_origin[i]);
          ++out.stats.kept;
        } else {
          ++out.stats.deleted;
        }
      }
      // A corner of a and a corner of b meeting at one point give one contact: the lower block's
      // (fresh is in block order, so the lower block's candidates come first). A corner that has
      // slid past the other corner and presses deeper than the contact there is a contact of its
      // own: suppressing it would let it sink in unseen.
      const std::size_t n_kept = kept.size();
      for (const Candidate& cand : fresh) {
        bool duplicate = false;
        for (const Candidate& k : kept) {
          const Point r = k.point - cand.point;
          if (dot(r, r) < d * d && cand.contact.gap >= k.contact.gap - 0.01 * d) duplicate = true;
        }
        if (duplicate) continue;
        kept.push_back(cand);
        kept_origin.push_back(-1);
      }
      // Rigid blocks: at least 2d per contact. Deformable blocks: the gridpoint spacing, which
      // zoning finer than 2d would otherwise inflate (docs/theory.md §4.4).
      if (kept.size() > n_kept)
        assign_lengths(kept, d, bl.deformable[pa] || bl.deformable[pb] ? 0.0 : 2.0 * d);
      for (std::size_t i = 0; i < kept.size(); ++i) {
        if (kept_origin[i] < 0) ++out.stats.created;
        out.result.push_back(kept[i]);
        out.origin.push_back(kept_origin[i]);
      }
    }
    if (end == pairs.size())
      flush_old_until(
          {std::numeric_limits<std::uint32_t>::max(), std::numeric_limits<std::uint32_t>::max()},
          true);
    else
      flush_old_until(pairs[end], false);
    return out;
  }
};

}  // namespace

DetectionStats ContactDetector::detect(model::Model& model,
                                       std::vector<std::unique_ptr<laws::LawGroup>>& laws,
                                       bool bond_new) {
  Blocks& bl = model.blocks;
  model::refresh_world(model);
  // Existing contacts by pair; their position in the old array is remembered.
  const std::size_t nb = bl.size();
  const std::vector<std::size_t> old_order = sorted_order(
      model.contacts, pair_key,
      [](const Contact& c) { return static_cast<std::size_t>(std::min(c.a, c.b)); }, nb);
  const DetectionGeometry geo(bl);
  const auto pairs = broad_phase(bl, geo, tolerance_ + 2.0 * model.rounding_length);
  const NarrowPhase narrow{model, table_, pairs, old_order, geo, tolerance_, bond_new};
  const int runs = static_cast<int>(std::clamp<std::size_t>(
      pairs.size() / 256, 1, static_cast<std::size_t>(omp_get_max_threads())));
  std::vector<PairRun> parts(static_cast<std::size_t>(runs));
#pragma omp parallel for schedule(static, 1) num_threads(runs) if (runs > 1)
  for (int t = 0; t < runs; ++t) {
    const auto [lo, hi] = laws::chunk_range(0, pairs.size(), t, runs);
    parts[static_cast<std::size_t>(t)] = narrow.run(lo, hi);
  }
  // Joined in pair order, new contacts numbered in that order: the same for any thread count.
  DetectionStats stats;
  std::vector<Candidate> result;
  std::vector<std::int64_t> origin;
  for (PairRun& part : parts) {
    for (std::size_t i = 0; i < part.result.size(); ++i)
      if (part.origin[i] < 0) part.result[i].contact.id = next_id_++;
    result.insert(result.end(), part.result.begin(), part.result.end());
    origin.insert(origin.end(), part.origin.begin(), part.origin.end());
    stats.created += part.stats.created;
    stats.deleted += part.stats.deleted;
    stats.kept += part.stats.kept;
  }

  // Sort by law then corner owner (memory order of the step loop).
  std::vector<Contact> contacts(result.size());
  for (std::size_t i = 0; i < result.size(); ++i) contacts[i] = result[i].contact;
  const auto touches_deformable = [&](const Contact& c) {
    return bl.deformable[static_cast<std::size_t>(c.a)] ||
           bl.deformable[static_cast<std::size_t>(c.b)];
  };
  const std::vector<std::size_t> order = sorted_order(
      contacts,
      [&](const Contact& c, std::size_t i) { return step_key(c, i, touches_deformable(c)); },
      [&](const Contact& c) {  // law, rigid before deformable, corner owner: step_key's order
        return (std::size_t{c.law} * 2 + touches_deformable(c)) * nb +
               static_cast<std::size_t>(c.a);
      },
      laws.size() * 2 * nb);
  for (std::size_t i = 0; i < order.size(); ++i) contacts[i] = result[order[i]].contact;

  // Each law rebuilds its arrays from old local indices.
  std::vector<std::size_t> old_begin(laws.size() + 1, 0);
  for (const Contact& c : model.contacts) ++old_begin[c.law + 1u];
  for (std::size_t l = 0; l < laws.size(); ++l) old_begin[l + 1] += old_begin[l];
  std::size_t pos = 0;
  for (std::size_t l = 0; l < laws.size(); ++l) {
    std::vector<std::int64_t> old_local;
    std::vector<laws::NewContact> fresh_info;
    for (; pos < order.size() && contacts[pos].law == l; ++pos) {
      const std::int64_t o = origin[order[pos]];
      old_local.push_back(o < 0 ? -1 : o - static_cast<std::int64_t>(old_begin[l]));
      const double spring_origin = bond_new ? 0.0 : std::min(contacts[pos].gap, 0.0);
      fresh_info.push_back(
          {contacts[pos].id, contacts[pos].length, contacts[pos].bonded != 0, spring_origin});
    }
    laws[l]->rebuild(old_local, fresh_info);
  }
  model.contacts.swap(contacts);
  return stats;
}

}  // namespace vorodec::solver
