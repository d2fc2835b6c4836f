#include "solver/scene/memory_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/grid.hpp"
#include "solver/model/shape.hpp"

namespace refmap {

std::size_t field_bytes(int nx, int ny, int ng) {
  // the layout of Array2<double>::resize: lead padding, rows rounded to 64 bytes
  constexpr int A = 8;
  const int lead = (A - ng % A) % A;
  const std::size_t stride = std::size_t((lead + nx + 2 * ng + A - 1) / A) * A;
  return stride * std::size_t(ny + 2 * ng) * sizeof(double);
}

std::string format_bytes(std::size_t b) {
  char buf[64];
  const double x = double(b);
  if (x >= 1024.0 * 1024 * 1024) std::snprintf(buf, sizeof buf, "%.2f GiB", x / (1024.0 * 1024 * 1024));
  else if (x >= 1024.0 * 1024) std::snprintf(buf, sizeof buf, "%.1f MiB", x / (1024.0 * 1024));
  else std::snprintf(buf, sizeof buf, "%.0f KiB", x / 1024.0);
  return buf;
}

std::string MemoryEstimate::summary() const {
  return format_bytes(total()) + " (fields " + format_bytes(fields) + ", Poisson " + format_bytes(poisson) +
         ", solids " + format_bytes(solids) + ", output " + format_bytes(output) + ")";
}

MemoryEstimate estimate_memory(const Config& cfg) {
  const Grid& g = cfg.grid;
  const int nx = g.nx, ny = g.ny, ng = Grid::ng;
  const std::size_t cell = field_bytes(nx, ny, ng), xface = field_bytes(nx + 1, ny, ng),
                    yface = field_bytes(nx, ny + 1, ng);
  MemoryEstimate m;
  bool elastic = false;
  for (const SolidSpec& s : cfg.solids) elastic = elastic || s.mu_s > 0.0;
  // Simulation: 16 state/work cell fields + 2 RK-4 stage fields; 3 x-face and 3 y-face
  // fields; the blended stress (3 cell fields) with elastic solids; the contact force
  // (1 x-face, 1 y-face) with solids
  m.fields = 18 * cell + 3 * (xface + yface);
  if (elastic) m.fields += 3 * cell;
  // time.elastic_coupling = "verlet": the last force, its change and the viscous force
  // (6 cell fields), the last and the midpoint face velocities (2 x-face, 2 y-face)
  if (elastic && verlet_coupling(cfg))
    m.fields += 6 * cell + 2 * (xface + yface);
  if (!cfg.solids.empty()) m.fields += xface + yface;
  // Poisson: multigrid keeps the finest operator (tx, ty, invd), the scaled right-hand
  // side and the coarse levels (tx, ty, invd, x, f: 5 fields on 1/4 + 1/16 + ... = 1/3 of
  // the cells); CG keeps the operator and 4 vectors; MG-PCG the multigrid and 5 vectors
  const std::size_t multigrid = 4 * cell + 5 * cell / 3;
  switch (cfg.poisson.method) {
    case PoissonMethod::Multigrid: m.poisson = multigrid; break;
    case PoissonMethod::Cg: m.poisson = 7 * cell; break;
    case PoissonMethod::Mgpcg: m.poisson = multigrid + 5 * cell; break;
  }
  // solids: 14 window fields + the known mask + fast-marching workspace (~6 doubles a cell)
  for (const SolidSpec& s : cfg.solids) {
    BoundingBox bb{};
    try {
      bb = make_shape(s.shape)->bbox();
    } catch (...) {
      bb = {g.x0, g.y0, g.x0 + g.lx(), g.y0 + g.ly()};
    }
    const double pad = (cfg.solid_opt.band + 8.0) * g.dx;  // band + the new-window margin
    const int wi = std::min(nx, int(std::ceil((bb.xmax - bb.xmin + 2 * pad) / g.dx)) + 1);
    const int wj = std::min(ny, int(std::ceil((bb.ymax - bb.ymin + 2 * pad) / g.dx)) + 1);
    const std::size_t w = field_bytes(std::max(wi, 1), std::max(wj, 1), ng);
    m.solids += 14 * w + w / 8 + std::size_t(6) * std::size_t(std::max(wi, 1)) * std::size_t(std::max(wj, 1)) * 8;
  }
  // a VTK frame: vorticity and the solids' merged phi, xi (2), normal stress, and one row
  // buffer; written frame by frame
  if (cfg.write_vtk) m.output = (cfg.solids.empty() ? 1 : 5) * cell;
  return m;
}

std::size_t available_memory_bytes() {
  std::size_t avail = 0;
  {
    std::ifstream in("/proc/meminfo");
    std::string key;
    std::size_t kb;
    std::string unit;
    while (in >> key >> kb) {
      std::getline(in, unit);
      if (key == "MemAvailable:") { avail = kb * 1024; break; }
    }
  }
  // a cgroup (v2) limit below the machine's free memory
  std::ifstream lim("/sys/fs/cgroup/memory.max"), cur("/sys/fs/cgroup/memory.current");
  std::string l;
  std::size_t c = 0;
  if (lim >> l && l != "max" && cur >> c) {
    const std::size_t L = std::stoull(l);
    const std::size_t room = L > c ? L - c : 0;
    avail = avail ? std::min(avail, room) : room;
  }
  return avail;
}

}  // namespace refmap
