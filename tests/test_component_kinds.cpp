// The optional components' kinds (solver/model/component_kind.hpp): their keys join the scene's
// key table where they say, the loader parses each kind's keys once into its own typed
// options (Config::components, in registration order), and the Simulation makes the
// components from those options.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "solver/components/actuation.hpp"
#include "solver/model/component_kind.hpp"
#include "solver/components/contact_component.hpp"
#include "solver/components/control_volume_forces.hpp"
#include "solver/components/implicit_velocity_step.hpp"
#include "solver/components/markers.hpp"
#include "solver/components/rigid_bodies.hpp"
#include "solver/components/solids.hpp"
#include "solver/scene/scene.hpp"
#include "solver/scene/scene_keys.hpp"
#include "solver/model/simulation.hpp"
#include "solver/components/tracers.hpp"
#include "solver/io/checkpoint_io.hpp"
#include "solver/model/diagnostics.hpp"
#include "solver/model/implicit_step.hpp"
#include "tests/test_helpers.hpp"
#include "tests/fixtures/scene_text.hpp"

namespace refmap {
namespace {

using testing::box_scene;
using testing::disc_toml;
using testing::kWalls;

/// The position of table.name in scene_keys(), -1 if absent.
long index_of(const std::string& table, const std::string& name) {
  const auto& k = scene_keys();
  for (std::size_t i = 0; i < k.size(); ++i)
    if (k[i].table == table && k[i].name == name) return long(i);
  return -1;
}

TEST(ComponentKinds, KeysAreInTheTableOnceWhereTheKindSays) {
  for (const ComponentKind& kind : component_kinds())
    for (const KeyDef& k : kind.keys) {
      int n = 0;
      for (const KeyDef& s : scene_keys()) n += s.table == k.table && s.name == k.name;
      EXPECT_EQ(n, 1) << k.dotted() << " of kind " << kind.name;
    }
  // the anchors: output.wall_stress right after output.diagnostics_every, output.body_force
  // after it, solid.markers right after solid.clamp; the kinds' own tables after theirs
  EXPECT_EQ(index_of("output", "wall_stress"), index_of("output", "diagnostics_every") + 1);
  EXPECT_EQ(index_of("output", "body_force"), index_of("output", "wall_stress") + 1);
  EXPECT_EQ(index_of("solid", "markers"), index_of("solid", "clamp") + 1);
  EXPECT_EQ(index_of("solid", "boundary_markers"), index_of("solid", "markers") + 1);
  EXPECT_EQ(index_of("solid", "actuation"), index_of("solid", "boundary_markers") + 1);
  std::vector<std::string> tables;
  for (const TableDef& t : scene_tables()) tables.push_back(t.name);
  const auto at = [&](const char* name) { return std::find(tables.begin(), tables.end(), name) - tables.begin(); };
  EXPECT_EQ(at("tracers"), at("probe") + 1);
  EXPECT_EQ(at("solid.actuation"), at("solid") + 1);
  // the solids' tables where the core's were, a rigid body's keys right after a solid's
  // initial velocity, the implicit step's after the core's choice of the step
  EXPECT_GT(at("solids"), at("tracers"));
  EXPECT_EQ(at("solid"), at("solids") + 1);
  EXPECT_EQ(at("suspension"), at("solid.actuation") + 1);
  EXPECT_EQ(index_of("solid", "motion"), index_of("solid", "omega") + 1);
  EXPECT_EQ(index_of("solid", "clamp"), index_of("solid", "pivot") + 1);
  EXPECT_EQ(index_of("time", "solid_implicit_k"), index_of("time", "verlet_project_drift") + 1);
  EXPECT_EQ(index_of("time", "implicit_tol"), index_of("time", "solid_rate_sweeps") + 1);
  // the registration order is the order of the hooks: actuation before the tracers. The
  // first four kinds only read keys (the Simulation adds their components): the solids' and
  // the implicit step's into the Config, contact's into its options
  ASSERT_GE(component_kinds().size(), 9u);
  EXPECT_EQ(component_kinds()[0].name, "solids");
  EXPECT_EQ(component_kinds()[1].name, "rigid_bodies");
  EXPECT_EQ(component_kinds()[2].name, "implicit_velocity_step");
  EXPECT_EQ(component_kinds()[3].name, "contact");
  EXPECT_EQ(component_kinds()[4].name, "actuation");
  EXPECT_EQ(component_kinds()[5].name, "tracers");
}

// Each key has one home: the solids' shape and shared options are the solids' kind's, a
// rigid body's motion the rigid bodies', the implicit solve's tolerance the implicit step's
// (none of them is the core's any more), and the kinds that write the Config have no options
// of their own.
TEST(ComponentKinds, TheSolidsRigidBodiesAndImplicitStepDeclareTheirOwnKeys) {
  const auto declares = [](const char* kind, const char* table, const char* name) {
    for (const KeyDef& k : component_kind(kind).keys)
      if (k.table == table && k.name == name) return true;
    return false;
  };
  EXPECT_TRUE(declares("solids", "solid", "shape"));
  EXPECT_TRUE(declares("solids", "solids", "band"));
  EXPECT_FALSE(declares("solids", "solid", "motion"));
  EXPECT_TRUE(declares("rigid_bodies", "solid", "motion"));
  EXPECT_TRUE(declares("rigid_bodies", "solid", "clamp"));
  EXPECT_TRUE(declares("implicit_velocity_step", "time", "implicit_tol"));
  EXPECT_FALSE(declares("implicit_velocity_step", "time", "solid_stress"));  // the core's choice of the step
  for (const char* kind : {"solids", "implicit_velocity_step"}) {
    EXPECT_NE(component_kind(kind).configure, nullptr) << kind;
    EXPECT_EQ(component_kind(kind).parse, nullptr) << kind;
  }
  // a scene's solids and implicit constants still reach the Config through them
  const Config c = load_scene_string(
      box_scene(16, kWalls, "[solids]\nband = 7.0\n" + disc_toml("a", 0.5, 0.5, 0.2, 1.0, "")), "own_keys.toml", {"time.solid_stress=\"semi_implicit\"", "time.implicit_tol=1e-7"});
  ASSERT_EQ(c.solids.size(), 1u);
  EXPECT_EQ(c.solids[0].name, "a");
  EXPECT_EQ(c.solid_opt.band, 7.0);
  EXPECT_EQ(c.implicit_tol, 1e-7);
}

TEST(ComponentKinds, OptionsAreParsedOnceIntoTypes) {
  const std::string text =
      box_scene(16, kWalls,
                "[output]\nbody_force = \"control_volume\"\n"
                "[[tracers]]\nline = [[0.1, 0.2], [0.3, 0.2]]\nn = 5\n"
                "[[tracers]]\nbox = [[0.1, 0.1], [0.9, 0.3]]\nnx = 4\nny = 2\n" +
                    disc_toml("a", 0.5, 0.6, 0.2, 1.0, "markers = [[0.5, 0.6]]\nboundary_markers = 3\n") +
                    disc_toml("b", 0.5, 0.15, 0.1, 1.0, "actuation = { stretch_x = \"1 + 0.1*t\" }\n"));
  const Config c = load_scene_string(text, "kinds.toml");
  // present in registration order; wall stress is off (its default)
  std::vector<std::string> names;
  for (const auto& [name, o] : c.components) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"actuation", "tracers", "markers", "body forces"}));
  EXPECT_EQ(c.component_options<ComponentOptions>("wall stress"), nullptr);

  const auto* tr = c.component_options<TracerOptions>("tracers");
  ASSERT_NE(tr, nullptr);
  ASSERT_EQ(tr->seeds.size(), 2u);
  EXPECT_FALSE(tr->seeds[0].box);
  EXPECT_EQ(tr->seeds[0].n, 5);
  EXPECT_EQ(tr->seeds[0].x1, 0.3);
  EXPECT_TRUE(tr->seeds[1].box);
  EXPECT_EQ(tr->seeds[1].nx * tr->seeds[1].ny, 8);

  const auto* mk = c.component_options<MarkerOptions>("markers");
  ASSERT_NE(mk, nullptr);
  ASSERT_EQ(mk->per_solid.size(), 2u);
  EXPECT_EQ(mk->per_solid[0].points.size(), 1u);
  EXPECT_EQ(mk->per_solid[0].boundary, 3);
  EXPECT_EQ(mk->per_solid[1].boundary, 0);

  const auto* ac = c.component_options<ActuationOptions>("actuation");
  ASSERT_NE(ac, nullptr);
  ASSERT_EQ(ac->per_solid.size(), 2u);
  EXPECT_FALSE(ac->per_solid[0].enabled());
  EXPECT_EQ(ac->per_solid[1].stretch_x.text(), "1 + 0.1*t");
  EXPECT_TRUE(ac->per_solid[1].shear.empty());

  // the Simulation makes one component per kind: 5 + 8 tracers, 1 + 3 markers
  Simulation sim(c);
  ASSERT_NE(sim.component<Tracers>(), nullptr);
  EXPECT_EQ(sim.component<Tracers>()->size(), 13);
  ASSERT_NE(sim.component<Markers>(), nullptr);
  EXPECT_EQ(sim.component<Markers>()->points().size(), 4u);
  EXPECT_NE(sim.control_volume_forces(), nullptr);
  // and the two components that every scene with solids has: the solids' own
  // (solver/components/solids.hpp) and contact (solver/components/contact_component.hpp)
  ASSERT_NE(sim.component<Solids>(), nullptr);
  ASSERT_NE(sim.component<ContactComponent>(), nullptr);
  EXPECT_EQ(sim.components().size(), 6u);
}

TEST(ComponentKinds, ASceneWithoutThemHasNone) {
  const Config c = load_scene_string(box_scene(16, kWalls, "[output]\nwall_stress = false\n"), "none.toml");
  EXPECT_TRUE(c.components.empty());
  Simulation sim(c);
  EXPECT_TRUE(sim.components().empty());
}

// The solids are a component (solver/components/solids.hpp) that the step calls through typed
// calls at Algorithm 1's fixed points (steps 1-3, the stress of eq. 5.2), not through hooks:
// made before the initial state and attached first, its records where the Simulation wrote
// the solids' before (after the flow's, before contact's), no row of its own in the timing
// table; the Simulation's accessors answer from it. A scene without solids has none.
TEST(Components, SolidsAreTheFirstComponentAndKeepTheirRecords) {
  const Config c = load_scene(testing::scene_path("two_solids_tgv.toml"), {"grid.nx=32", "grid.ny=32"});
  Simulation sim(c);
  ASSERT_GE(sim.components().size(), 2u);
  const auto* solids = dynamic_cast<const Solids*>(sim.components()[0].get());
  ASSERT_NE(solids, nullptr);
  EXPECT_EQ(sim.solid_set(), solids);
  EXPECT_FALSE(solids->has_hooks());
  EXPECT_NE(dynamic_cast<const ContactComponent*>(sim.components()[1].get()), nullptr);
  ASSERT_EQ(sim.solids().size(), 2u);
  EXPECT_EQ(&sim.solids(), &solids->list());
  EXPECT_TRUE(solids->elastic());
  EXPECT_EQ(&sim.solid_stress_xx(), &solids->stress_xx());

  const std::vector<std::string> tags = sim.state().tags();
  const auto at = [&](const std::string& t) { return std::find(tags.begin(), tags.end(), t) - tags.begin(); };
  const std::ptrdiff_t count = at("sim.solids");
  ASSERT_LT(count + 2, std::ptrdiff_t(tags.size()));
  EXPECT_EQ(tags[std::size_t(count - 1)], "sim.poisson_residual");
  EXPECT_EQ(tags[std::size_t(count + 1)], "solid0");
  EXPECT_EQ(tags[std::size_t(count + 2)], "solid1");
  EXPECT_EQ(at("sim.sxx"), at("sim.gyf") + 1);
  EXPECT_GT(at("contact"), count + 2);

  for (int k = 0; k < 2; ++k) sim.step();
  EXPECT_EQ(sim.elastic_energy(), solids->elastic_energy());
  EXPECT_GT(sim.elastic_energy(), 0.0);
  EXPECT_EQ(sim.timers().entries().count("solids"), 0u);
  EXPECT_EQ(sim.timers().entries().at("level set").calls, 4);  // one per solid and step

  Simulation fluid(load_scene_string(box_scene(16, kWalls, ""), "fluid.toml"));
  EXPECT_EQ(fluid.solid_set(), nullptr);
  EXPECT_TRUE(fluid.solids().empty());
  EXPECT_EQ(fluid.solid_stress_xx().nx(), 0);
  EXPECT_EQ(fluid.elastic_energy(), 0.0);
}

/// Records the step points it is called at, in order.
class PointLog : public Component {
 public:
  const char* name() const override { return "point log"; }
  void at(StepPoint p, Simulation&, double) override { points.push_back(p); }
  std::vector<StepPoint> points;
};

// The rigid bodies are a component (solver/components/rigid_bodies.hpp): made before the
// initial state, attached right after contact (its cut faces come after the contact force in
// G_f), its state after the contact's; and a step calls the points in the order of
// solver/model/component.hpp, each once except G_f's (predictor and cell velocities).
TEST(Components, RigidBodiesComeAfterContactAndTheStepCallsThePointsInOrder) {
  const std::string body = "[[solid]]\nname = \"post\"\nshape = \"circle\"\ncenter = [0.5, 0.5]\nradius = 0.15\n"
                           "density = 1.0\nmotion = \"fixed\"\nforcing = \"sharp\"\n";
  const Config c = load_scene_string(box_scene(16, kWalls, body), "post.toml");
  Simulation sim(c);
  ASSERT_EQ(sim.components().size(), 3u);
  EXPECT_NE(dynamic_cast<const Solids*>(sim.components()[0].get()), nullptr);
  EXPECT_NE(dynamic_cast<const ContactComponent*>(sim.components()[1].get()), nullptr);
  const auto* rb = dynamic_cast<const RigidBodiesComponent*>(sim.components()[2].get());
  ASSERT_NE(rb, nullptr);
  EXPECT_EQ(sim.bodies(), &rb->bodies());
  const std::vector<std::string> tags = sim.state().tags();
  const auto at = [&](const char* t) { return std::find(tags.begin(), tags.end(), t) - tags.begin(); };
  ASSERT_LT(at("bodies"), std::ptrdiff_t(tags.size()));
  EXPECT_GT(at("bodies"), at("contact"));

  auto log = std::make_unique<PointLog>();
  PointLog* p = log.get();
  sim.add_component(std::move(log));
  sim.step();
  using P = StepPoint;
  const std::vector<StepPoint> expected = {P::Begin,  P::Advected,           P::Stressed,
                                           P::PoissonCoefficients,        P::Forces,
                                           P::FaceAccelerations,          P::BeforePredictor,
                                           P::Predicted, P::PressureUpdated, P::FaceAccelerations,
                                           P::End};
  EXPECT_EQ(p->points, expected);
}

// With held cells (forcing_hold, the increment splitting) the bodies' component is also
// called where the substeps form their rates: it makes the held cells at Substeps (before the
// step's G_f^n), takes the rate of each RK-4 stage and of the explicit viscous step at Rates,
// and with the implicit viscous step the solve's rates at HeldSolved instead of the last.
TEST(Components, HeldCellsAreCalledAtTheSubstepsPoints) {
  using P = StepPoint;
  for (const bool implicit : {false, true}) {
    const std::string body = "[[solid]]\nname = \"post\"\nshape = \"circle\"\ncenter = [0.5, 0.5]\nradius = 0.15\n"
                             "density = 1.0\nmotion = \"fixed\"\nforcing = \"sharp\"\nforcing_hold = true\n";
    std::string scene = box_scene(16, kWalls, body) + "\n";
    Config c = load_scene_string(scene, "post.toml");
    c.splitting = Splitting::Increment;
    if (implicit) c.viscous_time = ViscousTime::Implicit;
    Simulation sim(c);
    ASSERT_NE(sim.components()[2]->held_cells(), nullptr);
    auto log = std::make_unique<PointLog>();
    PointLog* p = log.get();
    sim.add_component(std::move(log));
    sim.step();
    std::vector<StepPoint> expected = {P::Begin, P::Substeps, P::FaceAccelerations, P::Rates, P::Rates, P::Rates,
                                       P::Rates, P::Advected, implicit ? P::HeldSolved : P::Rates, P::Stressed,
                                       P::PoissonCoefficients, P::Forces, P::FaceAccelerations, P::BeforePredictor,
                                       P::Predicted, P::PressureUpdated, P::FaceAccelerations, P::End};
    EXPECT_EQ(p->points, expected) << "implicit = " << implicit;
  }
}

// The implicit velocity step is a component (solver/components/implicit_velocity_step.hpp)
// that takes the velocity step of eq. (5.2): attached after contact, its records where the
// flow's end (after the solids', before the Verlet coupling's and contact's: the order of the
// checkpoints written before it was a component), its column right after the flow's last
// built-in one (and the contact's), before the Picard columns; a checkpoint carries its warm
// start, so a resumed run's solves take the same cycles and the state continues bit for
// bit. An explicit run has none of it.
TEST(Components, ImplicitVelocityStepKeepsItsRecordsColumnAndWarmStart) {
  const std::vector<std::string> implicit_tags = {
      "implicit.du",    "implicit.dv",         "implicit.du2",      "implicit.dv2",
      "implicit.dt1",   "implicit.dt2",        "implicit.steps",    "implicit.iterations",
      "implicit.residual", "implicit.total_iterations", "implicit.sweep_change"};
  // the implicit viscous step with the explicit stress: the Verlet coupling's records follow
  const Config c = load_scene(testing::scene_path("disc_tgv.toml"), {"time.viscous=\"implicit\"", "grid.nx=32", "grid.ny=32"});
  Simulation sim(c);
  ASSERT_EQ(sim.components().size(), 3u);
  EXPECT_NE(dynamic_cast<const ContactComponent*>(sim.components()[1].get()), nullptr);
  const auto* step = dynamic_cast<const ImplicitVelocityStep*>(sim.components()[2].get());
  ASSERT_NE(step, nullptr);
  EXPECT_TRUE(step->takes_velocity_step());
  EXPECT_EQ(sim.implicit_velocity(), &step->solver());

  // the records: contiguous, in the solver's order, after the last solid's, before the rest
  const std::vector<std::string> tags = sim.state().tags();
  const auto at = [&](const std::string& t) { return std::find(tags.begin(), tags.end(), t) - tags.begin(); };
  const std::ptrdiff_t first = at("implicit.du");
  ASSERT_LT(first, std::ptrdiff_t(tags.size()));
  ASSERT_LT(first + std::ptrdiff_t(implicit_tags.size()), std::ptrdiff_t(tags.size()));  // the Verlet records follow
  EXPECT_EQ(std::vector<std::string>(tags.begin() + first, tags.begin() + first + std::ptrdiff_t(implicit_tags.size())),
            implicit_tags);
  EXPECT_EQ(tags[std::size_t(first - 1)], "solid0");
  EXPECT_EQ(tags[std::size_t(first) + implicit_tags.size()], "sim.verlet.fpx");
  EXPECT_GT(at("contact"), first);

  // the column: after total_energy and the contact's, before the Picard columns
  Simulation picard(load_scene(testing::scene_path("disc_tgv.toml"), {"time.solid_stress=\"semi_implicit\"", "grid.nx=32",
                                                                      "grid.ny=32", "time.solid_picard_iterations=1"}));
  const std::vector<std::string> cols = diagnostic_columns(picard);
  const auto col = [&](const char* n) { return std::find(cols.begin(), cols.end(), n) - cols.begin(); };
  ASSERT_LT(col("implicit_iterations"), std::ptrdiff_t(cols.size()));
  EXPECT_EQ(col("contact_energy"), col("total_energy") + 1);
  EXPECT_EQ(col("implicit_iterations"), col("contact_energy") + 1);
  EXPECT_EQ(col("picard_change"), col("implicit_iterations") + 1);

  // a checkpoint after 3 steps (the warm start extrapolates the last two changes), resumed
  for (int k = 0; k < 3; ++k) sim.step();
  CheckpointWriter w;
  sim.save_state(w);
  Simulation resumed(c);
  CheckpointReader r = CheckpointReader::from_payload(w.payload(), "the test's checkpoint");
  resumed.load_state(r);
  EXPECT_EQ(resumed.implicit_velocity()->total_iterations(), sim.implicit_velocity()->total_iterations());
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(sim.step(), resumed.step());
    EXPECT_EQ(resumed.implicit_velocity()->last_iterations(), sim.implicit_velocity()->last_iterations()) << k;
    EXPECT_EQ(diagnostic_values(resumed, 0.0, 0.0), diagnostic_values(sim, 0.0, 0.0)) << k;
  }
  CheckpointWriter a, b;
  sim.save_state(a);
  resumed.save_state(b);
  EXPECT_TRUE(a.payload() == b.payload()) << "the state after the resumed steps differs";

  // without solids: right after the flow's last column; explicit: nothing of it
  const Config tg = load_scene(testing::scene_path("taylor_green.toml"), {"time.viscous=\"implicit\"", "grid.nx=16", "grid.ny=16"});
  Simulation fluid(tg);
  const std::vector<std::string> fc = diagnostic_columns(fluid);
  ASSERT_GE(fc.size(), 2u);
  EXPECT_EQ(fc.back(), "implicit_iterations");
  EXPECT_EQ(fc[fc.size() - 2], "wall_time");
  Simulation expl(load_scene(testing::scene_path("taylor_green.toml"), {"grid.nx=16", "grid.ny=16"}));
  EXPECT_EQ(expl.implicit_velocity(), nullptr);
  EXPECT_EQ(expl.component<ImplicitVelocityStep>(), nullptr);
  for (const std::string& t : expl.state().tags()) EXPECT_NE(t.rfind("implicit.", 0), 0u) << t;
}

}  // namespace
}  // namespace refmap
