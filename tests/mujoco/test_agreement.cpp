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
// measured maxima below are 0.2–1.9 µm and 0.002–10 µrad. The tolerance is
// the goal of issue 3 (1e-5 m, 1e-4 rad), 5–10× above what is measured.
//
// With friction MuJoCo's law differs in kind (mapping.hpp): on the cone the
// damper's slip term μ·c·|v_t| adds to the normal force, so a body that
// lands or slides hops off the ground, and MuJoCo puts the contact point
// midway between the surfaces, p/2 above the 2D point, so a rolling disc
// rolls on R − p/2. Measured maxima (c = 200, c = 1000): point mass 2.3e-4
// and 1.8e-5 m, box 4.0e-3 and 4.8e-3 m, T 3.0e-3 and 3.2e-3 m, circle
// 5.4e-3 and 2.9e-3 m. Tolerance: issue 3's goal where it is met (point
// mass, 1e-3 m); elsewhere 1.25 × the larger measured value rounded up to
// one significant digit, an allowance for rounding differences between
// builds, which these chaotic landings amplify: box 7e-3 m, T 4e-3 m,
// circle 7e-3 m. Issue 3 asks for 3e-3 m (box, T) and 1e-3 m (circle):
// not reached; see validation/report/README.md.
#include <algorithm>
#include <cmath>

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
