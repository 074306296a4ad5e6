// Closed forms of a body at rest on penalty contacts (docs/closed-forms.md,
// section 1).
//
// A body resting on N equal contact points, each a linear spring of
// stiffness k (N/m) with a damper that does no work at rest: in equilibrium
// the springs carry the weight, so every point sinks by the same depth.
// The second law below is the soft-constraint (impedance) law's answer at
// rest, the law of a solver that regularises each contact row (MuJoCo's,
// docs/mujoco.md derives it): the functions take its constants as numbers
// and know nothing of the solver.
#pragma once

namespace contact2d::benchmarks {

// Penalty contact at rest. The force balance
//   N·k·d = m·g
// gives the depth d (m) of each of the N points: m in kg, g in m/s², k in
// N/m. A point mass or a disc has N = 1, a flat box on its corners N = 2.
double rest_depth(double mass, double gravity, double stiffness, int contacts);

// Soft constraint at rest. Each of the n contact rows is regularised with
// R = (1 − d)/d·Â (d the impedance, Â the approximate inverse mass in 1/kg)
// and pulled by the reference acceleration aref = −K·d·p (direct form with a
// flat impedance: K·d² = s, s the row's stiffness in N/m per kg of Â⁻¹). At
// rest J·qacc = 0, so each row's force f = (aref − J·qacc)/R satisfies
//   f·R = K·d·p   ⇒   p = f·Â·(1 − d)/s,   f = m·g/n,
// whatever the true inverse mass. Returns p (m).
double soft_constraint_rest_depth(double mass, double gravity, double inv_weight, double impedance,
                                  int contacts, double stiffness);

}  // namespace contact2d::benchmarks
