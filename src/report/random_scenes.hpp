// The random scenes of README.md section 6: scenes the MuJoCo mapping was not
// built on, drawn from a seeded SplitMix64 (core/rng.hpp), so the same seed
// gives the same scenes on every machine. The four shapes in turn with
// m = 10^U(−1, 1) kg, k = 10^U(3, 5.5) N/m, the damping ratio
// ζ log-uniform in [0.1, 5] (underdamped, critical and overdamped contacts
// equally likely per factor of ζ), stratified: the range of log ζ is cut
// into `count` equal slices, a seeded shuffle gives each scene one, and its
// ζ is uniform in log inside it (so every scene's ζ is log-uniform and the
// bands of README.md section 6 get their share, ±1, whatever the seed);
// from it c = 2ζ√(k·m) N·s/m with m the total mass (a T's from its parts),
// μ = U(0.1, 1); a point mass's half height U(0, 0.2) m, a box's sides
// 0.05 + U(0, 1) m, a disc's radius 0.02 + U(0, 0.5) m, a T of one to three
// parts (sides 0.05 + U(0, 0.55) m, centres U(−0.3, 0.3) m, masses
// m·U(0.2, 1)); dropped from y = U(0.6, 1.5) m with vx = U(−1.5, 1.5) m/s and,
// except the point mass, θ = U(−0.6, 0.6) rad and ω = U(−3, 3) rad/s.
// Kelvin–Voigt, α = 100 s/m, Δt = 1e-4 s, 1.5 s, semi-implicit Euler. Each
// drawn value is rounded to the digits the report prints (mass, k, c to 6,
// μ to 3, lengths and the initial state to 4), so the table shows exactly
// what ran; ζ = c/(2√(k·m)) of those values holds to c's 6-digit rounding.
// ζ is that of the body's translation on its contacts (m, not the smaller
// effective mass 1/(1/m + r²/I) of a corner, whose own ratio is larger).
// Every scene passes the core's validate().
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace contact2d::report {

struct RandomScene {
  std::string name;  // "s00", "s01", …
  Scene scene;
  double mass = 0.0;  // total mass, kg (a T's from its parts)
};

// The range of the drawn damping ratio ζ = c/(2√(k·m)).
constexpr double kMinZeta = 0.1;
constexpr double kMaxZeta = 5.0;

// Scenes the report draws: enough for at least eight in each ζ band of
// README.md section 6 for every seed. The bands ζ < 0.3, 0.3–1 and ≥ 1 are
// the fractions ln 3/ln 50 = 0.281, 0.308 and 0.411 of log ζ; with 32
// slices, 8, 9 and 13 slices lie wholly inside them.
constexpr int kRandomSceneCount = 32;

// Throws std::runtime_error naming the key when a drawn scene fails validate().
std::vector<RandomScene> draw_random_scenes(std::uint64_t seed, int count);

}  // namespace contact2d::report
