#include "game/engine.hpp"

#include "core/integrators.hpp"
#include "io/scene_file.hpp"

namespace contact2d::game {
namespace {

class ReferenceEngine final : public Engine {
 public:
  explicit ReferenceEngine(const Scene& scene)
      : model_(make_model(scene)), integrator_(scene.sim.integrator), dt_(scene.sim.dt) {}

  std::string_view name() const override { return "ref"; }
  void reset(const State& state) override { state_ = state; }
  void set_applied(const Vec3& force) override { model_.applied = force; }
  bool step() override {
    return contact2d::step(model_, integrator_, dt_, state_) == StepStatus::Ok;
  }
  const State& state() const override { return state_; }
  const Model& model() const override { return model_; }

 private:
  Model model_;
  Integrator integrator_;
  double dt_;
  State state_;
};

}  // namespace

std::unique_ptr<Engine> make_engine(const std::string& name, const Scene& scene) {
  if (name == "ref") return std::make_unique<ReferenceEngine>(scene);
  if (name == "mujoco") {
    throw InputError(
        "--engine mujoco: not available for play (the MuJoCo adapter cannot step a scene "
        "interactively or load its obstacles yet); use --engine ref");
  }
  throw InputError("--engine " + name + ": unknown engine (use ref or mujoco)");
}

}  // namespace contact2d::game
