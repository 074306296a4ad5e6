// The spec of `contact2d atlas` (docs/atlas.md): the parameter space a
// fidelity atlas covers, read from TOML. Plain data; turning it into points
// and running them is analysis/atlas.hpp.
//
//   [atlas]
//   sample = "grid"                  # or "random"
//   bodies = ["point_mass", "box"]   # shapes (default geometry) or scene files
//   mappings = ["calibrated"]        # seed | exact | calibrated | compensated
//   engine = "mujoco3"               # optional: MuJoCo 3.14 instead of 2.2.2
//   damping = ["kelvin_voigt"]       # kelvin_voigt | compression
//   integrator = "semi_implicit_euler"
//   duration = 2.0                   # s
//   output_dt = 1e-3                 # s, the samples the errors are taken at
//   converged_tol = 1e-12            # the converged solution's tolerance (default)
//   count = 100                      # random only: points per body × mapping × damping
//   seed = 1                         # random only
//
//   [axes]                           # each: a number (constant), a list (grid: every
//   mass = 1.0                       # value; random: one of them, uniformly) or, random
//   k = [1e4, 1e5, 1e6]              # only, { min = A, max = B } (log-uniform in [A, B])
//   zeta = [0.2, 1.0]                # or c = ... (N·s/m); exactly one of the two
//   mu = [0.0, 0.5]
//   mu_roll = 0.0
//   dt = 1e-4
//
//   [initial]                        # optional: the initial state of every body
//   y = 0.6                          # (theta and omega are not applied to a point mass)
//
// Every error is an InputError of one line naming the spec, the field and
// its allowed range.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/scene.hpp"

namespace contact2d {

// One continuous parameter of the atlas.
struct AtlasAxis {
  std::vector<double> values;  // a list (grid: every value; random: one of them)
  bool log_uniform = false;    // random only: log-uniform in [min, max]
  double min = 0.0, max = 0.0;
};

struct AtlasBody {
  std::string label;  // the shape's name, or the scene file's stem
  Scene scene;        // the base scene (its contact and time values are replaced per point)
};

struct AtlasSpec {
  std::string origin;  // the spec file, in messages
  bool random = false;
  std::vector<AtlasBody> bodies;
  std::vector<std::string> mappings;
  // The registry's kind of the MuJoCo run at every point; empty: MuJoCo
  // 2.2.2 (analysis/atlas_run.cpp checks the name).
  std::string engine;
  std::vector<DampingLaw> damping;
  Integrator integrator = Integrator::SemiImplicitEuler;
  double duration = 2.0;
  double output_dt = 1e-3;
  double converged_tol = 1e-12;
  long long count = 0;     // random: points per body × mapping × damping law
  std::uint64_t seed = 1;  // random
  bool by_zeta = true;     // the damping axis is ζ (c = 2ζ√(k·m)); else c itself
  AtlasAxis mass, k, damping_value, mu, mu_roll, dt;
  std::string digest;  // FNV-1a 64 of the spec's text, 16 hex digits: shards of one spec match
};

// The allowed ranges, checked by the parser (and named in its messages).
constexpr long long kAtlasMaxPoints = 10'000'000;

// Parses spec text; scene files named in `bodies` are relative to
// `base_dir`. Throws InputError.
AtlasSpec parse_atlas_spec(const std::string& text, const std::string& origin,
                           const std::string& base_dir);
// Reads the file and parses it. Throws InputError.
AtlasSpec load_atlas_spec(const std::string& path);

// The number of points the spec describes (grid: the product of every
// list's length; random: count × bodies × mappings × damping laws).
long long atlas_point_count(const AtlasSpec& spec);

}  // namespace contact2d
