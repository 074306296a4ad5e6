// MuJoCo alone against closed forms: the static penetration under the
// calibrated mapping and the rolling circle's stop distance.
#include <cmath>

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
// p = (1 − d)·F/k − ε to within 1e-6·F/k, the residual of a run that has
// settled for 2 s (the contact's decay time is 2m/c = 0.01 s) and of
// MuJoCo's solver tolerance (1e-8); and |p − F/k| ≤ 1.1e-4·F/k.
void expect_static_penetration(const std::string& toml, double load_per_contact, double k,
                               double sphere_offset) {
  const Scene scene = test::scene_from(toml);
  const test::MujocoRun run = test::run_mujoco(scene, {});
  ASSERT_FALSE(run.trajectory.divergence.has_value());
  const double p = final_penetration(scene, run.trajectory);
  const double nominal = load_per_contact / k;
  const double expected = (1.0 - 1e-4) * nominal - sphere_offset;
  EXPECT_NEAR(p, expected, 1e-6 * nominal) << "p = " << p << " m, F/k = " << nominal << " m";
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
// v0²/(2a). MuJoCo's circle stops later, by +1.7 % (3.111 m against 3.058 m)
// and +1.4 % for the second case, measured: its elliptic cone shares one
// friction budget between sliding and rolling, so while rolling resistance
// is at its limit the disc slips forward (2 % of v), and the contact point
// sits p/2 above the 2D one. Tolerance: 2.5 %, the measured excess with a
// 1.5× allowance; the test also requires the excess to be positive, which
// is the explained direction.
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
  const double analytic = rc.v0 * rc.v0 / (2.0 * rc.mu_roll * g / (1.5 * rc.radius));
  const double excess = end.q.x() / analytic - 1.0;
  EXPECT_GT(excess, 0.0) << "stopped at " << end.q.x() << " m, analytic " << analytic << " m";
  EXPECT_LT(excess, 0.025) << "stopped at " << end.q.x() << " m, analytic " << analytic << " m";
}

INSTANTIATE_TEST_SUITE_P(Discs, RollingStop,
                         ::testing::Values(RollCase{1.0, 0.1, 0.01, 2.0},
                                           RollCase{3.0, 0.2, 0.02, 1.5}));

}  // namespace
}  // namespace contact2d
