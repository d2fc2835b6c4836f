#pragma once
// The columns of diagnostics.csv: one table of named columns (global ones, then the
// per-solid ones repeated for every solid as solidK_NAME). A new column is one entry in
// the tables of diagnostics.cpp.
#include <string>
#include <vector>

namespace refmap {

class Simulation;

/// The column names for this simulation (the solid columns only when it has solids).
std::vector<std::string> diagnostic_columns(const Simulation& sim);

/// One row of values in the order of diagnostic_columns(): the state after a step of size
/// `last_dt` (0 before the first step), `wall_s` wall seconds into the run.
std::vector<double> diagnostic_values(const Simulation& sim, double last_dt, double wall_s);

}  // namespace refmap
