// The two engines on the same scenes (Kelvin–Voigt law, dt = 1e-4,
// semi-implicit Euler in both, calibrated mapping unless stated).
//
// Frictionless. With impedance d = 1e-4 MuJoCo's normal force is
//   f = (k·Â·p − c·Â·v + d·g_n)/(d·A + (1 − d)·Â)
// (mujoco/mapping.hpp), i.e. the Kelvin–Voigt force with a relative error
// of order d·A/Â, where A = 1/m + r_x²/I is the contact's true inverse mass
// and Â = 2/(3m) MuJoCo's estimate: at most 1.5e-4 for the point mass and
// circle (A = 1/m) and 6e-4 for the box (r²/I ≤ 3/m). Over an impact whose
// depth is a few centimetres this moves the body by micrometres; the
// measured maxima (printed) are 0.13–1.8 µm and 3e-5–10 µrad. The
// tolerance is a requirement, the goal of issue 3 (1e-5 m, 1e-4 rad): 5.5×
// above the largest measured position difference and 10× above the largest
// angle (the d·A/Â estimate above, a relative force error ≤ 6e-4 over
// centimetre-deep impacts, allows up to ~1e-5 m, so the goal is not
// loose against the physics).
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
// difference): its tolerance is issue 3's goal, 1e-3 m, a requirement
// (measured 2.3e-4 m at c = 200 and 1.8e-5 m at c = 1000, 4× and 50×
// below it).
// Pins: measured maxima (c = 200, c = 1000) box 4.04e-3 and 4.83e-3 m, T
// 3.02e-3 and 3.15e-3 m, circle 5.44e-3 and 2.93e-3 m; pin = 1.25 × the
// larger value rounded up to one significant digit (the 25 % covers
// rounding differences between builds, which the chaotic landings amplify):
// box 7e-3 m, T 4e-3 m, circle 7e-3 m. Each run prints its value; if a pin
// fails, the change in the engine or the mapping must be explained before
// the pin moves. Issue 3 asks for 3e-3 m (box, T) and 1e-3 m (circle): not
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

class FrictionlessDrop : public ::testing::TestWithParam<DropCase> {};

TEST_P(FrictionlessDrop, AgreesToMicrometres) {
  const auto [shape, c] = GetParam();
  const test::BothRuns runs = test::run_both(test::drop_scene(shape, c, 0.0));
  std::printf("frictionless %s, c = %g: max position difference %.3g m, angle %.3g rad\n",
              std::string(shape_name(shape)).c_str(), c, runs.errors.max_pos,
              runs.errors.max_angle);
  EXPECT_EQ(runs.errors.samples, 2001);
  EXPECT_LT(runs.errors.max_pos, kFrictionlessPosition);
  EXPECT_LT(runs.errors.max_angle, kFrictionlessAngle);
  // The body really landed: the test is about contact (m·g/k = 1e-3 m).
  const Model model = make_model(test::drop_scene(shape, c, 0.0));
  double deepest = 0.0;
  for (const Sample& s : runs.ref.samples)
    deepest = std::max(deepest, max_penetration(model, s.state.q));
  EXPECT_GT(deepest, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(AllBodies, FrictionlessDrop, ::testing::ValuesIn(drop_cases()), drop_name);

// The point mass's requirement and the regression pins above.
double friction_tolerance(Shape shape) {
  switch (shape) {
    case Shape::PointMass: return 1e-3;
    case Shape::Box: return 7e-3;
    case Shape::TShape: return 4e-3;
    case Shape::Circle: return 7e-3;
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

// The slides' timeconst = √(m/k) reproduces k/m and c/m only at ζ = 1
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
