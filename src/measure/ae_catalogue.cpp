#include "vorodec/measure/ae_catalogue.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

namespace vorodec::measure {

namespace {

struct OpenEvent {
  std::size_t index;                 // into the result
  std::vector<std::size_t> members;  // crack indices
  double last;                       // s, time of the last crack
  double wx = 0, wy = 0, mx = 0, my = 0;
};

void close(const OpenEvent& o, std::span<const laws::CrackEvent> cracks, const AeSettings& s,
           std::vector<AeEvent>& events) {
  AeEvent& e = events[o.index];
  const double n = static_cast<double>(o.members.size());
  double energy = 0.0;
  for (const std::size_t k : o.members) energy += cracks[k].energy;
  e.duration = o.last - e.time;
  e.x = energy > 0.0 ? o.wx / energy : o.mx / n;
  e.y = energy > 0.0 ? o.wy / energy : o.my / n;
  e.energy = energy * s.thickness;
  e.magnitude = e.energy > 0.0 ? 2.0 / 3.0 * std::log10(e.energy) - 3.2
                               : -std::numeric_limits<double>::infinity();
  e.cracks = o.members.size();
  e.tensile = static_cast<std::size_t>(std::count_if(
      o.members.begin(), o.members.end(),
      [&](std::size_t k) { return cracks[k].type == laws::ContactEvent::tensile_failure; }));
  e.type = e.tensile == e.cracks ? AeType::tensile : e.tensile == 0 ? AeType::shear : AeType::mixed;
}

}  // namespace

std::vector<AeEvent> cluster_events(std::span<const laws::CrackEvent> cracks, const AeSettings& s) {
  const double window = s.radius / s.shear_wave_speed, r2 = s.radius * s.radius;
  std::vector<AeEvent> events;
  std::vector<OpenEvent> open;
  for (std::size_t k = 0; k < cracks.size(); ++k) {
    const laws::CrackEvent& c = cracks[k];
    for (std::size_t i = 0; i < open.size();) {  // closed: no crack joined within the window
      if (c.time - open[i].last > window) {
        close(open[i], cracks, s, events);
        open.erase(open.begin() + static_cast<std::ptrdiff_t>(i));
      } else {
        ++i;
      }
    }
    // The nearest open event that has a crack within the radius.
    OpenEvent* join = nullptr;
    double nearest = r2;
    for (OpenEvent& o : open)
      for (const std::size_t m : o.members) {
        const double dx = cracks[m].x - c.x, dy = cracks[m].y - c.y, d2 = dx * dx + dy * dy;
        if (d2 <= nearest) {
          nearest = d2;
          join = &o;
        }
      }
    if (!join) {
      events.push_back({c.time, 0, 0, 0, 0, 0, 0, 0, AeType::tensile});
      open.push_back({events.size() - 1, {}, c.time});
      join = &open.back();
    }
    join->members.push_back(k);
    join->last = c.time;
    join->wx += c.energy * c.x;
    join->wy += c.energy * c.y;
    join->mx += c.x;
    join->my += c.y;
  }
  for (const OpenEvent& o : open) close(o, cracks, s, events);
  return events;
}

BValue b_value(std::span<const AeEvent> events, double bin, std::size_t min_events) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::map<long, std::size_t> histogram;  // bin index -> events
  for (const AeEvent& e : events)
    if (std::isfinite(e.magnitude)) ++histogram[std::lround(e.magnitude / bin)];
  if (histogram.empty()) return {nan, nan, nan, 0};
  const auto mode =
      std::max_element(histogram.begin(), histogram.end(),
                       [](const auto& a, const auto& b) { return a.second < b.second; });
  const double mc = static_cast<double>(mode->first) * bin;
  double sum = 0.0;
  std::size_t n = 0;
  for (const AeEvent& e : events)
    if (std::isfinite(e.magnitude) && std::lround(e.magnitude / bin) >= mode->first) {
      sum += static_cast<double>(std::lround(e.magnitude / bin)) * bin;
      ++n;
    }
  if (n < min_events) return {nan, nan, mc, n};
  const double b = std::numbers::log10e / (sum / static_cast<double>(n) - (mc - 0.5 * bin));
  return {b, b / std::sqrt(static_cast<double>(n)), mc, n};
}

}  // namespace vorodec::measure
