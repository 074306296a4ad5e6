// The two engines on the same scenes (Kelvin–Voigt law, dt = 1e-4,
// semi-implicit Euler in both, calibrated mapping unless stated).
//
// Frictionless, ζ = c/(2√(k·m)) ∈ {0.1, 0.3, 1, 5} for every body (m the
// total mass, 1 kg; a corner of the box or T presents the smaller effective
// mass 1/A, so its own ratio c/(2√(k/A)) = ζ·√(m·A) is up to 2.05× larger).
// With impedance d = 1e-4 MuJoCo's normal force is
//   f = (k·Â·p − c·Â·v + d·g_n)/(d·A + (1 − d)·Â)
// (mujoco/mapping.hpp), i.e. the Kelvin–Voigt force with a relative error
// of order eta = d·A/Â, where A = 1/m + r_x²/I is the contact's true inverse
// mass and Â = 2/(3m) MuJoCo's estimate: at most 1.5e-4 for the point mass
// and circle (A = 1/m), 6e-4 for the box (r²/I ≤ 3/m) and 6.3e-4 for the T.
//
// ζ ≥ 1: the body lands once or twice and settles; the force error moves it
// by micrometres. The tolerance is a requirement, the agreement goal
// (1e-5 m, 1e-4 rad). Measured (max position m / angle rad):
//   ζ = 1   point mass 1.8e-6 / 0,  box 5.9e-7 / 1.0e-5,
//           T 7.8e-7 / 1.6e-6,      disc 4.8e-7 / 6e-12
//   ζ = 5   point mass 2.0e-7 / 0,  box 3.2e-7 / 1.1e-6,
//           T 1.4e-7 / 4.8e-7,      disc 1.3e-7 / 3e-11
// i.e. 5.5× (point mass, ζ = 1) to 77× below the position goal and ≥ 10×
// below the angle goal.
//
// ζ < 1 (calibrated; the compensated mapping removes this error, see
// test_compensated.cpp): the goal does not hold (ζ = 0.3: 1.4e-5 to 5.1e-5 m, the box
// 1.1e-4 rad; ζ = 0.1: 4.3e-5 to 1.3e-3 m). The tolerance is then a bound
// derived from the force error (force_error_bound below): each impact's
// contact impulse J is off by at most eta·J, so the rebound velocity by
// eta·J/m (a relative restitution error eta), kept by later reflections
// (restitution ≤ 1) and integrated over the flights that follow: a bounce's
// apex error ~ eta × (1 + e)·v·(2v/g) ~ eta × apex height, accumulating
// over the bounces; resting contact at the end adds eta × its depth.
// Underdamped bodies bounce more and higher, so the bound grows as ζ falls:
// point mass 6e-7 m (ζ = 5, at rest after one impact) to 2.8e-3 m
// (ζ = 0.1, three bounces). Measured / bound (position, angle):
//   ζ = 0.3 point mass 5.1e-5 / 2.2e-3 m,  box 2.1e-5 / 5.4e-3 m and
//           1.1e-4 / 4.4e-2 rad,  T 3.2e-5 / 7.6e-3 m and 9.8e-5 / 1.6e-2 rad,
//           disc 1.4e-5 / 1.7e-3 m
//   ζ = 0.1 point mass 8.2e-4 / 2.8e-3 m,  box 3.0e-4 / 9.8e-3 m and
//           2.6e-3 / 7.9e-2 rad,  T 1.3e-3 / 1.2e-2 m and 6.2e-3 / 2.4e-2 rad,
//           disc 4.3e-5 / 2.9e-3 m
// (a body without rotation, point mass and disc, keeps the 1e-4 rad goal
// for its angle: no torque acts in either engine). The tightest case is the
// point mass at ζ = 0.1, 3.4× below its bound (then the T's angle at
// ζ = 0.1, 3.9×); the others are 9–390× below. The bound is first order and
// counts every impulse at its full size, which is why it is loose; what it
// does not model is how the difference grows from bounce to bounce,
// measured for the point mass at ζ = 0.1: the vertical velocity difference
// after its three impacts is 3.3e-5, 1.7e-4 and 2.6e-3 m/s (relative 1e-5,
// 7e-5, 1.4e-3). The first is the force error itself (a relative force
// error eta' = d·(A/Â − 1) = 5e-5 changes ζ by eta'/2 and the restitution
// by ~0.16·eta' = 8e-6 at ζ = 0.1); the growth is the time step's: the
// discrete restitution depends on where inside a step the contact begins
// (the reference alone, its drop raised by 0.1·v·Δt at a time, gives a
// sawtooth in the first apex of 3.4e-3 relative, i.e. 1.7e-3 in the rebound
// speed, per step of phase), and a position difference δy at the next
// impact shifts that phase by δy/(v·Δt), so each bounce multiplies the
// difference (×5, ×15 here) until it is bounded by that sawtooth. A longer
// or less damped run than these would need eta + 1.7e-3 per impact in the
// bound. These numbers are why the report's random scenes are split by ζ
// (README.md section 6).
//
// With friction the tolerances are REGRESSION PINS, not derived bounds:
// MuJoCo's law differs in kind (mapping.hpp), and these landings are
// chaotic (a tilted body lands on a corner and rocks), so no closed form
// predicts the difference; what the pins guard is that it does not grow.
// Why MuJoCo differs by millimetres: (1) on its friction cone the damper's
// slip term μ·c·|v_t| adds to the normal force, so a body that lands or
// slides gets extra normal impulse and hops off the ground, which the 2D
// law (Fn from depth and normal speed only) never does; after a hop the
// two bodies land at different times and places and the difference is
// carried forward; (2) MuJoCo puts the contact point midway between the
// surfaces, p/2 above the 2D point (p = m·g/k = 1e-3 m at rest), which
// changes the friction's lever arm and, for the disc, the rolling radius to
// R − p/2; (3) for the disc the elliptic cone shares one friction budget
// between sliding and rolling (see RollingStop in test_contact_laws.cpp).
// The point mass differs least (it cannot rock, so nothing amplifies the
// difference): its tolerance is the agreement goal, 1e-3 m, a requirement
// (measured 2.3e-4 m at c = 200 and 1.8e-5 m at c = 1000, 4× and 50×
// below it).
// Pins: measured maxima (c = 200, c = 1000) box 4.04e-3 and 4.83e-3 m, T
// 3.02e-3 and 3.15e-3 m, circle 5.44e-3 and 2.93e-3 m; pin = 1.25 × the
// larger value rounded up to one significant digit (the 25 % covers
// rounding differences between builds, which the chaotic landings amplify):
// box 7e-3 m, T 4e-3 m, circle 7e-3 m. Each run prints its value; if a pin
// fails, the change in the engine or the mapping must be explained before
// the pin moves. The agreement goal is 3e-3 m (box, T) and 1e-3 m (circle): not
// reached; see validation/report/README.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "mj_test_util.hpp"

namespace contact2d {
namespace {

using mujoco::Mapping;

constexpr double kFrictionlessPosition = 1e-5;  // m
constexpr double kFrictionlessAngle = 1e-4;     // rad

struct DropCase {
  Shape shape;
  double c;
};

void PrintTo(const DropCase& d, std::ostream* os) { *os << shape_name(d.shape) << ", c = " << d.c; }

std::string drop_name(const ::testing::TestParamInfo<DropCase>& info) {
  return std::string(shape_name(info.param.shape)) + "_c" +
         std::to_string(static_cast<int>(info.param.c));
}

std::vector<DropCase> drop_cases() {
  std::vector<DropCase> out;
  for (double c : {200.0, 1000.0}) {
    for (Shape s : {Shape::PointMass, Shape::Box, Shape::TShape, Shape::Circle})
      out.push_back({s, c});
  }
  return out;
}

// ζ of a drop: c/(2√(k·m)) with m the body's total mass (1 kg for all four,
// the T's two parts included), so c = 2ζ·√(1e4·1) = 200·ζ: ζ = 1 and 5 are
// the c = 200 and 1000 of the friction cases below.
struct DampingCase {
  Shape shape;
  double zeta;
};

void PrintTo(const DampingCase& d, std::ostream* os) {
  *os << shape_name(d.shape) << ", zeta = " << d.zeta;
}

std::string damping_name(const ::testing::TestParamInfo<DampingCase>& info) {
  const int tenths = static_cast<int>(std::lround(info.param.zeta * 10));
  return std::string(shape_name(info.param.shape)) + "_zeta" + std::to_string(tenths / 10) + "_" +
         std::to_string(tenths % 10);
}

std::vector<DampingCase> damping_cases() {
  std::vector<DampingCase> out;
  for (double zeta : {0.1, 0.3, 1.0, 5.0}) {
    for (Shape s : {Shape::PointMass, Shape::Box, Shape::TShape, Shape::Circle})
      out.push_back({s, zeta});
  }
  return out;
}

Scene damping_scene(const DampingCase& d) {
  return test::drop_scene(d.shape, 2 * d.zeta * std::sqrt(1e4 * 1.0), 0.0);
}

// The derived bound of the header comment: every impact's contact impulse
// (per sample interval, the velocity change less gravity's) off by at most
// eta of itself, the velocity error so made kept to the end (a later
// reflection scales it by the restitution, at most 1) and integrated over
// the flights. Contact that lasts to the end of the run is rest: a force
// error there only moves the resting depth, by eta of the deepest
// penetration.
struct ForceErrorBound {
  double pos = 0.0;    // m
  double angle = 0.0;  // rad
};

ForceErrorBound force_error_bound(const Model& model, const Trajectory& ref, double eta) {
  ForceErrorBound out;
  const auto& samples = ref.samples;
  size_t rest = samples.size();  // first sample of the final, resting contact
  while (rest > 0 && max_penetration(model, samples[rest - 1].state.q) > 0.0) --rest;
  double dv = 0.0;
  double dw = 0.0;
  double deepest = 0.0;
  for (size_t i = 1; i < samples.size(); ++i) {
    const double h = samples[i].t - samples[i - 1].t;
    const State& a = samples[i - 1].state;
    const State& b = samples[i].state;
    deepest = std::max(deepest, max_penetration(model, b.q));
    if (i < rest) {
      dv += eta * std::hypot(b.v.x() - a.v.x(), b.v.y() - a.v.y() + model.gravity * h);
      dw += eta * std::abs(b.v.z() - a.v.z());
    }
    out.pos += dv * h;
    out.angle += dw * h;
  }
  out.pos += eta * deepest;
  return out;
}

class FrictionlessDrop : public ::testing::TestWithParam<DampingCase> {};

TEST_P(FrictionlessDrop, AgreesWithinTheGoalOrTheForceErrorBound) {
  const DampingCase d = GetParam();
  const Scene scene = damping_scene(d);
  const Model model = make_model(scene);
  const test::BothRuns runs = test::run_both(scene);
  // eta = d·A/Â: A the largest inverse mass a contact point presents
  // (1/m + r²/I), Â MuJoCo's body_invweight0 as the generator read it.
  const double eta =
      mujoco::kMinimalSolimp[0] / (min_effective_mass(model.body) * runs.mj.settings.inv_mass);
  const ForceErrorBound bound = force_error_bound(model, runs.ref, eta);
  const bool goal = d.zeta >= 1.0;
  // Without rotation (point mass; the disc, whose contact normal passes
  // through its centre) no torque acts in either engine: the goal holds.
  const double pos_tolerance = goal ? kFrictionlessPosition : bound.pos;
  const double angle_tolerance = goal || bound.angle == 0.0 ? kFrictionlessAngle : bound.angle;
  std::printf(
      "frictionless %s, zeta = %g (c = %g): max position difference %.3g m (tolerance %.3g, %s), "
      "angle %.3g rad (tolerance %.3g); force-error bound %.3g m, %.3g rad (eta = %.2g)\n",
      std::string(shape_name(d.shape)).c_str(), d.zeta, scene.contact.c, runs.errors.max_pos,
      pos_tolerance, goal ? "goal" : "bound", runs.errors.max_angle, angle_tolerance, bound.pos,
      bound.angle, eta);
  EXPECT_EQ(runs.errors.samples, 2001);
  EXPECT_LT(runs.errors.max_pos, pos_tolerance);
  EXPECT_LT(runs.errors.max_angle, angle_tolerance);
  // The body really landed: the test is about contact (m·g/k = 1e-3 m).
  double deepest = 0.0;
  for (const Sample& s : runs.ref.samples)
    deepest = std::max(deepest, max_penetration(model, s.state.q));
  EXPECT_GT(deepest, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(AllBodies, FrictionlessDrop, ::testing::ValuesIn(damping_cases()),
                         damping_name);

// The report's claim (README.md section 6): the difference grows as ζ
// falls. Measured ratios of the ζ = 0.1 to the ζ = 1 difference: 450
// (point mass), 510 (box), 1650 (T), 90 (disc); asserted > 10.
TEST(FrictionlessDropAcrossDamping, DifferenceGrowsAsZetaFalls) {
  for (Shape s : {Shape::PointMass, Shape::Box, Shape::TShape, Shape::Circle}) {
    const double low = test::run_both(damping_scene({s, 0.1})).errors.max_pos;
    const double critical = test::run_both(damping_scene({s, 1.0})).errors.max_pos;
    EXPECT_GT(low, 10 * critical) << shape_name(s);
  }
}

// The point mass's requirement and the regression pins above.
double friction_tolerance(Shape shape) {
  switch (shape) {
    case Shape::PointMass: return 1e-3;
    case Shape::Box: return 7e-3;
    case Shape::TShape: return 4e-3;
    case Shape::Circle: return 7e-3;
    case Shape::Ellipse: return 7e-3;
  }
  return 0.0;
}

class FrictionDrop : public ::testing::TestWithParam<DropCase> {};

TEST_P(FrictionDrop, AgreesWithinTheMeasuredFrictionDifference) {
  const auto [shape, c] = GetParam();
  const Scene scene = test::drop_scene(shape, c, 0.5);
  const test::BothRuns runs = test::run_both(scene);
  std::printf("friction %s, c = %g: max position difference %.3g m (pin %.3g m)\n",
              std::string(shape_name(shape)).c_str(), c, runs.errors.max_pos,
              friction_tolerance(shape));
  EXPECT_LT(runs.errors.max_pos, friction_tolerance(shape));
  // Friction acted: the body ends far from where it would without it.
  const Trajectory frictionless = simulate(test::drop_scene(shape, c, 0.0));
  const double shift =
      std::abs(frictionless.samples.back().state.q.x() - runs.ref.samples.back().state.q.x());
  EXPECT_GT(shift, 10 * friction_tolerance(shape));
}

INSTANTIATE_TEST_SUITE_P(AllBodies, FrictionDrop, ::testing::ValuesIn(drop_cases()), drop_name);

// The seed mapping's timeconst = √(m/k) reproduces k/m and c/m only at ζ = 1
// (mapping.hpp): at ζ = 0.1 it is 100× too stiff, at ζ = 5 25× too soft.
// The point mass's drop then differs from the reference by centimetres,
// against micrometres (ζ = 5) and under a millimetre (ζ = 0.1, a long
// bouncing run) for calibrated. Asserted: seed is at least 10× worse and
// off by more than a millimetre, far outside anything rounding could do.
TEST(SeedMapping, IsMeasurablyWorseWhenZetaIsNotOne) {
  for (double c : {20.0, 1000.0}) {  // ζ = c/(2√(m·k)) = 0.1 and 5
    const Scene scene = test::drop_scene(Shape::PointMass, c, 0.0);
    const double seed = test::run_both(scene, Mapping::Seed).errors.max_pos;
    const double calibrated = test::run_both(scene, Mapping::Calibrated).errors.max_pos;
    EXPECT_GT(seed, 1e-3) << "c = " << c;
    EXPECT_GT(seed, 10 * calibrated) << "c = " << c;
  }
}

}  // namespace
}  // namespace contact2d
