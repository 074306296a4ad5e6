// Implicit Euler's analytic Jacobian (acceleration_jacobian,
// core/dynamics.hpp) against central finite differences of the force stage
// itself, acceleration(model, q, v), on random states away from the law's
// kinks.
//
// Kinks: a contact appearing or leaving (d = 0), the compression damper
// switching (v_n = 0), Kelvin–Voigt's clamp (k·d = c·v_n). A state is used
// only when every probe q ± h·e_j, v ± h·e_j has the same contacts and every
// contact is at least 1e3·h·(1 + |r|)·(1 + |ω|) from each switch, so that all
// probes lie on one smooth branch.
//
// Tolerance: the central difference of a smooth f errs by h²·|f'''|/6
// (truncation) plus about ε·|f|/h (rounding). With h = 1e-6 and these laws
// (α ≤ 1e3 s/m: f''' ~ μ·Fn·2α³; k ≤ 1e6 N/m, forces ≤ ~1e4 N, m ~ 1 kg)
// the two are ~1e-5·|J| and ~1e-6 at worst; the check is
// |J_analytic − J_fd|max ≤ 1e-4·(1 + |J_analytic|max), and the measured
// worst is printed (docs/speed.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/dynamics.hpp"
#include "core/rng.hpp"
#include "core/scene.hpp"

namespace contact2d {
namespace {

constexpr double kH = 1e-6;

// Same contact list (count, ground share, obstacles touched) at q and q'.
bool same_contacts(const ContactSet& a, const ContactSet& b) {
  if (a.size() != b.size() || a.ground_count() != b.ground_count()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a.begin()[i].obstacle != b.begin()[i].obstacle) return false;
  }
  return true;
}

// Every contact away from its law's switches by `margin` (see the top).
bool away_from_kinks(const Model& model, const ContactSet& contacts, const Vec3& v) {
  const double omega = model.body.rotates ? v.z() : 0.0;
  for (const Contact& c : contacts) {
    const ContactParams& law = model.law(c);
    const double margin = 1e3 * kH * (1.0 + std::hypot(c.rx, c.ry)) * (1.0 + std::abs(v.z()));
    const double v_n = (v.x() - omega * c.ry) * c.nx + (v.y() + omega * c.rx) * c.ny;
    if (c.depth < margin) return false;
    if (law.damping == DampingLaw::Compression && std::abs(v_n) < margin) return false;
    if (law.damping == DampingLaw::KelvinVoigt &&
        std::abs(law.k * c.depth - law.c * v_n) < margin * (law.k + law.c))
      return false;
  }
  return true;
}

struct Sample {
  int used = 0;
  int with_obstacle = 0;
  double worst = 0.0;
};

Sample check(bool obstacles) {
  std::uint64_t rng = obstacles ? 17 : 16;
  auto u = [&rng] { return next_uniform(rng); };
  Sample result;
  for (int trial = 0; trial < 20000; ++trial) {
    const Shape shape = static_cast<Shape>(trial % 4);
    Scene scene = default_scene(shape);
    scene.contact.k = std::pow(10.0, 3.0 + 3.0 * u());
    scene.contact.c = u() < 0.3 ? 0.0 : std::pow(10.0, 3.0 * u());
    scene.contact.mu = u();
    scene.contact.alpha = std::pow(10.0, 1.0 + 2.0 * u());
    scene.contact.mu_roll = shape == Shape::Circle ? 0.05 * u() : 0.0;
    scene.contact.damping = u() < 0.5 ? DampingLaw::Compression : DampingLaw::KelvinVoigt;
    scene.sim.gravity = 9.81;
    // A wall to the right whose left face the body's right side can reach.
    if (obstacles) scene.obstacles.push_back(make_box_obstacle(0.3, 0.5, 0.2, 1.0));
    Model model = make_model(scene);
    model.applied = Vec3(u() - 0.5, u() - 0.5, 0.1 * (u() - 0.5));
    const Vec3 q(0.1 * u() - 0.05, 0.12 * u() - 0.02, shape == Shape::PointMass ? 0.0 : u() - 0.5);
    const Vec3 v(2.0 * u() - 1.0, 2.0 * u() - 1.0,
                 shape == Shape::PointMass ? 0.0 : 10.0 * u() - 5.0);

    ContactSet contacts(model), probe(model), fd_probe(model);
    find_contacts(model, q, contacts);
    if (contacts.empty() || !away_from_kinks(model, contacts, v)) continue;
    Eigen::Matrix<double, 3, 6> fd;
    bool smooth = true;
    for (int j = 0; j < 6 && smooth; ++j) {
      Vec3 qp = q, qm = q, vp = v, vm = v;
      if (j < 3) {
        qp[j] += kH;
        qm[j] -= kH;
      } else {
        vp[j - 3] += kH;
        vm[j - 3] -= kH;
      }
      find_contacts(model, qp, probe);
      smooth = same_contacts(contacts, probe) && away_from_kinks(model, probe, vp);
      const Vec3 ap = acceleration(model, probe, vp);
      find_contacts(model, qm, probe);
      smooth = smooth && same_contacts(contacts, probe) && away_from_kinks(model, probe, vm);
      const Vec3 am = acceleration(model, probe, vm);
      fd.col(j) = (ap - am) / (2.0 * kH);
    }
    if (!smooth) continue;
    AccelerationJacobian jac;
    const Vec3 a = acceleration_jacobian(model, contacts, q, v, jac, fd_probe);
    EXPECT_EQ(a, acceleration(model, contacts, v)) << "the same a as the force stage";
    Eigen::Matrix<double, 3, 6> analytic;
    analytic << jac.dq, jac.dv;
    const double scale = 1.0 + analytic.cwiseAbs().maxCoeff();
    const double err = (analytic - fd).cwiseAbs().maxCoeff() / scale;
    ++result.used;
    if (contacts.size() > contacts.ground_count()) ++result.with_obstacle;
    result.worst = std::max(result.worst, err);
    EXPECT_LE(err, 1e-4) << "trial " << trial << "\nanalytic\n" << analytic << "\nfd\n" << fd;
  }
  return result;
}

TEST(Jacobian, GroundContactsMatchCentralDifferences) {
  const Sample s = check(false);
  std::printf("ground: %d states, worst |J − J_fd|/(1 + |J|) = %.3g\n", s.used, s.worst);
  EXPECT_GT(s.used, 2000) << "the sample must exercise every body";
}

// Obstacle contacts: ∂a/∂v analytic, ∂a/∂q by forward differences inside
// acceleration_jacobian (step 1e-7·max(1, |q_j|): error ~ 1e-7·|f''| plus
// rounding ε·|f|/1e-7 ~ 1e-9·|f|, inside the same 1e-4 bound).
TEST(Jacobian, ObstacleContactsMatchCentralDifferences) {
  const Sample s = check(true);
  std::printf("with a wall: %d states (%d touching it), worst |J − J_fd|/(1 + |J|) = %.3g\n",
              s.used, s.with_obstacle, s.worst);
  EXPECT_GT(s.with_obstacle, 200) << "the sample must touch the wall";
}

}  // namespace
}  // namespace contact2d
