// Whole-step timing driver for the peer code IncRMT (github chr1shr/incrmt; Rycroft et al.,
// J. Fluid Mech. 898, A9, 2020), built against a separate checkout of it by
// bench/run_peer_compare.sh (never part of refmap's build; none of the peer's code is in this
// repository). It sets up the peer's `multi-drop` material constants (rho_s = 3, G = 2,
// mu_f = 1e-3, walls on [-1, 1]^2, transition and pinning widths 2.5 dx, the example's
// padding factors 0.8 / 0.4 / 0.8) with the circles of a list file, as refmap's scene of
// the same circles (bench/scenes/make_incrmt_circles.py --list), takes WARM steps, then
// times STEPS steps of the peer's own time step and prints one line:
//   circles M steps seconds us_per_cell_step dt
// Usage: incrmt_discs CIRCLES_FILE M WARM STEPS   (file: one "x y r omega" line per circle)
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "fluid_2d.hh"
#include "obj_field.hh"
#include "object.hh"
#include "sim_type.hh"

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fputs("usage: incrmt_discs CIRCLES_FILE M WARM STEPS\n", stderr);
    return 2;
  }
  const int m = std::atoi(argv[2]), warm = std::atoi(argv[3]), steps = std::atoi(argv[4]);
  std::FILE* in = std::fopen(argv[1], "r");
  if (!in) {
    std::fprintf(stderr, "incrmt_discs: cannot read %s\n", argv[1]);
    return 2;
  }
  std::vector<object*> objs;
  double x, y, r, w;
  while (std::fscanf(in, "%lf %lf %lf %lf", &x, &y, &r, &w) == 4) objs.push_back(new obj_circle(x, y, r, 0, 0, w));
  std::fclose(in);
  sim_type walls(-1, 1, -1, 1, false, false);
  static char outdir[] = "incrmt_discs.odr";  // nothing is written: no output flags, no frames
  fluid_2d f(m, m, walls, 1e-3, 1.0, 2.5, 2.5, 0, 0, outdir);
  mat_const mc(2.0, 3.0, 1.0, true);
  for (object* o : objs) f.add_object(o, mc);
  f.initialize(0.8, 0.4, 0.8);
  const double dt = f.dt_reg;
  for (int k = 0; k < warm; ++k) f.step_forward(dt);
  const double t0 = wtime();
  for (int k = 0; k < steps; ++k) f.step_forward(dt);
  const double s = wtime() - t0;
  std::printf("%d %d %d %.6f %.6f %.6g\n", int(objs.size()), m, steps, s, s * 1e6 / (double(m) * m * steps), dt);
  for (object* o : objs) delete o;
  return 0;
}
