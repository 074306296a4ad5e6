// A grazing contact: the first step at which two runs of one scene disagree
// on whether a point of the body touches something, while they still agree
// to rounding.
//
// Why. A contact is on when its depth is > 0 (core/contacts.hpp). A point
// that comes within a rounding error of a surface and turns back (a corner
// of a hopping or rocking box, a disc's lowest point at the top of a hop)
// touches in one run and not in the other when the two runs' states differ
// by more than its distance to the surface, e.g. 1e-12 m. From that step
// on, one engine applies a contact force the other does not, and the runs
// part by many orders of magnitude more than the rounding that decided it.
// That difference is neither engine's model: a change of the state by its
// rounding moves the contact either way.
//
// How. Both runs sampled at every step (output_dt = Δt) up to their
// departure: the first common sample at which some point of the body is
// more than a given distance apart in the two runs (the diagnosis takes
// 1/kGrazingGrowth of the difference it explains). At each step, with the
// body's points c = p + R(θ)·r_b in each run (a disc's point stays below
// its centre):
//   ground     point i touches when c_y < 0 (the contact stage's test);
//   obstacles  the number of contacts with obstacle j (find_contacts).
// The first step at which the two runs disagree on one of them is the
// grazing contact. For a ground point the runs' heights have opposite
// signs, so both are within the runs' distance there: the contact was
// decided by that distance — rounding when it is below kRoundingAgreement,
// else whatever small difference the engines' models keep — and the runs
// then part by kGrazingGrowth times that distance or more.
#pragma once

#include <optional>
#include <string>

#include "core/run.hpp"
#include "core/scene.hpp"

namespace contact2d::analysis {

// Two runs within this at every point of the body are the same run up to
// rounding (the mappings' frictionless agreement on the shipped scenes is
// 1e-9 m and better, docs/mujoco.md).
constexpr double kRoundingAgreement = 1e-9;  // m
// A contact switch explains a difference that grew from the runs' distance
// at the switch by at least this factor (three orders of magnitude: the
// switch, not the models' difference before it, made the difference).
constexpr double kGrazingGrowth = 1e3;

struct GrazingContact {
  double t = 0.0;          // s: the step whose state the runs disagree on
  std::string where;       // "point 2 on the ground", "obstacle 1"
  bool touches_a = false;  // touching in run a (and not in b)
  // The point's height above the surface in each run (negative: inside),
  // m; for an obstacle, minus the touching run's deepest contact with it
  // and NaN for the other run.
  double height_a = 0.0, height_b = 0.0;
  double apart = 0.0;  // m: the largest distance between the runs' points at that step
};

// The first common sample at which some point of the body is more than
// `distance` apart in a and b; NaN when they never are. The runs' states
// are compared at their common sample times, by index (one scene, one
// output_dt).
double departure_time(const Scene& scene, const Trajectory& a, const Trajectory& b,
                      double distance);

// The first common sample at which a and b disagree on a contact (above),
// before their departure at `distance`; nullopt when they never do.
std::optional<GrazingContact> grazing_contact(const Scene& scene, const Trajectory& a,
                                              const Trajectory& b, double distance);

}  // namespace contact2d::analysis
