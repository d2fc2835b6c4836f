// The step that lands on a frame or t_end (solver/app/step_landing.hpp).
#include <gtest/gtest.h>

#include "solver/app/step_landing.hpp"

namespace refmap {
namespace {

// The FSI3 case: dt = 5e-5, eps_t = 1e-11 (t_end = 10); after a full step the frame would be
// 1.5e-11 away, a sliver the health check calls a collapsed step (dt <= 1e-9 t_end = 1e-8).
TEST(StepLanding, StretchesAStepThatWouldLeaveASliver) {
  const double dt = 5e-5, eps_t = 1e-11, gap = dt + 1.5e-11;
  EXPECT_EQ(landing_step(dt, gap, eps_t), gap);
}

// gaps within eps_t of dt, the ordinary rounding of an exact multiple, keep dt to the bit
TEST(StepLanding, KeepsTheStepWhenTheGapIsWithinTolerance) {
  const double dt = 5e-5, eps_t = 1e-11;
  EXPECT_EQ(landing_step(dt, dt + 0.5 * eps_t, eps_t), dt);
  EXPECT_EQ(landing_step(dt, 3.0 * dt, eps_t), dt);  // a frame several steps away
  EXPECT_EQ(landing_step(dt, dt * (1.0 + 2e-4), eps_t), dt);  // more than 1e-4 dt short: a real step follows
}

TEST(StepLanding, CutsAStepThatWouldOvershoot) {
  const double dt = 5e-5, eps_t = 1e-11;
  EXPECT_EQ(landing_step(dt, 0.3 * dt, eps_t), 0.3 * dt);
}

}  // namespace
}  // namespace refmap
