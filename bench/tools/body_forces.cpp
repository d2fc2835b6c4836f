// refmap_body_forces: both force estimators of body 0 over one run, one row per step
// (docs/bodies.md, "Force from a control volume"; results/README.md, "Body forces: control
// volume against forcing"). The state does not depend on output.body_force, so one run
// gives both: the direct forcing's force (RigidBodies::load, the default columns) and the
// control-volume balance (ControlVolumeForces::load, output.body_force = "control_volume"),
// with the momentum of the soft solids clamped to body 0 (rho_s times area times mean
// velocity, as bench/fsi_summary.py adds its rate of change to the forcing's force).
//
//   refmap_body_forces SCENE T_BEGIN [key=value ...] > rows.csv
// Columns: time, forcing_fx, forcing_fy, forcing_torque, cv_fx, cv_fy, cv_torque,
// clamped_px, clamped_py (rows from the first step ending at or after T_BEGIN).
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "solver/components/control_volume_forces.hpp"
#include "solver/scene/scene.hpp"
#include "solver/model/simulation.hpp"

int main(int argc, char** argv) {
  using namespace refmap;
  if (argc < 3) {
    std::fprintf(stderr, "usage: refmap_body_forces SCENE T_BEGIN [key=value ...]\n");
    return 2;
  }
  std::vector<std::string> sets(argv + 3, argv + argc);
  sets.push_back("output.body_force=\"control_volume\"");
  const double t_begin = std::atof(argv[2]);
  try {
    Config cfg = load_scene(argv[1], sets);
    Simulation sim(cfg);
    if (!sim.bodies() || !sim.bodies()->rigid(0)) {
      std::fprintf(stderr, "refmap_body_forces: solid 0 of %s is not a rigid body\n", argv[1]);
      return 2;
    }
    std::printf("time,forcing_fx,forcing_fy,forcing_torque,cv_fx,cv_fy,cv_torque,clamped_px,clamped_py\n");
    long max_steps = cfg.max_steps > 0 ? cfg.max_steps : -1;
    while (sim.time() < cfg.t_end * (1.0 - 1e-12) && max_steps-- != 0) {
      sim.step();
      if (sim.time() < t_begin) continue;
      const BodyLoad& f = sim.bodies()->load(0);
      const BodyLoad& c = sim.control_volume_forces()->load(0);
      double px = 0.0, py = 0.0;
      const auto& d = sim.solid_diagnostics();
      for (std::size_t k = 0; k < cfg.solids.size(); ++k)
        if (cfg.solids[k].clamp_index == 0) {
          px += cfg.solids[k].density * d[k].area * d[k].u;
          py += cfg.solids[k].density * d[k].area * d[k].v;
        }
      std::printf("%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", sim.time(), f.fx, f.fy, f.torque, c.fx,
                  c.fy, c.torque, px, py);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "refmap_body_forces: %s\n", e.what());
    return 2;
  }
  return 0;
}
