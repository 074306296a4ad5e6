// The one reader of MuJoCo's arrays both versions go through
// (mujoco/state_arrays.hpp), on arrays written here by hand: which contacts
// it lists, each version's margin rule, the inverse masses through the
// version's solve, the rows in the quadratic zone, names, and the misfits
// it refuses. Every expected value is worked out in the comment beside it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mujoco/state_arrays.hpp"

namespace contact2d::mujoco {
namespace {

// The world (body 0, a plane geom 0) and one body (body 1, geom 1) on three
// slide joints x, y, z (dofs 0, 1, 2).
StateArrays two_bodies() {
  StateArrays a;
  a.nv = 3;
  a.body_names = {"", "box"};
  a.geom_names = {"floor", "box"};
  a.body_weldid = {0, 1};
  a.body_parentid = {0, 0};
  a.body_mass = {0.0, 2.0};
  a.body_inertia = {0, 0, 0, 1, 1, 1};
  a.body_invweight0 = {0, 0, 0.5, 0};
  a.jnt_bodyid = {1, 1, 1};
  a.jnt_type = {2, 2, 2};  // mjJNT_SLIDE
  a.geom_bodyid = {0, 1};
  a.geom_condim = {3, 3};
  a.geom_contype = {1, 1};
  a.geom_conaffinity = {1, 1};
  a.geom_friction = {1, 0.005, 0.0001, 0.5, 0.005, 0.0001};
  a.geom_margin = {0.01, 0.03};
  a.geom_gap = {0.002, 0.004};
  a.geom_priority = {0, 0};
  a.geom_solmix = {1, 1};
  a.geom_solref = {0.02, 1, 0.02, 1};
  a.qvel = {0, 0, 0};
  a.qacc = {0, 0, 0};
  return a;
}

// A contact of the plane and the box at the origin, normal +z: the box's
// translational Jacobian is the identity on its three dofs, the world's
// is zero.
ArrayContact floor_contact(int efc_address) {
  ArrayContact c;
  c.geom1 = 0;
  c.geom2 = 1;
  c.dim = 3;
  c.efc_address = efc_address;
  c.frame = {0, 0, 1, 1, 0, 0, 0, 1, 0};
  c.friction = {0.5, 0.5, 0.005, 0.0001, 0.0001};
  for (size_t k = 0; k < 3; ++k) {
    c.jac2[k].index = {static_cast<int>(k)};
    c.jac2[k].value = {1.0};
  }
  return c;
}

// M = diag(2, 4, 8): M⁻¹ divides each column by its mass.
SolveM diagonal_solve(int* calls = nullptr) {
  return [calls](const std::vector<SparseRow>& rows) {
    if (calls) ++*calls;
    const double mass[3] = {2.0, 4.0, 8.0};
    std::vector<SparseRow> out = rows;
    for (SparseRow& row : out)
      for (size_t k = 0; k < row.index.size(); ++k)
        row.value[k] /= mass[static_cast<size_t>(row.index[k])];
    return out;
  };
}

TEST(StateArrays, OnlyContactsInTheConstraintProblemAreListed) {
  StateArrays a = two_bodies();
  a.efc_force.assign(8, 0.0);
  ArrayContact in_gap = floor_contact(0);
  in_gap.exclude = 1;  // within its gap: MuJoCo keeps it out of the problem
  ArrayContact no_rows = floor_contact(-1);
  ArrayContact listed = floor_contact(4);
  listed.dist = 0.25;  // told apart from the others
  a.contacts = {in_gap, no_rows, listed};
  ModelState s;
  read_state_arrays(a, diagonal_solve(), s);
  ASSERT_EQ(s.contacts.size(), 1U);
  EXPECT_EQ(s.contacts[0].dist, 0.25);
}

TEST(StateArrays, MarginAndGapFollowEachVersionsRuleAndAPairsOwn) {
  StateArrays a = two_bodies();
  a.efc_force.assign(4, 0.0);
  ArrayContact c = floor_contact(0);
  c.dist = 0.001;
  c.includemargin = 0.003;
  a.contacts = {c};
  ModelState larger;
  read_state_arrays(a, diagonal_solve(), larger);
  // 2.2.2: the larger geom's, max(0.01, 0.03) and max(0.002, 0.004).
  EXPECT_EQ(larger.contacts.at(0).margin, 0.03);
  EXPECT_EQ(larger.contacts[0].gap, 0.004);
  EXPECT_FALSE(larger.contacts[0].explicit_pair);
  EXPECT_DOUBLE_EQ(larger.contacts[0].dist, -0.002);  // 0.001 − 0.003

  a.margin_rule = MarginRule::Summed;  // 3.x: 0.01 + 0.03 and 0.002 + 0.004
  ModelState summed;
  read_state_arrays(a, diagonal_solve(), summed);
  EXPECT_DOUBLE_EQ(summed.contacts.at(0).margin, 0.04);
  EXPECT_DOUBLE_EQ(summed.contacts[0].gap, 0.006);

  a.pair_geom1 = {1};  // a <pair> names the geoms in either order
  a.pair_geom2 = {0};
  a.pair_margin = {0.5};
  a.pair_gap = {0.1};
  ModelState paired;
  read_state_arrays(a, diagonal_solve(), paired);
  EXPECT_TRUE(paired.contacts.at(0).explicit_pair);
  EXPECT_EQ(paired.contacts[0].margin, 0.5);
  EXPECT_EQ(paired.contacts[0].gap, 0.1);
}

TEST(StateArrays, InverseMassesAreTheFrameRowsThroughTheVersionsSolve) {
  StateArrays a = two_bodies();
  a.efc_force.assign(4, 0.0);
  a.contacts = {floor_contact(0)};
  int calls = 0;
  ModelState s;
  read_state_arrays(a, diagonal_solve(&calls), s);
  EXPECT_EQ(calls, 1);  // every row in one solve
  const StateContact& c = s.contacts.at(0);
  // n = z: the row is dof 2 alone; A = 1/8. Tangents x and y: 1/2 and 1/4.
  EXPECT_EQ(c.jacobian.index, std::vector<int>{2});
  EXPECT_EQ(c.jacobian.value, std::vector<double>{1.0});
  EXPECT_EQ(c.solved.value, std::vector<double>{0.125});
  EXPECT_EQ(c.A, 0.125);
  EXPECT_EQ(c.A_t, 0.5);
  EXPECT_EQ(c.tangent[1].index, std::vector<int>{1});

  // Two geoms moving as one (the same Jacobian on both sides): J₂ − J₁ = 0,
  // the row vanishes.
  a.contacts[0].jac1 = a.contacts[0].jac2;
  ModelState same;
  read_state_arrays(a, diagonal_solve(), same);
  EXPECT_TRUE(same.contacts.at(0).jacobian.index.empty());
  EXPECT_EQ(same.contacts[0].A, 0.0);
}

TEST(StateArrays, RowsInTheQuadraticZoneComeFromTheForces) {
  StateArrays a = two_bodies();
  // Pyramidal condim 3: 4 rows; two push.
  a.efc_force = {1.0, 0.0, 2.0, 0.0};
  a.contacts = {floor_contact(0)};
  ModelState pyramid;
  read_state_arrays(a, diagonal_solve(), pyramid);
  EXPECT_EQ(pyramid.contacts.at(0).rows, 4);
  EXPECT_EQ(pyramid.contacts[0].quadratic, 2);

  // Elliptic condim 3: 3 rows; inside the cone when ‖(f₁/μ, f₂/μ)‖ < f₀.
  a.elliptic = true;
  a.efc_force = {1.0, 0.15, 0.2, 0.0};  // ‖(0.3, 0.4)‖ = 0.5 < 1
  ModelState inside;
  read_state_arrays(a, diagonal_solve(), inside);
  EXPECT_EQ(inside.contacts.at(0).rows, 3);
  EXPECT_EQ(inside.contacts[0].quadratic, 3);
  a.efc_force = {1.0, 0.3, 0.4, 0.0};  // ‖(0.6, 0.8)‖ = 1: on the cone, sliding
  ModelState on_cone;
  read_state_arrays(a, diagonal_solve(), on_cone);
  EXPECT_EQ(on_cone.contacts.at(0).quadratic, 0);
}

TEST(StateArrays, NamesArePrintableAndTheUnnamedNumbered) {
  StateArrays a = two_bodies();
  a.body_names = {"", "a\x1b[2Jb"};
  a.geom_names = {"", "g"};
  a.jnt_type = {2, 3, 0};
  ModelState s;
  read_state_arrays(a, diagonal_solve(), s);
  EXPECT_EQ(s.body_names, (std::vector<std::string>{"world", "a\\x1b[2Jb"}));
  EXPECT_EQ(s.geom_names, (std::vector<std::string>{"geom #0", "g"}));
  EXPECT_EQ(s.body_joints.at(1), "slide, hinge, free");
  EXPECT_EQ(s.geom_mu, (std::vector<double>{1.0, 0.5}));
}

TEST(StateArrays, ArraysThatDoNotFitAreNamed) {
  StateArrays a = two_bodies();
  a.efc_force.assign(4, 0.0);
  a.contacts = {floor_contact(0)};
  EXPECT_EQ(arrays_misfit(a), "");
  StateArrays b = a;
  b.contacts[0].geom2 = 2;
  EXPECT_EQ(arrays_misfit(b), "a contact's geom is out of range");
  b = a;
  b.efc_force.assign(3, 0.0);  // 4 pyramidal rows from address 0
  EXPECT_EQ(arrays_misfit(b), "a contact's constraint rows are out of range");
  b = a;
  b.contacts[0].jac2[0] = {{2, 1}, {1.0, 1.0}};
  EXPECT_EQ(arrays_misfit(b), "a Jacobian row's columns are out of range or order");
  b = a;
  b.geom_margin.pop_back();
  EXPECT_EQ(arrays_misfit(b), "the geom arrays differ in length");
  b = a;
  b.qacc.pop_back();
  EXPECT_EQ(arrays_misfit(b), "qvel or qacc is not nv long");
}

}  // namespace
}  // namespace contact2d::mujoco
