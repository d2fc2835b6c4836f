// make_poisson_solver: method dispatch (solver/pressure/poisson.hpp), and the names of the
// solver's options. The method, cycle and smoother are enums, named here and validated
// once by the scene loader; the numeric options are checked here because tests and
// benchmarks build PoissonOptions directly.
#include <stdexcept>
#include <string>

#include "solver/pressure/poisson.hpp"
#include "solver/pressure/poisson_cg.hpp"
#include "solver/pressure/poisson_multigrid.hpp"

namespace refmap {

// The scene-file names (solver/io/enum_names.hpp); the order is that of the choices in error
// messages and in scenes/README.md.
std::span<const OptionName<PoissonMethod>> option_names(PoissonMethod) {
  static const OptionName<PoissonMethod> n[] = {
      {PoissonMethod::Multigrid, "multigrid"}, {PoissonMethod::Cg, "cg"}, {PoissonMethod::Mgpcg, "mgpcg"}};
  return name_list(n);
}

std::span<const OptionName<MgCycle>> option_names(MgCycle) {
  static const OptionName<MgCycle> n[] = {{MgCycle::V, "V"}, {MgCycle::F, "F"}};
  return name_list(n);
}

std::span<const OptionName<MgSmoother>> option_names(MgSmoother) {
  static const OptionName<MgSmoother> n[] = {{MgSmoother::Rbgs, "rbgs"}, {MgSmoother::Jacobi, "jacobi"}};
  return name_list(n);
}

std::span<const OptionName<MgCoarseOperator>> option_names(MgCoarseOperator) {
  static const OptionName<MgCoarseOperator> n[] = {{MgCoarseOperator::Average, "average"},
                                                   {MgCoarseOperator::Harmonic, "harmonic"},
                                                   {MgCoarseOperator::Galerkin, "galerkin"}};
  return name_list(n);
}

std::unique_ptr<PoissonSolver> make_poisson_solver(const PoissonOptions& opt) {
  if (opt.pre_smooth < 0 || opt.post_smooth < 0 || opt.pre_smooth + opt.post_smooth < 1)
    throw std::invalid_argument("Poisson solver: pre_smooth/post_smooth must be >= 0, not both 0 (got " +
                                std::to_string(opt.pre_smooth) + "/" +
                                std::to_string(opt.post_smooth) + ")");
  if (!(opt.tol > 0))
    throw std::invalid_argument("Poisson solver: tol must be > 0");
  if (opt.max_iter < 0)
    throw std::invalid_argument("Poisson solver: max_iter must be >= 0");
  if (opt.coarse_cells < 1)
    throw std::invalid_argument("Poisson solver: coarse_cells must be >= 1");
  if (!(opt.jacobi_omega > 0 && opt.jacobi_omega <= 1))
    throw std::invalid_argument("Poisson solver: jacobi_omega must be in (0, 1]");
  if (!(opt.rbgs_omega > 0 && opt.rbgs_omega < 2))
    throw std::invalid_argument("Poisson solver: rbgs_omega must be in (0, 2)");
  switch (opt.method) {
    case PoissonMethod::Multigrid: return std::make_unique<MultigridSolver>(opt);
    case PoissonMethod::Cg: return std::make_unique<CGSolver>(opt);
    case PoissonMethod::Mgpcg: return std::make_unique<MGPCGSolver>(opt);
  }
  throw std::invalid_argument("Poisson solver: unknown method " + std::to_string(int(opt.method)));
}

}  // namespace refmap
