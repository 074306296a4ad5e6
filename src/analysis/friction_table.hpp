// MuJoCo with friction, against the reference: the friction table of
// validation/report/friction.md, of docs/mujoco.md and of
// bench/friction_table.cpp (contact2d_friction).
//
// Eight scenes, all 1 kg, Kelvin–Voigt, k = 1e4 N/m, Δt = 1e-4 s,
// semi-implicit Euler in both engines (MuJoCo's Euler), samples every 1 ms
// (α = 100 s/m unless stated):
//   point_slide     point mass resting, vx = 1 m/s, μ = 0.6, α = 500, c = 20, 1 s
//   box_slide       box 0.4 × 0.2 m lying flat, vx = 2 m/s, μ = 0.5, c = 50, 1.5 s
//   box_slide_c200  the same with c = 200 N·s/m
//   tshape          the T dropped from 0.8 m at θ = 0.2, vx = 0.3, μ = 0.5, c = 200, 2 s
//   roll            disc R = 0.1 m rolling at 2 m/s, μ = 0.5, μ_roll = 0.01 m, c = 200, 3 s
//   slide_roll      disc at 2 m/s without spin, μ = 0.2, c = 200, 2 s: slides,
//                   then rolls at 2/3 of v0
//   backspin        disc dropped from 0.3 m, vx = 1 m/s, ω = +30 rad/s, μ = 0.5, c = 200, 2 s
//   backspin_bounce disc dropped from 0.3 m, vx = 1.5 m/s, ω = +20 rad/s, μ = 0.4,
//                   μ_roll = 0.004 m, c = 200, 2 s: bounces with backspin
//
// Each row: the largest position difference between the engines under
// calibrated and under compensated, MuJoCo's largest height above the
// reference (the hop), and the attribution, every part a measured distance
// between two runs:
//   shape        the reference (tanh) against the reference under the cone's
//                shape without its push (friction_law = viscous_cone)
//   push         viscous_cone against soft_cone: the push c·s, the divisor
//                1 + μ²/impratio, the contact point halfway into the
//                penetration
//   conformance  the reference under soft_cone against MuJoCo (compensated):
//                what is not the friction law (MuJoCo's soft contact, its
//                step; rounding)
// (all at compensated's impratio and rolling coefficient). By the triangle
// inequality the compensated difference is at most shape + push +
// conformance. And every setting of MuJoCo 2.2.2 that touches friction, each
// on its own (FrictionKnob), and the friction split (friction_split_xml):
// the same scene in MuJoCo with the damper's push taken out of the cone,
// which no mapping can use (it weakens the friction limit during impacts)
// but which shows how much of the difference the push makes.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace contact2d::analysis {

struct FrictionScene {
  std::string name;
  std::string what;  // one line for a table
  Scene scene;
};
std::vector<FrictionScene> friction_scenes();

struct FrictionOutcome {
  double max_pos = 0.0;    // m, reference ↔ MuJoCo
  double max_angle = 0.0;  // rad
  double hop = 0.0;        // MuJoCo's COM height above the reference's, largest, m
};

// A setting of MuJoCo 2.2.2 that touches friction, applied alone to the
// calibrated model (the one to build on).
enum class FrictionKnob {
  ImpratioTenth,  // impratio × 0.1
  ImpratioTen,    // impratio × 10
  Pyramidal,      // cone = "pyramidal"
  Noslip,         // noslip_iterations = 10
  Condim,         // condim 6 where the scene needs 3 (torsion and rolling rows added)
  MarginGap,      // margin = gap = 1 mm on every geom (contacts found early, not active)
  Pair,           // every contact an explicit <pair> with the ground (geom collisions off)
};
constexpr FrictionKnob kFrictionKnobs[] = {FrictionKnob::ImpratioTenth, FrictionKnob::ImpratioTen,
                                           FrictionKnob::Pyramidal,     FrictionKnob::Noslip,
                                           FrictionKnob::Condim,        FrictionKnob::MarginGap,
                                           FrictionKnob::Pair};
// "impratio x0.1", … (header-only: the report's pages name the knobs
// without linking MuJoCo).
inline std::string knob_name(FrictionKnob knob) {
  switch (knob) {
    case FrictionKnob::ImpratioTenth: return "impratio x0.1";
    case FrictionKnob::ImpratioTen: return "impratio x10";
    case FrictionKnob::Pyramidal: return "pyramidal cone";
    case FrictionKnob::Noslip: return "noslip_iterations 10";
    case FrictionKnob::Condim: return "condim 6";
    case FrictionKnob::MarginGap: return "margin = gap = 1 mm";
    case FrictionKnob::Pair: return "explicit <pair>";
  }
  return "";
}
// The calibrated model of `scene` with the knob applied; empty when it does
// not apply (condim 6 on a scene that already has it).
std::string friction_knob_xml(const Scene& scene, FrictionKnob knob);

struct FrictionRow {
  std::string name, what;
  FrictionOutcome calibrated, compensated;
  FrictionOutcome split;  // compensated with the push removed (measurement only)
  // The attribution (m, largest position distance), see the top of the file.
  double shape = 0.0;
  double push = 0.0;
  double conformance = 0.0;
  double conformance_angle = 0.0;  // rad
  // Each knob's difference to the reference (m), in kFrictionKnobs' order;
  // NaN where it does not apply, +∞ where MuJoCo diverged.
  std::vector<double> knobs;
  // MuJoCo 3.14 with its friction damper (mujoco3:compensated:corners:damper,
  // docs/mujoco3.md): max_pos is NaN when MuJoCo 3 did not run here.
  FrictionOutcome mujoco3_damper{std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0};
  // MuJoCo 3.14 without it (mujoco3:compensated), the same NaN.
  FrictionOutcome mujoco3_compensated{std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0};
};

// The scene as the reference runs it to conform to MuJoCo's model under
// `mapping` (compensated by default): friction_law = law at the model's
// impratio and rolling coefficient.
Scene conformance_scene(const Scene& scene, FrictionLaw law,
                        const std::string& mapping = "compensated");

// One scene's difference with friction taken apart (m, largest position
// distance): the reference (tanh) against MuJoCo under `mapping`, and the
// three parts of the top of this file under the same mapping.
// With `mujoco3`, MuJoCo 3.14 on the model written for it (the same
// mapping) beside 2.2.2: the same reference runs, its total and rest, and
// the largest distance between the two versions (NaN when not run).
struct FrictionParts {
  double total = 0.0;  // reference ↔ MuJoCo
  double shape = 0.0;  // reference ↔ reference under viscous_cone
  double push = 0.0;   // viscous_cone ↔ soft_cone
  double rest = 0.0;   // soft_cone ↔ MuJoCo
  bool ok = false;     // false: an engine diverged (the numbers are NaN)
  double total_v3 = std::numeric_limits<double>::quiet_NaN();  // reference ↔ 3.14
  double rest_v3 = std::numeric_limits<double>::quiet_NaN();   // soft_cone ↔ 3.14
  double apart_v3 = std::numeric_limits<double>::quiet_NaN();  // 2.2.2 ↔ 3.14
};
FrictionParts friction_parts(const Scene& scene, const std::string& mapping, bool mujoco3 = false);

// The split's shares: the frictional geom carries w of the spring and a
// damper of ρ·c, with μ/w so that its friction limit is the scene's.
constexpr double kSplitShare = 0.3;
constexpr double kSplitDamper = 1e-4;

// MuJoCo's model of `scene` under the compensated mapping with the friction
// split applied to the contact geoms.
std::string friction_split_xml(const Scene& scene, double w, double rho);

// Runs both engines under both mappings and the split on one scene.
FrictionRow friction_row(const FrictionScene& s);
// Every scene (threads: as analysis::parallel_for).
std::vector<FrictionRow> friction_table(unsigned threads = 0);

}  // namespace contact2d::analysis
