// The physics behind the game: one ball stepped at the scene's Δt with an
// external force from the player. "ref" is the reference solver (the core's
// step() on the scene's model, obstacles included).
#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "core/dynamics.hpp"
#include "core/scene.hpp"

namespace contact2d::game {

class Engine {
 public:
  virtual ~Engine() = default;
  virtual std::string_view name() const = 0;
  virtual void reset(const State& state) = 0;
  virtual void set_applied(const Vec3& force) = 0;  // (Fx, Fy, τ), held until changed
  virtual bool step() = 0;                          // one Δt; false when the step failed
  virtual const State& state() const = 0;
  // The scene's model: the divergence rule and the energy use it.
  virtual const Model& model() const = 0;
};

// "ref" (always) or "mujoco" (when it can play obstacles). Throws InputError
// for an unknown or unavailable engine.
std::unique_ptr<Engine> make_engine(const std::string& name, const Scene& scene);

}  // namespace contact2d::game
