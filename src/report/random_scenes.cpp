// Seeded random scenes (report/random_scenes.hpp).
#include "report/random_scenes.hpp"

#include "core/format.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/rng.hpp"

namespace contact2d::report {
namespace {

// x rounded to `digits` significant digits, as "%.*g" prints it.
double rounded(double x, int digits) {
  return std::strtod(format_number(x, digits).c_str(), nullptr);
}

// The shape's own dimensions of `s`, drawn from `state`; returns the body's
// mass: `m`, or a compound's sum of its parts' masses.
double draw_body(std::uint64_t& state, double m, Scene& s) {
  auto u = [&state] { return next_uniform(state); };
  switch (s.shape) {
    case Shape::PointMass: s.half_height = rounded(u() * 0.2, 4); break;
    case Shape::Box:
      s.width = rounded(0.05 + u(), 4);
      s.height = rounded(0.05 + u(), 4);
      break;
    case Shape::Circle: s.radius = rounded(0.02 + u() * 0.5, 4); break;
    case Shape::Ellipse:
      s.a = rounded(0.02 + u() * 0.5, 4);
      s.b = rounded(0.02 + u() * 0.5, 4);
      break;
    case Shape::TShape: {
      s.parts.clear();
      const int n = 1 + static_cast<int>(u() * 3);
      double total = 0.0;
      for (int j = 0; j < n; ++j) {
        BoxPart part;
        part.mass = rounded(m * (0.2 + u() * 0.8), 6);
        part.width = rounded(0.05 + u() * 0.55, 4);
        part.height = rounded(0.05 + u() * 0.55, 4);
        part.x = rounded(u() * 0.6 - 0.3, 4);
        part.y = rounded(u() * 0.6 - 0.3, 4);
        total += part.mass;
        s.parts.push_back(part);
      }
      return total;
    }
  }
  if (!shape_features(s.shape).compound) s.mass = m;  // a compound's mass comes from its parts
  return m;
}

}  // namespace

std::vector<RandomScene> draw_random_scenes(std::uint64_t seed, int count) {
  std::uint64_t state = seed;
  auto u = [&state] { return next_uniform(state); };
  // ζ stratified: scene i lies in slice slots[i] of `count` equal slices of
  // log ζ over [kMinZeta, kMaxZeta] (a seeded Fisher–Yates shuffle), at a
  // uniform place inside it; so each scene's ζ is log-uniform and the scenes
  // cover the range evenly.
  std::vector<int> slots(static_cast<size_t>(std::max(count, 0)));
  std::iota(slots.begin(), slots.end(), 0);
  for (int i = count - 1; i > 0; --i) std::swap(slots[i], slots[static_cast<int>(u() * (i + 1))]);
  std::vector<RandomScene> out;
  for (int i = 0; i < count; ++i) {
    // The four shapes of the course, in turn (the ellipse is not drawn yet:
    // the report's snapshot of these scenes was made without it).
    constexpr std::array kDrawn = {Shape::PointMass, Shape::Box, Shape::TShape, Shape::Circle};
    const Shape shape = kDrawn[static_cast<size_t>(i) % kDrawn.size()];
    Scene s = default_scene(shape);
    double m = std::pow(10.0, u() * 2 - 1);
    const double k = std::pow(10.0, 3 + u() * 2.5);
    const double zeta = kMinZeta * std::pow(kMaxZeta / kMinZeta, (slots[i] + u()) / count);
    m = rounded(m, 6);
    m = draw_body(state, m, s);
    s.contact.k = rounded(k, 6);
    s.contact.c = rounded(2 * zeta * std::sqrt(s.contact.k * m), 6);
    s.contact.mu = rounded(0.1 + u() * 0.9, 3);
    s.contact.alpha = 100;
    s.contact.damping = DampingLaw::KelvinVoigt;
    const double spin = shape_features(shape).turns ? 1.0 : 0.0;
    s.initial.q = Vec3(0.0, rounded(0.6 + u() * 0.9, 4), rounded(spin * (u() * 1.2 - 0.6), 4));
    s.initial.v = Vec3(rounded(u() * 3 - 1.5, 4), 0.0, rounded(spin * (u() * 6 - 3), 4));
    s.sim.dt = 1e-4;
    s.sim.duration = 1.5;
    s.sim.integrator = Integrator::SemiImplicitEuler;
    const std::string name = format_text("s%02d", i);
    if (const auto error = validate(s)) {
      throw std::runtime_error("random scene " + name + ": " + error->key + " = " +
                               std::to_string(error->value) + " is out of range: " + error->range);
    }
    out.push_back({name, s, m});
  }
  return out;
}

}  // namespace contact2d::report
