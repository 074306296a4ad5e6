// The reference stepper and the one run loop (core/stepper.hpp, core/run.hpp):
// the stepper is the integrator with its contacts kept for the next step and
// the divergence monitor, and the loop samples and stops as documented.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/run.hpp"
#include "support/support.hpp"

namespace contact2d {
namespace {

// A box tumbling onto the ground: rotation, several corners, impacts.
Scene tumbling_box(Integrator integrator) {
  Scene scene = default_scene(Shape::Box);
  scene.initial.q = Vec3(0.0, 0.3, 0.4);
  scene.initial.v = Vec3(0.5, 0.0, 3.0);
  scene.sim.integrator = integrator;
  scene.sim.duration = 0.5;
  return scene;
}

class StepperPerIntegrator : public ::testing::TestWithParam<Integrator> {};

// The contacts the stepper keeps are those of its current state, after
// every step: the cache never goes stale (compared bit for bit with a fresh
// find_contacts).
TEST_P(StepperPerIntegrator, KeptContactsAreThoseOfTheCurrentState) {
  const Scene scene = tumbling_box(GetParam());
  ReferenceStepper stepper(scene);
  ContactSet fresh(stepper.model());
  int touching_steps = 0;
  for (int i = 0; i < 5000; ++i) {
    ASSERT_EQ(stepper.step(), StepStatus::Ok);
    find_contacts(stepper.model(), stepper.state().q, fresh);
    ASSERT_EQ(stepper.contacts().size(), fresh.size()) << "step " << i;
    auto a = stepper.contacts().begin();
    for (const Contact& b : fresh) {
      ASSERT_EQ(a->depth, b.depth);
      ASSERT_EQ(a->r(), b.r());
      ++a;
    }
    touching_steps += fresh.empty() ? 0 : 1;
  }
  EXPECT_GT(touching_steps, 100) << "the case must reach the ground";
}

// The stepper is exactly the integrator: the same states, bit for bit, as
// stepping the model with step() and a workspace of its own.
TEST_P(StepperPerIntegrator, MatchesTheBareIntegrator) {
  const Scene scene = tumbling_box(GetParam());
  ReferenceStepper stepper(scene);
  for (int i = 0; i < 3000; ++i) stepper.step();
  const State bare =
      test::advance(make_model(scene), GetParam(), scene.sim.dt, initial_state(scene), 3000);
  EXPECT_EQ(stepper.state().q, bare.q);
  EXPECT_EQ(stepper.state().v, bare.v);
}

INSTANTIATE_TEST_SUITE_P(AllIntegrators, StepperPerIntegrator, ::testing::ValuesIn(kAllIntegrators),
                         [](const auto& info) { return std::string(integrator_name(info.param)); });

TEST(Stepper, ResetFindsTheContactsOfTheNewState) {
  ReferenceStepper stepper(tumbling_box(Integrator::SemiImplicitEuler));
  EXPECT_TRUE(stepper.contacts().empty());
  State sunk;
  sunk.q = Vec3(0.0, 0.05, 0.0);  // the 0.2 m tall box, 5 cm into the ground
  stepper.reset(sunk);
  ASSERT_EQ(stepper.contacts().size(), 2u);
  EXPECT_NEAR(max_penetration(stepper.contacts()), 0.05, 1e-16);
}

// An applied force m·g upwards cancels gravity exactly (F_y = m·g − m·g = 0
// in floating point), so a point mass in flight keeps its velocity exactly.
TEST(Stepper, AppliedForceReachesTheBody) {
  Scene scene = default_scene(Shape::PointMass);
  scene.initial.q = Vec3(0.0, 10.0, 0.0);
  scene.initial.v = Vec3(1.0, 0.5, 0.0);
  ReferenceStepper stepper(scene);
  stepper.set_applied(Vec3(0.0, scene.mass * scene.sim.gravity, 0.0));
  for (int i = 0; i < 1000; ++i) stepper.step();
  EXPECT_EQ(stepper.state().v, Vec3(1.0, 0.5, 0.0));
}

// Samples at t = 0, every output_dt and the last step; none after a divergence.
TEST(RunLoop, SamplesEveryOutputDtAndTheEnd) {
  Scene scene = tumbling_box(Integrator::RK4);
  scene.sim.duration = 0.1;
  scene.sim.output_dt = 0.01;
  const Trajectory t = simulate(scene);
  ASSERT_FALSE(t.divergence);
  ASSERT_EQ(t.samples.size(), 11u);
  for (size_t i = 0; i < t.samples.size(); ++i)
    EXPECT_NEAR(t.samples[i].t, 0.01 * static_cast<double>(i), 1e-12);
}

// An output_dt longer than the run samples t = 0 and the end only, however
// long: 1e300 s (1e304 steps of 1e-4 s) overflowed llround, whose result
// then made the stride 1 and sampled all 1001 steps.
TEST(RunLoop, AnOutputDtBeyondTheRunSamplesTheStartAndTheEnd) {
  Scene scene = tumbling_box(Integrator::RK4);
  scene.sim.duration = 0.1;
  for (const double output_dt : {0.2, 1e15, 1e300}) {
    scene.sim.output_dt = output_dt;
    EXPECT_EQ(sample_stride(scene.sim), step_count(scene.sim)) << output_dt;
    const Trajectory t = simulate(scene);
    ASSERT_EQ(t.samples.size(), 2u) << output_dt;
    EXPECT_EQ(t.samples[0].t, 0.0);
    EXPECT_NEAR(t.samples[1].t, 0.1, 1e-12);
  }
}

TEST(RunLoop, StopsAtTheFirstDivergence) {
  // Explicit Euler on an undamped stiff contact gains energy every bounce.
  Scene scene = default_scene(Shape::PointMass);
  scene.contact.k = 1e6;
  scene.contact.c = 0.0;
  scene.sim.integrator = Integrator::ExplicitEuler;
  scene.sim.dt = 2e-3;  // ω·Δt = 2
  scene.sim.duration = 5.0;
  const Trajectory t = simulate(scene);
  ASSERT_TRUE(t.divergence);
  EXPECT_LT(t.samples.back().t, t.divergence->time);
}

// An engine that reports bad numbers itself (as MuJoCo does) stops the run
// as non-finite, with the time of the step.
class FailingStepper final : public Stepper {
 public:
  explicit FailingStepper(const Scene& scene) : model_(make_model(scene)), contacts_(model_) {}
  void reset(const State& s) override { state_ = s; }
  void set_applied(const Vec3&) override {}
  StepStatus step() override { return ++steps_ == 3 ? StepStatus::NonFinite : StepStatus::Ok; }
  const State& state() const override { return state_; }
  const ContactSet& contacts() const override { return contacts_; }
  const Model& model() const override { return model_; }
  StepStability stability() const override { return {}; }
  std::string describe() const override { return "failing"; }

 private:
  Model model_;
  ContactSet contacts_;
  State state_;
  int steps_ = 0;
};

TEST(RunLoop, EngineFailureStopsTheRunAsNonFinite) {
  Scene scene = default_scene(Shape::PointMass);
  scene.initial.q = Vec3(0.0, 1.0, 0.0);
  scene.sim.dt = 1e-3;
  scene.sim.output_dt = 1e-3;
  FailingStepper stepper(scene);
  const Trajectory t = simulate(stepper, scene.sim);
  ASSERT_TRUE(t.divergence);
  EXPECT_EQ(t.divergence->kind, DivergenceKind::NonFinite);
  EXPECT_NEAR(t.divergence->time, 3e-3, 1e-15);
  EXPECT_EQ(t.samples.size(), 3u);  // t = 0, 1, 2 ms
}

// The energy balance of the run loop (core/divergence.hpp): a passive system
// only loses energy, so a rise is the integrator's. Its tolerance is
// E_avail·(2·(ω·Δt/2)/(1 − ω·Δt/2) + 1e-9), the semi-implicit Euler
// oscillation bound doubled (a rise is measured from an earlier minimum).
Scene bouncing_t_scene(Integrator integrator) {
  Scene scene = default_scene(Shape::TShape);
  scene.contact.c = 0.0;
  scene.contact.mu = 0.0;
  scene.initial.q = Vec3(0.0, 0.5, 0.4);
  scene.initial.v = Vec3(0.0, 0.0, 3.0);
  scene.sim.integrator = integrator;
  scene.sim.duration = 10.0;
  return scene;
}

TEST(EnergyBalance, ToleranceIsTheSemiImplicitOscillationBound) {
  const Scene scene = bouncing_t_scene(Integrator::SemiImplicitEuler);
  const Trajectory t = simulate(scene);
  const Model model = make_model(scene);
  const double wdt = contact_stiffness(model).omega * scene.sim.dt;
  EXPECT_NEAR(t.energy.tolerance,
              t.available_energy * (2.0 * (0.5 * wdt) / (1.0 - 0.5 * wdt) + 1e-9),
              1e-12 * t.available_energy);
}

// A T bouncing without damping or friction for 10 s (the case that used to
// pass silently): semi-implicit Euler's energy oscillates within the bound,
// explicit Euler's grows past it without reaching the divergence rule.
TEST(EnergyBalance, SemiImplicitStaysWithinExplicitEulerIsFlagged) {
  const Trajectory semi = simulate(bouncing_t_scene(Integrator::SemiImplicitEuler));
  ASSERT_FALSE(semi.divergence);
  EXPECT_GT(semi.energy.max_rise, 0.0) << "the bounce must exercise the oscillation";
  EXPECT_FALSE(semi.energy.exceeded())
      << semi.energy.max_rise << " J against " << semi.energy.tolerance << " J";

  const Trajectory expl = simulate(bouncing_t_scene(Integrator::ExplicitEuler));
  ASSERT_FALSE(expl.divergence) << "below the divergence rule: the rise is the warning's to catch";
  EXPECT_TRUE(expl.energy.exceeded())
      << expl.energy.max_rise << " J against " << expl.energy.tolerance << " J";
  EXPECT_GT(expl.energy.final, expl.energy.initial) << "explicit Euler gains energy";
}

// A body that never touches anything, under explicit Euler: 200 steps of
// Δt = 0.01 s from 100 m. Each step raises E = ½·m·v² + m·g·y by exactly
// ½·m·g²·Δt² (core/divergence.hpp), so the largest rise is 200 times that,
// and the allowance holds it. The tolerance is rounding: E ≈ 1e6 J is
// computed to |E|·2⁻⁵² ≈ 2e-10 J a step, and y ≈ 100 m carries ulp(y)·m·g ≈
// 1.4e-10 J per step over 200 steps, under 1e-7 J in all.
Scene free_flight_scene(Integrator integrator) {
  Scene scene = default_scene(Shape::PointMass);
  scene.mass = 1e3;
  scene.contact.k = 1.0;
  scene.initial.q = Vec3(0.0, 100.0, 0.0);
  scene.initial.v = Vec3::Zero();
  scene.sim.dt = 0.01;
  scene.sim.duration = 2.0;
  scene.sim.integrator = integrator;
  return scene;
}

TEST(EnergyBalance, ExplicitEulerGainsHalfMG2Dt2EveryStepInFreeFlight) {
  const Scene scene = free_flight_scene(Integrator::ExplicitEuler);
  const Trajectory t = simulate(scene);
  ASSERT_FALSE(t.divergence);
  const double per_step = 0.5 * scene.mass * 9.81 * 9.81 * scene.sim.dt * scene.sim.dt;
  EXPECT_NEAR(t.energy.max_rise, 200 * per_step, 1e-7);
  // The same product in another order: a few ulps of 962 J (1.1e-13 J each).
  EXPECT_NEAR(t.energy.free_flight_gain, 200 * per_step, 1e-12);
  EXPECT_FALSE(t.energy.rise_in_contact);
  EXPECT_FALSE(t.energy.exceeded())
      << t.energy.max_rise << " J against " << t.energy.tolerance << " J";
  for (Integrator other :
       {Integrator::SemiImplicitEuler, Integrator::ImplicitEuler, Integrator::RK4}) {
    const Trajectory o = simulate(free_flight_scene(other));
    EXPECT_EQ(o.energy.free_flight_gain, 0.0) << integrator_name(other);
    EXPECT_FALSE(o.energy.exceeded()) << integrator_name(other) << ": " << o.energy.max_rise;
  }
}

// Should such a rise exceed the allowance, the message names free flight,
// not contact: nothing touched.
TEST(EnergyBalance, AFreeFlightRiseIsBlamedOnFreeFlight) {
  const Scene scene = free_flight_scene(Integrator::ExplicitEuler);
  const Trajectory t = simulate(scene);
  EnergyBalance b = t.energy;
  b.tolerance = 0.0;
  const std::string text = describe_energy_rise(b, t.available_energy, scene);
  EXPECT_NE(text.find("explicit Euler gains ½·m·g²·Δt² = 4.81 J on every step in free flight"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("in contact"), std::string::npos) << text;
}

// One undamped bounce of the point mass under explicit Euler (k = 1e4 N/m,
// Δt = 1e-4 s: ω·Δt = 0.01): every step in contact multiplies the energy by
// 1 + (ω·Δt)², and the bounce gains what the allowance's growth term,
// (1 + (ω·Δt)²)^(π/(ω·Δt)) − 1 = 3.19 % of E_avail, says, a little less: the
// contact is shorter than π/ω by 2·asin(d_eq/A)/ω, 1.4 % of it (gravity's
// static depth d_eq = m·g/k = 0.98 mm against the amplitude A = v/ω = 44 mm),
// and loses part of a step at each end (0.6 %); measured 2.5 % less. Without
// the term the rise (0.32 J) is three times the oscillation bound (0.104 J).
TEST(EnergyBalance, OneUndampedBounceUnderExplicitEulerGainsItsErrorTerm) {
  Scene scene = default_scene(Shape::PointMass);
  scene.contact.k = 1e4;
  scene.contact.c = 0.0;
  scene.contact.mu = 0.0;
  scene.initial.q = Vec3(0.0, 1.05, 0.0);
  scene.initial.v = Vec3::Zero();
  scene.sim.dt = 1e-4;
  scene.sim.duration = 0.5;  // lands at 0.45 s, leaves 31 ms later
  scene.sim.integrator = Integrator::ExplicitEuler;
  const Trajectory t = simulate(scene);
  ASSERT_FALSE(t.divergence);
  const double wdt = 0.01;
  const double growth = std::pow(1.0 + wdt * wdt, test::kPi / wdt) - 1.0;
  EXPECT_LE(t.energy.max_rise, t.available_energy * growth);
  EXPECT_GE(t.energy.max_rise, 0.95 * t.available_energy * growth);
  EXPECT_TRUE(t.energy.rise_in_contact);
  EXPECT_FALSE(t.energy.exceeded())
      << t.energy.max_rise << " J against " << t.energy.tolerance << " J";
}

}  // namespace
}  // namespace contact2d
