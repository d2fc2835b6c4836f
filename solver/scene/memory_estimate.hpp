#pragma once
// What a scene will hold in memory, estimated from the Config before anything is
// allocated, so that a grid far larger than the machine stops at load time with an exit-2
// error naming the grid keys instead of std::bad_alloc mid-run. The estimate counts the
// arrays the solver allocates (solver/model/simulation.hpp, solver/model/solid.hpp, the Poisson
// solver's levels) with the row padding of Field (core/field.hpp); tests check it
// against the resident memory of a constructed Simulation.
#include <cstddef>
#include <string>

#include "solver/model/config.hpp"

namespace refmap {

struct MemoryEstimate {
  std::size_t fields = 0;     ///< the flow solver's grid fields (state, RK-4 work, faces)
  std::size_t poisson = 0;    ///< the Poisson solver's operator and levels
  std::size_t solids = 0;     ///< the solids' windows at the start (they follow the solid)
  std::size_t output = 0;     ///< transient arrays of a VTK frame
  std::size_t total() const { return fields + poisson + solids + output; }
  /// "1.23 GiB (fields 0.9, Poisson 0.2, solids 0.01, output 0.1)"
  std::string summary() const;
};

MemoryEstimate estimate_memory(const Config& cfg);

/// Bytes this process may still allocate: MemAvailable of /proc/meminfo, lowered to the
/// cgroup's memory.max headroom where one is set; 0 when neither can be read.
std::size_t available_memory_bytes();

/// Bytes of one Field of nx x ny cells with `ng` ghost layers (row padding included).
std::size_t field_bytes(int nx, int ny, int ng);

std::string format_bytes(std::size_t b);

}  // namespace refmap
