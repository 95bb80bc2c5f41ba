#pragma once
// Acoustic emission from cracks (docs/theory.md §15.4, after Hazzard & Young): cracks close in
// space and time are one event. A crack joins an open event when it lies within `radius` of one of
// the event's cracks and follows the event's last crack within radius / shear_wave_speed, the time
// a shear wave needs to cross that distance; an event no crack has joined for that long is closed.
#include <cstddef>
#include <span>
#include <vector>

#include "vorodec/laws/contact_law.hpp"

namespace vorodec::measure {

struct AeSettings {
  double radius;            // m
  double shear_wave_speed;  // m/s
  double thickness;         // m, out of plane: crack energies are per metre of it
};

enum class AeType : int { tensile = 1, shear = 2, mixed = 3 };

struct AeEvent {
  double time;       // s, of its first crack
  double duration;   // s, first to last crack
  double x, y;       // m, centroid of its cracks weighted by their energy (plain mean if none)
  double energy;     // J, released strain energy of its cracks times the thickness
  double magnitude;  // (2/3) log10(energy / J) - 3.2 (Gutenberg-Richter energy relation)
  std::size_t cracks, tensile;  // crack count and how many of them are tensile
  AeType type;                  // all tensile, all shear, or mixed
};

// Events of `cracks` in the order of their first crack; cracks must be in time order (the
// solver's list is).
std::vector<AeEvent> cluster_events(std::span<const laws::CrackEvent> cracks, const AeSettings& s);

// Gutenberg-Richter b-value by Aki's maximum likelihood over the events of magnitude >= mc, with
// Utsu's half-bin correction for magnitudes binned at `bin`: b = log10(e) / (mean(M) - (mc -
// bin / 2)), and Aki's standard error b / sqrt(n). mc is the magnitude of completeness by
// maximum curvature (the most populated bin). b = NaN when fewer than `min_events` are counted.
struct BValue {
  double b, error, mc;
  std::size_t events;  // counted (M >= mc)
};
BValue b_value(std::span<const AeEvent> events, double bin = 0.1, std::size_t min_events = 10);

}  // namespace vorodec::measure
