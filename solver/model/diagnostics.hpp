#pragma once
// The columns of diagnostics.csv (one row per output step, the global quantities) and of
// solids.csv (long format: one row per solid and output step, the per-solid quantities,
// so its width does not grow with the number of solids). A new column is one entry in the
// tables of diagnostics.cpp.
#include <string>
#include <vector>

namespace refmap {

class Simulation;

/// The column names for this simulation (the solid columns only when it has solids).
std::vector<std::string> diagnostic_columns(const Simulation& sim);

/// One row of values in the order of diagnostic_columns(): the state after a step of size
/// `last_dt` (0 before the first step), `wall_s` wall seconds into the run.
std::vector<double> diagnostic_values(const Simulation& sim, double last_dt, double wall_s);

/// The columns of solids.csv: step, time, solid (its index in the scene), the solid's
/// quantities, and the rigid bodies' when the scene has one (nan on the other solids'
/// rows). Empty without solids (no file).
std::vector<std::string> solid_columns(const Simulation& sim);

/// The rows of solids.csv for the current state, one per solid in index order.
std::vector<std::vector<double>> solid_values(const Simulation& sim);

}  // namespace refmap
