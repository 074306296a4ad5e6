// MuJoCo with friction, against the reference (issue 13, item 3): the
// friction table of validation/report/closed_forms.md's last section, of
// docs/mujoco.md and of bench/friction_table.cpp (contact2d_friction).
//
// Six scenes, all 1 kg, Kelvin–Voigt, k = 1e4 N/m, α = 100, Δt = 1e-4 s,
// semi-implicit Euler in both engines (MuJoCo's Euler), samples every 1 ms:
//   box_slide       box 0.4 × 0.2 m lying flat, vx = 2 m/s, μ = 0.5, c = 50, 1.5 s
//   box_slide_c200  the same with c = 200 N·s/m
//   tshape          the T dropped from 0.8 m at θ = 0.2, vx = 0.3, μ = 0.5, c = 200, 2 s
//   roll            disc R = 0.1 m rolling at 2 m/s, μ = 0.5, μ_roll = 0.01 m, c = 200, 3 s
//   slide_roll      disc at 2 m/s without spin, μ = 0.2, c = 200, 2 s: slides,
//                   then rolls at 2/3 of v0
//   backspin        disc dropped from 0.3 m, vx = 1 m/s, ω = +30 rad/s, μ = 0.5, c = 200, 2 s
//
// Each row: the largest position difference between the engines under
// calibrated and under compensated, and MuJoCo's largest height above the
// reference (the hop). The attribution is a measurement: the same scene in
// MuJoCo with the damper's push taken out of the cone (friction_split_xml:
// every contact geom split into a frictionless one carrying the spring and
// the damper, and a frictional one with a small share of both), which no
// mapping can use (it weakens the friction limit during impacts) but which
// shows how much of the difference the push makes.
#pragma once

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

struct FrictionRow {
  std::string name, what;
  FrictionOutcome calibrated, compensated;
  FrictionOutcome split;  // compensated with the push removed (measurement only)
};

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
