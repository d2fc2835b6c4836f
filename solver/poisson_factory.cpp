// make_poisson_solver: method / cycle / smoother dispatch (solver/poisson.hpp).
#include <stdexcept>
#include <string>

#include "solver/poisson.hpp"
#include "solver/poisson_cg.hpp"
#include "solver/poisson_multigrid.hpp"

namespace refmap {

std::unique_ptr<PoissonSolver> make_poisson_solver(const PoissonOptions& opt) {
  if (opt.cycle != "V" && opt.cycle != "F")
    throw std::invalid_argument("Poisson solver: unknown cycle '" + opt.cycle +
                                "' (expected \"V\" or \"F\")");
  if (opt.smoother != "rbgs" && opt.smoother != "jacobi")
    throw std::invalid_argument("Poisson solver: unknown smoother '" + opt.smoother +
                                "' (expected \"rbgs\" or \"jacobi\")");
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
  if (opt.method == "multigrid") return std::make_unique<MultigridSolver>(opt);
  if (opt.method == "cg") return std::make_unique<CGSolver>(opt);
  if (opt.method == "mgpcg") return std::make_unique<MGPCGSolver>(opt);
  throw std::invalid_argument("Poisson solver: unknown method '" + opt.method +
                              "' (expected \"multigrid\", \"cg\" or \"mgpcg\")");
}

}  // namespace refmap
