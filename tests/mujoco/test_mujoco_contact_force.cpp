// MuJoCo's contact force in closed form (docs/mujoco.md, "Checked against
// MuJoCo"), checked against MuJoCo 2.2.2 itself for impedance d from 1e-4 to
// 0.99, both solref forms, a contact in line with the COM (A = 1/m) and one
// at a lever (A = 1/m + r²/I, 4.5 Â), and MuJoCo's three solvers.
//
// For one frictionless contact row (condim 1) MuJoCo 2.2.2
// (engine_core_constraint.c) sets, with pos = efc_pos (the signed distance,
// negative in penetration), v = efc_vel = J·qvel (positive when separating):
//   aref = −B·v − K·d·pos           (mj_referenceConstraint)
//   R    = (1 − d)/d·Â, Â = efc_diagApprox = body_invweight0 (mj_diagApprox,
//          mj_makeImpedance; the ground contributes 0)
//   K = S/d_max², B = D/d_max  with (S, D) = (−solref[0], −solref[1]) direct,
//       (1/(tc²ζ²), 2/tc) standard (tc raised to 2Δt by refsafe)
// and the solver minimises ½‖qacc − qacc_smooth‖²_M + ½·(J·qacc − aref)²/R
// over the active row, whose minimiser gives
//   f = (aref − a0)/(A + R) = d·(−B·v − K·d·pos − a0)/(d·A + (1 − d)·Â)
// with A = J·M⁻¹·Jᵀ the contact's true inverse inertia and a0 = J·qacc_smooth
// (= −g here: gravity, no velocity product terms with ω = 0). The test
// computes A, Â and a0 from the model's numbers by hand (not from mjData),
// sets the state in qpos/qvel, calls mj_forward and compares efc_force.
#include <cmath>
#include <cstdio>

#include "benchmarks/soft_constraint.hpp"
#include "mj_test_util.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"

namespace contact2d {
namespace {

namespace mj = contact2d::mujoco;

constexpr double kMass = 2.0, kInertia = 0.01, kLever = 0.1, kG = 9.81, kDt = 0.002;
constexpr double kMachEps = 2.220446049250313e-16;  // double's machine epsilon
constexpr double kRho = 1e-3;                       // radius of the contact sphere
constexpr double kDrop = 0.05;                      // the sphere's centre is kDrop below the COM

struct ForceCase {
  double d;     // flat impedance (solimp d0 = dwidth = d)
  bool direct;  // solref (−S, −D) or (timeconst, dampratio)
  bool lever;   // the contact at r = 0.1 m from the COM, with a hinge
  int solver;   // mjSOL_NEWTON, mjSOL_PGS, mjSOL_CG
};

const char* solver_name(int solver) {
  return solver == mjSOL_NEWTON ? "Newton" : solver == mjSOL_PGS ? "PGS" : "CG";
}

void PrintTo(const ForceCase& c, std::ostream* os) {
  *os << "d = " << c.d << (c.direct ? ", direct" : ", standard")
      << (c.lever ? ", lever" : ", point") << ", " << solver_name(c.solver);
}

// The solref pairs: direct S = 5000 1/s², D = 50 1/s; standard tc = 0.02 s,
// ζ = 1 (S = 2500, D = 100; refsafe leaves tc alone: 0.02 > 2Δt = 0.004).
std::string solref(bool direct) { return direct ? "-5000 -50" : "0.02 1"; }
double gain_S(bool direct) { return direct ? 5000.0 : 1.0 / (0.02 * 0.02); }
double gain_D(bool direct) { return direct ? 50.0 : 2.0 / 0.02; }

std::string model_xml(const ForceCase& c) {
  const std::string d = mj::format_exact(c.d);
  const std::string solimp = d + " " + d + " 0.001 0.5 2";
  const std::string solver = c.solver == mjSOL_NEWTON ? "Newton"
                             : c.solver == mjSOL_PGS  ? "PGS"
                                                      : "CG";
  const std::string lever = c.lever ? mj::format_exact(kLever) : "0";
  return "<mujoco model=\"force\">\n"
         "  <option timestep=\"" +
         mj::format_exact(kDt) + "\" solver=\"" + solver +
         "\"/>\n"
         "  <default><geom condim=\"1\" solref=\"" +
         solref(c.direct) + "\" solimp=\"" + solimp +
         "\"/></default>\n"
         "  <worldbody>\n    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\"/>\n"
         "    <body name=\"b\" pos=\"0 0 0\">\n"
         "      <joint name=\"x\" type=\"slide\" axis=\"1 0 0\"/>\n"
         "      <joint name=\"z\" type=\"slide\" axis=\"0 0 1\"/>\n" +
         std::string(c.lever ? "      <joint name=\"theta\" type=\"hinge\" axis=\"0 -1 0\"/>\n"
                             : "") +
         "      <inertial pos=\"0 0 0\" mass=\"" + mj::format_exact(kMass) + "\" diaginertia=\"" +
         mj::format_exact(kInertia) + " " + mj::format_exact(kInertia) + " " +
         mj::format_exact(kInertia) +
         "\"/>\n"
         "      <geom name=\"contact\" type=\"sphere\" size=\"" +
         mj::format_exact(kRho) + "\" pos=\"" + lever + " 0 " + mj::format_exact(-kDrop) +
         "\"/>\n"
         "    </body>\n  </worldbody>\n</mujoco>\n";
}

struct Measured {
  double force, predicted;
  double pos, vel;
  double kappa;  // the rounding amplification (see EqualsTheClosedForm)
};

Measured measure(const ForceCase& c, double penetration, double velocity) {
  const mj::ModelPtr model = mj::load_model(model_xml(c), "force test model");
  const mj::DataPtr data = mj::make_data(model.get());
  // The sphere's lowest point at −penetration: COM height kDrop + ρ − p.
  data->qpos[1] = kDrop + kRho - penetration;
  data->qvel[1] = velocity;
  mj_forward(model.get(), data.get());
  EXPECT_EQ(data->ncon, 1);
  EXPECT_EQ(data->nefc, 1);
  // By hand: A = 1/m (+ r²/I: the normal row is J = (0, 1, r) in (x, z, θ),
  // since a point at horizontal offset r rises by r·dθ about the −y hinge),
  // Â = body_invweight0 = (1/m + 0 + 1/m)/3, a0 = −g.
  const double A = 1.0 / kMass + (c.lever ? kLever * kLever / kInertia : 0.0);
  const double Ahat = 2.0 / (3.0 * kMass);
  EXPECT_NEAR(model->body_invweight0[2], Ahat, 1e-15);
  const double a0 = -kG;
  const double d = c.d;
  const double K = gain_S(c.direct) / (d * d), B = gain_D(c.direct) / d;
  const double pos = data->efc_pos[0], vel = data->efc_vel[0];
  const double aref = -B * vel - K * d * pos, R = (1.0 - d) / d * Ahat;
  const double predicted = benchmarks::soft_constraint_force(A, Ahat, d, aref, a0);
  const double cancel = (std::abs(B * vel) + std::abs(K * d * pos) + std::abs(a0)) /
                        std::abs(aref - a0);  // the numerator's cancellation
  const double primal = std::max(std::abs(aref), std::abs(a0)) / std::abs(aref - a0) * (A + R) / R;
  return {data->efc_force[0], predicted, pos, vel, cancel + primal};
}

class MujocoContactForce : public ::testing::TestWithParam<ForceCase> {};

// The state: p = 1 mm, v = −0.1, 0 and +0.01 m/s (approaching, at rest,
// separating; all keep f > 0, the quadratic zone the closed form is for).
//
// Tolerance: rounding, 16·ε·κ relative (ε = 2.2e-16), with κ the case's
// amplification of rounding, computed per case and printed:
//   κ = (|B·v| + |K·d·pos| + |a0|)/|aref − a0|            the numerator's
//       cancellation, which the closed form and MuJoCo both suffer, plus
//     + max(|aref|, |a0|)/|aref − a0|·(A + R)/R           the primal solvers':
// Newton and CG find qacc and then f = (aref − J·qacc)/R; J·qacc lies
// between a0 and aref and carries a relative rounding ε, which 1/R turns
// into ε·max(|aref|, |a0|)/R against f = (aref − a0)/(A + R). At d = 0.99,
// R = 0.01·Â ≪ A and κ reaches 388 (the lever, standard form). The state is
// read back from MuJoCo (efc_pos, efc_vel, which equal −p and v to rounding,
// checked), so both sides evaluate the same numbers. Measured: error/(ε·κ)
// at most 2.7 (printed for every case), so 16 leaves a factor 6; the bound
// is at most 1.4e-12, and the smallest effect the closed form carries that
// a penalty law does not (d·A against (1 − d)·Â at d = 1e-4, 1.5e-4
// relative; the d·a0 term) is 8 orders larger.
// Convergence is not what limits it: one active row makes the problem a
// quadratic in qacc, which Newton solves in one step (exact line search on
// a quadratic), PGS in one sweep (a single row is solved exactly by its
// diagonal update: PGS, working on f directly, shows no 1/R amplification,
// ≤ 4.3e-16 measured) and CG in nv ≤ 3 steps; MuJoCo's tolerance (1e-8 on
// the scaled cost improvement, 100 iterations) is a stopping test these
// exact steps pass.
TEST_P(MujocoContactForce, EqualsTheClosedForm) {
  const ForceCase c = GetParam();
  for (double v : {-0.1, 0.0, 0.01}) {
    const Measured m = measure(c, 1e-3, v);
    const double error = (m.force - m.predicted) / m.predicted;
    const double bound = 16.0 * kMachEps * m.kappa;
    std::printf(
        "force check: d = %-6g %-8s %-5s %-6s v = %-5g: f = %.15g N, closed form %.15g N, "
        "relative error %.2e, kappa %.3g, error/(eps kappa) %.2f\n",
        c.d, c.direct ? "direct" : "standard", c.lever ? "lever" : "point", solver_name(c.solver),
        v, m.force, m.predicted, error, m.kappa, std::abs(error) / (kMachEps * m.kappa));
    EXPECT_NEAR(m.pos, -1e-3, 1e-15);
    EXPECT_NEAR(m.vel, v, 1e-15);
    EXPECT_GT(m.predicted, 0.0);
    EXPECT_NEAR(error, 0.0, bound) << "f = " << m.force << ", closed form " << m.predicted;
  }
}

std::vector<ForceCase> all_cases() {
  std::vector<ForceCase> cases;
  for (int solver : {mjSOL_NEWTON, mjSOL_PGS, mjSOL_CG})
    for (bool lever : {false, true})
      for (bool direct : {true, false})
        for (double d : {1e-4, 1e-3, 0.01, 0.1, 0.5, 0.9, 0.99})
          cases.push_back({d, direct, lever, solver});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(ImpedanceFrom1e4To099, MujocoContactForce,
                         ::testing::ValuesIn(all_cases()));

// The two things that make MuJoCo's force differ from a penalty law, each
// checked against MuJoCo so that the closed form above is not a tautology:
// (1) the true A enters: at d = 0.5 the force at the lever differs from the
// force in line with the COM by the ratio of (d·A + (1 − d)·Â);
// (2) the d·a0 term: with gravity off, f falls by d·g/(d·A + (1 − d)·Â).
TEST(MujocoContactForceTerms, TrueInverseInertiaAndGravityTerm) {
  const ForceCase point{0.5, true, false, mjSOL_NEWTON}, lever{0.5, true, true, mjSOL_NEWTON};
  const Measured fp = measure(point, 1e-3, 0.0), fl = measure(lever, 1e-3, 0.0);
  const double Ahat = 2.0 / (3.0 * kMass);
  const double Ap = 1.0 / kMass, Al = Ap + kLever * kLever / kInertia;
  const double ratio = (0.5 * Ap + 0.5 * Ahat) / (0.5 * Al + 0.5 * Ahat);
  std::printf("lever/point force ratio: MuJoCo %.15g, closed form %.15g\n", fl.force / fp.force,
              ratio);
  EXPECT_NEAR(fl.force / fp.force, ratio, 1e-12);
  EXPECT_LT(ratio, 0.5);  // a large effect, far outside the tolerance

  // Gravity off: same model with gravity 0.
  std::string xml = model_xml(point);
  xml.replace(xml.find("<option "), 8, "<option gravity=\"0 0 0\" ");
  const mj::ModelPtr model = mj::load_model(xml, "force test model");
  const mj::DataPtr data = mj::make_data(model.get());
  data->qpos[1] = kDrop + kRho - 1e-3;
  mj_forward(model.get(), data.get());
  const double drop = benchmarks::soft_constraint_force(Ap, Ahat, 0.5, 0.0, -kG);
  std::printf("gravity term: MuJoCo %.15g N, closed form d·g/(d·A + (1 − d)·Â) = %.15g N\n",
              fp.force - data->efc_force[0], drop);
  EXPECT_NEAR((fp.force - data->efc_force[0]) / drop, 1.0, 1e-12);
}

}  // namespace
}  // namespace contact2d
