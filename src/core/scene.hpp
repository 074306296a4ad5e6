// A scene: which body, its contact law, initial state and time stepping.
// Plain data; reading it from a file lives in src/io. Defaults are the values
// documented in the README's scene-file table.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/dynamics.hpp"
#include "core/integrators.hpp"
#include "core/shape.hpp"

namespace contact2d {

struct SimParams {
  double dt = 1e-4;
  double duration = 2.0;
  double output_dt = 1e-3;  // sample spacing of the trajectory (rounded to a multiple of dt)
  Integrator integrator = Integrator::SemiImplicitEuler;
  double gravity = 9.81;
};

struct Scene {
  Shape shape = Shape::PointMass;
  // [body]
  double mass = 1.0;
  double half_height = 0.05;  // point mass: contact point at (0, −half_height)
  double width = 0.4;         // box
  double height = 0.2;        // box
  double radius = 0.1;        // circle
  double a = 0.2;             // ellipse: semi-axis along the body's x
  double b = 0.1;             // ellipse: semi-axis along the body's y
  double inertia = 0.0;  // ellipse: about the COM, kg·m²; 0 = a uniform plate's m·(a² + b²)/4
  std::vector<BoxPart> parts;  // tshape; empty = the default T
  ContactParams contact;
  std::vector<Obstacle> obstacles;  // static geometry, same contact law as the ground
  State initial;
  SimParams sim;
};

// The default T: a 0.6 × 0.1 bar (0.6 kg) on a 0.1 × 0.4 stem (0.4 kg).
std::vector<BoxPart> default_tshape_parts();

// Scene with the documented defaults of a shape (initial state included).
Scene default_scene(Shape shape);

// A value outside its allowed range: names the key and the range.
// The most parts a tshape's body may have (scene.cpp says why).
inline constexpr size_t kMaxParts = 64;

struct ValidationError {
  std::string key;     // e.g. "body.mass" or "body.parts[1].width"
  std::string range;   // e.g. "must be in (0, 1e9] kg"
  double value = 0.0;  // the offending value
};

// Checks every range rule; returns the first violation.
std::optional<ValidationError> validate(const Scene& scene);

RigidBody make_body(const Scene& scene);
Model make_model(const Scene& scene);

// The most samples a run keeps (validate refuses a sampling with more).
constexpr long long kMaxSamples = 10'000'000;

// Number of steps and sample stride implied by sim.dt, sim.duration, sim.output_dt.
long long step_count(const SimParams& sim);
long long sample_stride(const SimParams& sim);

}  // namespace contact2d
