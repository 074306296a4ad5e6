// MuJoCo alone against closed forms: the static penetration under the
// calibrated mapping and the rolling circle's stop distance.
#include <cmath>
#include <cstdio>

#include "benchmarks/rolling.hpp"
#include "mj_test_util.hpp"

namespace contact2d {
namespace {

// Penetration of the lowest contact point at the end of a run.
double final_penetration(const Scene& scene, const Trajectory& t) {
  return max_penetration(make_model(scene), t.samples.back().state.q);
}

// At rest the solver's contact force equals the load F on the contact and
// MuJoCo's soft constraint gives (1 − d)·F = k·p_mj (mujoco/mapping.hpp: the
// regulariser R = (1−d)/d·Â balances d·aref with aref = k·Â·p_mj/d), so
// p_mj = (1 − d)·F/k with d = 1e-4: 1e-4 below F/k, whatever m, k and the
// number of contacts. A corner sphere of radius ε touches ε before its 2D
// corner does (p_mj = p + ε), so a box's corners sink ε less. Asserted:
// p = (1 − d)·F/k − ε to within 1e-12·F/k, and |p − F/k| ≤ 1.1e-4·F/k.
// The first tolerance is rounding: after 2 s the contact's transient
// (decay time 2m/c = 0.01 s) has fallen by e^(−200), and MuJoCo's Newton
// solver on one or two contacts at rest converges to rounding (its
// termination tolerance, 1e-8 on the relative improvement of its cost, is
// not what stops it here: measured residuals are 2.7e-15, 1.1e-14 and
// 1.6e-15 of F/k, printed). What remains is p = R − y (or h − y) rounded:
// ulp(y) ≤ 1.4e-17 m at y ≤ 0.1 m, ≤ 6e-14 of the smallest F/k here
// (2.3e-4 m). 1e-12 is 16× that bound and 90× the largest measured value;
// the d = 1e-4 it checks is 1e8× larger. (It was 1e-6 before, an allowance
// for the solver's tolerance that the measurements show is not needed.)
// The second: the d = 1e-4 shift, plus the box's ε/(F/k) = 2e-6, rounded
// up.
void expect_static_penetration(const std::string& toml, double load_per_contact, double k,
                               double sphere_offset) {
  const Scene scene = test::scene_from(toml);
  const test::MujocoRun run = test::run_mujoco(scene, {});
  ASSERT_FALSE(run.trajectory.divergence.has_value());
  const double p = final_penetration(scene, run.trajectory);
  const double nominal = load_per_contact / k;
  const double expected = (1.0 - 1e-4) * nominal - sphere_offset;
  std::printf("static penetration: p = %.9g m, (1 - d)·F/k − ε = %.9g m, residual %.3g of F/k\n", p,
              expected, (p - expected) / nominal);
  EXPECT_NEAR(p, expected, 1e-12 * nominal) << "p = " << p << " m, F/k = " << nominal << " m";
  EXPECT_NEAR(p, nominal, 1.1e-4 * nominal);
}

TEST(StaticPenetration, CircleIsMgOverK) {
  expect_static_penetration(
      "scene = \"circle\"\n[body]\nmass = 1.0\nradius = 0.1\n[contact]\nk = 1e4\nc = 200\nmu = "
      "0.5\n"
      "damping = \"kelvin_voigt\"\n[initial]\ny = 0.1\n[sim]\ndt = 1e-4\nduration = 2\n",
      1.0 * 9.81, 1e4, 0.0);
}

TEST(StaticPenetration, HeavyStiffPointMassIsMgOverK) {
  expect_static_penetration(
      "scene = \"point_mass\"\n[body]\nmass = 7.0\nhalf_height = 0.05\n[contact]\nk = 3e5\nc = "
      "3000\n"
      "damping = \"kelvin_voigt\"\n[initial]\ny = 0.05\n[sim]\ndt = 1e-4\nduration = 2\n",
      7.0 * 9.81, 3e5, 0.0);
}

// A box lying flat rests on two 2D corners (two corner spheres), m·g/2 each.
TEST(StaticPenetration, FlatBoxCarriesHalfTheWeightOnEachCorner) {
  expect_static_penetration(
      "scene = \"box\"\n[body]\nmass = 2.0\nwidth = 0.4\nheight = 0.2\n[contact]\nk = 2e4\nc = "
      "400\nmu = 0.5\n"
      "damping = \"kelvin_voigt\"\n[initial]\ny = 0.1\n[sim]\ndt = 1e-4\nduration = 2\n",
      0.5 * 2.0 * 9.81, 2e4, mujoco::kCornerRadius);
}

// Rolling without slipping under a constant resisting torque μ_roll·m·g,
// a disc (I = m·R²/2) decelerates at a = μ_roll·g/(1.5·R) and stops after
// v0²/(2a). MuJoCo's circle stops later: by +1.73 % (3.111 m against
// 3.058 m) and +1.50 % (1.746 m against 1.720 m) for the second case,
// measured. The upper limit is a REGRESSION PIN, not a derived bound: its
// elliptic cone shares one friction budget between sliding and rolling, so
// while rolling resistance is at its limit the disc slips forward (about
// 2 % of v, measured), which lengthens the stop by about that fraction; no
// closed form of MuJoCo's cone solution is derived here. The other known
// difference, the contact point p/2 above the 2D one (rolling radius
// R − p/2), is derived and small: it shortens the stop by p/(6R) (0.16 % at
// p = 1e-3 m, R = 0.1 m), so it cannot explain the excess. Pin: 2.5 %, the
// larger measured excess with a 1.5× allowance for rounding between
// builds; the test also requires the excess to be positive, the direction
// the slip explains, so a MuJoCo that stopped short would fail.
struct RollCase {
  double mass, radius, mu_roll, v0;
};

void PrintTo(const RollCase& r, std::ostream* os) {
  *os << "m = " << r.mass << ", R = " << r.radius << ", mu_roll = " << r.mu_roll
      << ", v0 = " << r.v0;
}

class RollingStop : public ::testing::TestWithParam<RollCase> {};

TEST_P(RollingStop, StopsNearTheAnalyticDistance) {
  const RollCase rc = GetParam();
  const double k = 1e4, g = 9.81;
  const double rest = rc.radius - rc.mass * g / k;
  char toml[1024];
  std::snprintf(toml, sizeof toml,
                "scene = \"circle\"\n[body]\nmass = %.17g\nradius = %.17g\n[contact]\nk = 1e4\nc = "
                "200\nmu = 0.5\n"
                "mu_roll = %.17g\ndamping = \"kelvin_voigt\"\n[initial]\ny = %.17g\nvx = "
                "%.17g\nomega = %.17g\n"
                "[sim]\ndt = 1e-4\nduration = 6\n",
                rc.mass, rc.radius, rc.mu_roll, rest, rc.v0, -rc.v0 / rc.radius);
  const Scene scene = test::scene_from(toml);
  const test::MujocoRun run = test::run_mujoco(scene, {});
  ASSERT_FALSE(run.trajectory.divergence.has_value());
  const State& end = run.trajectory.samples.back().state;
  EXPECT_LT(std::abs(end.v.x()), 1e-3);  // it has stopped
  const double analytic = benchmarks::rolling_resistance_distance(
      rc.v0, benchmarks::rolling_resistance_deceleration(rc.mu_roll, g, rc.radius,
                                                         benchmarks::kDiscInertiaRatio));
  const double excess = end.q.x() / analytic - 1.0;
  std::printf(
      "MuJoCo disc m = %g, R = %g, mu_roll = %g, v0 = %g: stops at %.6f m, analytic %.6f m, "
      "excess %.4g\n",
      rc.mass, rc.radius, rc.mu_roll, rc.v0, end.q.x(), analytic, excess);
  EXPECT_GT(excess, 0.0) << "stopped at " << end.q.x() << " m, analytic " << analytic << " m";
  EXPECT_LT(excess, 0.025) << "stopped at " << end.q.x() << " m, analytic " << analytic << " m";
}

INSTANTIATE_TEST_SUITE_P(Discs, RollingStop,
                         ::testing::Values(RollCase{1.0, 0.1, 0.01, 2.0},
                                           RollCase{3.0, 0.2, 0.02, 1.5}));

}  // namespace
}  // namespace contact2d
