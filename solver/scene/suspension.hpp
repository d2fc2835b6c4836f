#pragma once
// Random placement of the particles of a suspension ([suspension] table of a scene): N discs
// or ellipses, one size or two, at random positions without overlap, by random sequential
// addition (RSA: each particle is tried at uniformly random positions until it clears every
// particle already placed and the walls; Feder 1980, docs/references.md). The scene loader
// (solver/scene/scene.cpp) expands the placement into ordinary [[solid]] tables, so the particles
// are soft solids like any other.
//
// Deterministic from the seed on every platform: std::mt19937_64's output sequence is fixed
// by the C++ standard, and it is mapped to [0, 1) here (53 bits) instead of through
// std::uniform_real_distribution, whose algorithm is left to the library.
//
// Random sequential addition jams at an area fraction of about 0.547 for equal discs (Feder
// 1980; Hinrichsen, Feder & Jossang 1986), below the densest packing pi / (2 sqrt 3) = 0.907,
// and well before that the attempts per particle grow steeply: a fraction above what the
// bounded attempts reach is reported, with the fraction reached, not placed approximately.
#include <cstdint>
#include <string>
#include <vector>

namespace refmap {

/// The keys of [suspension] (solver/scene/scene_keys.cpp; defaults from this struct).
struct SuspensionSpec {
  long count = 0;              ///< number of particles (0: from area_fraction)
  double area_fraction = 0.0;  ///< requested sum of particle areas / domain area (0: from count)
  double radius = 0.0;         ///< radius of the (first) size; required
  double radius2 = 0.0;        ///< radius of the second size (0: one size)
  double fraction2 = 0.5;      ///< share of the particles (by number) of the second size
  double aspect = 1.0;         ///< a / b of ellipses with the disc's area (1: discs)
  long seed = 1;
  double gap = 0.1;            ///< least surface distance to particles and walls, in units of radius
  long attempts = 10000;       ///< tries per particle before the placement gives up
  std::string name = "p";      ///< particle i is the solid named <name><i>
  // the material of every particle, as the [[solid]] keys of the same names
  double mu_s = 0.0;
  double density = 1.0;
  double viscosity = 0.0;
};

/// One placed particle: an ellipse with semi-axes a >= b (a along `angle`); a disc has a = b.
struct Particle {
  double x = 0.0, y = 0.0, a = 0.0, b = 0.0, angle = 0.0;
  double area() const;
};

/// The domain the particles are placed in: [x0, x0 + lx] x [y0, y0 + ly]; a periodic
/// direction wraps, the others are walls the particles keep `gap` from.
struct PlacementBox {
  double x0 = 0.0, y0 = 0.0, lx = 1.0, ly = 1.0;
  bool periodic_x = false, periodic_y = false;
};

struct Placement {
  std::vector<Particle> particles;  ///< in placement order (larger size first)
  long requested = 0;               ///< particles asked for
  long attempts = 0;                ///< positions tried in all
  bool complete() const { return long(particles.size()) == requested; }
  double area_fraction(const PlacementBox& box) const;
};

/// The particle sizes asked for (radius of each, larger first): `count` of them, or as many
/// as make the area fraction closest to `area_fraction` (within half the smaller particle's
/// area; with two sizes the second size's number is fraction2 of the total, rounded).
std::vector<double> suspension_radii(const SuspensionSpec& s, const PlacementBox& box);

/// Random sequential addition of the particles of suspension_radii. Stops at the first
/// particle that finds no free position in `s.attempts` tries (then !complete()).
Placement place_suspension(const SuspensionSpec& s, const PlacementBox& box);

/// Whether two particles come closer than `gap` (a length), including across the periodic
/// sides of `box` (nearest image). Exact for two discs; for ellipses the boundary of each,
/// grown by gap / 2, is sampled at 256 points and tested against the other grown by gap / 2
/// (the sampling misses at most a sliver of depth a (pi / 256)^2 / 2 ~ 1e-4 a, well below
/// any gap in use).
bool particles_closer_than(const Particle& p, const Particle& q, double gap, const PlacementBox& box);

/// The portable uniform variate in [0, 1): the top 53 bits of one std::mt19937_64 draw.
double uniform01(std::uint64_t draw);

}  // namespace refmap
