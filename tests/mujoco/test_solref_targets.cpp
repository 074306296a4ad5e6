// `contact2d solref` from targets (mujoco/solref_tool.hpp, solve_targets):
// a restitution, an impact's duration, a rest depth. Each is pasted into a
// hand-written MuJoCo model (a free sphere above a plane, the calibrated
// snippet as a default class) and measured in MuJoCo itself.
//
// Tolerances.
//   restitution    MuJoCo's Euler is semi-implicit, whose discrete
//                  restitution differs from the continuous Kelvin–Voigt one
//                  to first order in ωΔt (the reference's closed-form
//                  rebound derives it, analysis/closed_forms.cpp): an early
//                  damper impulse ζ·ωΔt·e and ζ → ζ/√(1 − ζωΔt); twice
//                  their sum plus (ωΔt)²; and calibrated's force is the
//                  Kelvin–Voigt force to a relative d·A/Â = 1e-4 (A = Â for a
//                  free body).
//   contact time   the force is sampled once a step: ±Δt at each end.
//   rest depth     at rest MuJoCo's depth is calibrated's (1 − d)·f/k to
//                  rounding; 1e-9 relative.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include <mujoco/mujoco.h>

#include "benchmarks/impact.hpp"
#include "mujoco/inspect.hpp"
#include "mujoco/mjcf.hpp"
#include "mujoco/model.hpp"
#include "mujoco/solref_tool.hpp"

namespace contact2d {
namespace {

namespace mj = contact2d::mujoco;

constexpr double kRadius = 0.05;

// A free sphere of `mass` touching the plane (its lowest point 1e-12 m
// above it), the snippet's <option> attributes and <default> pasted in, its
// geom in the snippet's class.
std::string free_sphere(double mass, double dt, double gravity, const std::string& snippet) {
  std::string option, head = snippet;
  if (snippet.rfind("<option", 0) == 0) {
    const size_t end = snippet.find("/>\n");
    option = snippet.substr(7, end - 7);
    head = snippet.substr(end + 3);
  }
  const double inertia = 0.4 * mass * kRadius * kRadius;
  char body[512];
  std::snprintf(
      body, sizeof body,
      "    <body name=\"ball\" pos=\"0 0 %.17g\">\n      <freejoint/>\n"
      "      <inertial pos=\"0 0 0\" mass=\"%.17g\" diaginertia=\"%.17g %.17g %.17g\"/>\n",
      kRadius + 1e-12, mass, inertia, inertia, inertia);
  return "<mujoco model=\"targets\">\n  <option timestep=\"" + mj::format_exact(dt) +
         "\" gravity=\"0 0 " + mj::format_exact(-gravity) + "\"" + option + "/>\n" + head +
         "  <worldbody>\n    <geom name=\"ground\" type=\"plane\" size=\"0 0 1\"/>\n" + body +
         "      <geom name=\"ball_geom\" class=\"contact2d\" type=\"sphere\" size=\"" +
         mj::format_exact(kRadius) + "\"/>\n    </body>\n  </worldbody>\n</mujoco>\n";
}

mj::SolrefInput free_body(double mass, double dt) {
  mj::SolrefInput in;
  in.mass = mass;
  in.dt = dt;
  in.joint = mj::Joint::Free;
  in.body_source = "test";
  in.k = 1.0;  // placeholders until solve_targets
  return in;
}

// The calibrated outcome for the solved input.
mj::MappingOutcome calibrated(const mj::SolrefInput& in) {
  const mj::SolrefReport r = mj::solref_report(in, {mj::Mapping::Calibrated});
  EXPECT_EQ(r.mappings.size(), 1u);
  EXPECT_TRUE(r.mappings[0].unavailable.empty());
  return r.mappings[0];
}

struct Impact {
  double out_speed = 0.0;   // vertical speed after the impact, m/s
  double force_time = 0.0;  // time with a positive contact force, s
};

// Throws the sphere at the plane at 1 m/s without gravity and steps until
// it has left it.
Impact impact(const std::string& xml, double seconds) {
  const mj::ModelPtr model = mj::load_model(xml, "targets test model");
  const mj::DataPtr data = mj::make_data(model.get());
  data->qvel[2] = -1.0;  // the free joint's z velocity
  const long steps = std::lround(seconds / model->opt.timestep);
  long first = -1, last = -1;
  for (long i = 0; i < steps; ++i) {
    mj_step(model.get(), data.get());
    // efc_force of the contact's normal row, as the step that just ran
    // computed it (mj_step leaves d->efc_* of its forward pass).
    if (data->nefc > 0 && data->efc_force[0] > 0.0) {
      if (first < 0) first = i;
      last = i;
    }
  }
  Impact out;
  out.out_speed = data->qvel[2];
  out.force_time = first < 0 ? 0.0 : static_cast<double>(last - first + 1) * model->opt.timestep;
  return out;
}

double restitution_tolerance(double zeta, double omega_dt) {
  const double e = benchmarks::kelvin_voigt_restitution(zeta);
  const double shifted =
      benchmarks::kelvin_voigt_restitution(zeta / std::sqrt(1.0 - zeta * omega_dt));
  return 2.0 * (zeta * omega_dt * e + std::abs(shifted - e)) + omega_dt * omega_dt + 1e-4;
}

TEST(SolrefTargets, RestitutionIsWhatMujocoRebounds) {
  for (const double e : {0.2, 0.5, 0.8}) {
    mj::SolrefInput in = free_body(1.5, 1e-4);
    in.k = 2e4;
    mj::SolrefTargets t;
    t.restitution = e;
    mj::solve_targets(in, t, /*k_given=*/true, /*c_given=*/false);
    EXPECT_FALSE(in.targets_note.empty());
    const double omega = std::sqrt(in.k / in.mass), zeta = in.c / (2.0 * std::sqrt(in.k * in.mass));
    EXPECT_NEAR(benchmarks::kelvin_voigt_restitution(zeta), e, 1e-12);  // the solve itself
    const mj::MappingOutcome o = calibrated(in);
    const Impact hit = impact(free_sphere(in.mass, in.dt, 0.0, o.default_snippet), 0.1);
    const double tolerance = restitution_tolerance(zeta, omega * in.dt);
    std::printf("restitution %.2f: c = %.6g N·s/m, MuJoCo rebounds at %.6f (tolerance %.2g)\n", e,
                in.c, hit.out_speed, tolerance);
    EXPECT_NEAR(hit.out_speed, e, tolerance) << "e = " << e;
  }
}

TEST(SolrefTargets, ContactTimeIsHowLongMujocosForceActs) {
  for (const double duration : {0.005, 0.02}) {
    mj::SolrefInput in = free_body(1.5, 1e-4);
    mj::SolrefTargets t;
    t.restitution = 0.4;
    t.contact_time = duration;
    mj::solve_targets(in, t, /*k_given=*/false, /*c_given=*/false);
    const double omega = std::sqrt(in.k / in.mass), zeta = in.c / (2.0 * std::sqrt(in.k * in.mass));
    EXPECT_NEAR(benchmarks::kelvin_voigt_contact_time(zeta) / omega, duration, 1e-12 * duration);
    const mj::MappingOutcome o = calibrated(in);
    const Impact hit = impact(free_sphere(in.mass, in.dt, 0.0, o.default_snippet), 0.1);
    std::printf("contact time %.3g s: k = %.6g N/m, MuJoCo's force acts %.6g s, rebounds at %.4f\n",
                duration, in.k, hit.force_time, hit.out_speed);
    EXPECT_NEAR(hit.force_time, duration, 2.0 * in.dt) << duration;
    EXPECT_NEAR(hit.out_speed, 0.4, restitution_tolerance(zeta, omega * in.dt));
  }
}

TEST(SolrefTargets, PenetrationIsWhereMujocoRests) {
  for (const double depth : {2e-4, 1e-3, 5e-3}) {
    mj::SolrefInput in = free_body(1.5, 1e-4);
    in.c = 100.0;
    mj::SolrefTargets t;
    t.penetration = depth;
    mj::solve_targets(in, t, /*k_given=*/false, /*c_given=*/true);
    const mj::MappingOutcome o = calibrated(in);
    EXPECT_NEAR(o.static_penetration, depth, 1e-12 * depth);  // the printed depth is the target
    const mj::ModelPtr model =
        mj::load_model(free_sphere(in.mass, in.dt, 9.81, o.default_snippet), "targets rest");
    const mj::DataPtr data = mj::make_data(model.get());
    for (long i = 0; i < 30000; ++i) mj_step(model.get(), data.get());  // 3 s: ζ ≥ 0.3, at rest
    mj_forward(model.get(), data.get());
    ASSERT_EQ(data->ncon, 1);
    const double measured = -data->contact[0].dist;
    std::printf("penetration %.3g m: k = %.6g N/m, MuJoCo rests at %.9g m\n", depth, in.k,
                measured);
    EXPECT_NEAR(measured, depth, 1e-9 * depth);
  }
}

// Under- and over-determined targets and values out of range are named.
TEST(SolrefTargets, ContradictionsAndRangesAreNamed) {
  auto message = [](mj::SolrefTargets t, bool k, bool c) {
    mj::SolrefInput in = free_body(1.0, 1e-4);
    in.k = 1e4;
    in.c = 10.0;
    try {
      mj::solve_targets(in, t, k, c);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  mj::SolrefTargets both;
  both.penetration = 1e-3;
  EXPECT_NE(message(both, true, true).find("--k"), std::string::npos);
  mj::SolrefTargets time_alone;
  time_alone.contact_time = 0.01;
  EXPECT_NE(message(time_alone, false, true).find("--contact-time: needs --restitution"),
            std::string::npos);
  mj::SolrefTargets e_and_c;
  e_and_c.restitution = 0.5;
  EXPECT_NE(message(e_and_c, true, true).find("--c"), std::string::npos);
  mj::SolrefTargets bad_e;
  bad_e.restitution = 1.0;
  EXPECT_NE(message(bad_e, true, false).find("--restitution 1: must be a number in (0, 1)"),
            std::string::npos)
      << message(bad_e, true, false);
  mj::SolrefTargets bad_p;
  bad_p.penetration = -1e-3;
  EXPECT_NE(message(bad_p, false, true).find("--penetration"), std::string::npos);
  EXPECT_NE(message({}, false, true).find("--k: required"), std::string::npos);
  EXPECT_NE(message({}, true, false).find("--c: required"), std::string::npos);
}

}  // namespace
}  // namespace contact2d
