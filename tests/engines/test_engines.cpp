// The engine registry (engines/engines.hpp): names in, steppers out, one
// result type, and a one-line error for anything it cannot run.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "core/input_error.hpp"
#include "engines/engines.hpp"
#include "io/scene_file.hpp"

namespace contact2d {
namespace {

std::string error_of(const std::string& name) {
  try {
    engines::parse_engine(name, "--engines");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Registry, ParsesTheReference) {
  const engines::EngineSpec spec = engines::parse_engine("ref");
  EXPECT_EQ(spec.kind, "ref");
  EXPECT_EQ(spec.name(), "ref");
}

TEST(Registry, UnknownNamesAreOneLineErrorsNamingTheOption) {
  EXPECT_EQ(error_of("bullet"), "--engines bullet: unknown engine (use ref, mujoco or mujoco3)");
  EXPECT_EQ(error_of("ref:exact"),
            "--engines ref:exact: unknown engine (use ref, mujoco or mujoco3)");
#ifdef CONTACT2D_WITH_MUJOCO
  EXPECT_EQ(error_of("mujoco:stiff"),
            "--engines mujoco:stiff: unknown mapping (seed, exact, calibrated, compensated)");
  EXPECT_EQ(error_of("mujoco:exact:spheres"),
            "--engines mujoco:exact:spheres: unknown geometry (corners, boxes)");
#else
  EXPECT_NE(error_of("mujoco").find("built without MuJoCo"), std::string::npos);
#endif
}

TEST(Registry, ListsWhatItCanRun) {
  const std::vector<std::string> names = engines::engine_names();
  ASSERT_FALSE(names.empty());
  EXPECT_EQ(names.front(), "ref");
  for (const std::string& name : names) EXPECT_EQ(engines::parse_engine(name).name(), name);
#ifdef CONTACT2D_WITH_MUJOCO
  // ref, then mujoco and mujoco3 each with :seed|exact|calibrated|compensated
  EXPECT_EQ(names.size(), 11u);
#else
  EXPECT_EQ(names.size(), 1u);
#endif
}

// The registry's reference run is the core's run loop on a ReferenceStepper:
// the same samples, bit for bit, and no MuJoCo settings.
TEST(Registry, ReferenceRunIsTheRunLoop) {
  const Scene scene = load_scene(std::string(CONTACT2D_SCENES_DIR) + "/box.toml");
  const engines::EngineRun run = engines::run_engine("ref", scene);
  const Trajectory direct = simulate(scene);
  ASSERT_EQ(run.trajectory.samples.size(), direct.samples.size());
  for (size_t i = 0; i < direct.samples.size(); ++i) {
    ASSERT_EQ(run.trajectory.samples[i].state.q, direct.samples[i].state.q);
    ASSERT_EQ(run.trajectory.samples[i].state.v, direct.samples[i].state.v);
  }
  EXPECT_EQ(run.description, "ref semi_implicit_euler");
  EXPECT_TRUE(std::isnan(run.impratio));
  EXPECT_TRUE(run.warnings.empty());
  EXPECT_GT(run.seconds, 0.0);
}

#ifdef CONTACT2D_WITH_MUJOCO
TEST(Registry, MujocoRunCarriesItsSolverSettings) {
  Scene scene = load_scene(std::string(CONTACT2D_SCENES_DIR) + "/point_mass.toml");
  scene.sim.duration = 0.1;
  const engines::EngineRun run = engines::run_engine("mujoco:exact", scene);
  EXPECT_EQ(run.engine, "mujoco:exact");
  EXPECT_EQ(run.description, "mujoco exact Euler");
  EXPECT_FALSE(run.trajectory.divergence);
  // exact: timeconst = 2m/c, dampratio c/(2√(mk)) (mujoco/mapping.hpp).
  EXPECT_DOUBLE_EQ(run.solref[0], 2.0 * scene.mass / scene.contact.c);
  EXPECT_FALSE(std::isnan(run.impratio));
}

// A geometry without a mapping names itself so that it parses back.
TEST(Registry, GeometryAloneRoundTrips) {
  const engines::EngineSpec spec = engines::parse_engine("mujoco::boxes");
  EXPECT_TRUE(spec.option("mapping").empty());
  EXPECT_EQ(spec.option("geometry"), "boxes");
  EXPECT_EQ(spec.name(), "mujoco::boxes");
}

TEST(Registry, ExplicitEulerIsNotOfferedByMujoco) {
  EXPECT_TRUE(engines::engine_offers("ref", Integrator::ExplicitEuler));
  EXPECT_FALSE(engines::engine_offers("mujoco", Integrator::ExplicitEuler));
  EXPECT_TRUE(engines::engine_offers("mujoco", Integrator::RK4));
}

TEST(IntegratorLabel, SceneNamesWithTheEnginesOwnInParentheses) {
  EXPECT_EQ(engines::integrator_label("ref", Integrator::SemiImplicitEuler), "semi_implicit_euler");
  EXPECT_EQ(engines::integrator_label("mujoco", Integrator::SemiImplicitEuler),
            "semi_implicit_euler (MuJoCo Euler)");
  EXPECT_EQ(engines::integrator_label("mujoco:seed", Integrator::ImplicitEuler),
            "implicit_euler (MuJoCo implicit)");
  EXPECT_EQ(engines::integrator_label("mujoco", Integrator::RK4), "rk4 (MuJoCo RK4)");
  EXPECT_EQ(engines::integrator_label("mujoco", Integrator::ExplicitEuler),
            "explicit_euler");  // none in 2.2
}

// Options are data: every value of every option parses in its place and
// names itself back, and a value outside the list is an error that lists
// the values.
TEST(Registry, OptionsAreDataTheParserFollows) {
  for (const engines::EngineInfo* info : engines::engine_list()) {
    if (info->make == nullptr) continue;
    std::string prefix(info->kind);
    for (const engines::EngineOption& option : info->options) {
      std::string listed;
      for (std::string_view value : option.values) {
        const engines::EngineSpec spec = engines::parse_engine(prefix + ":" + std::string(value));
        EXPECT_EQ(spec.option(option.name), value);
        EXPECT_EQ(spec.name(), prefix + ":" + std::string(value));
        EXPECT_EQ(engines::option_value(spec, option.name), value);
        listed += (listed.empty() ? "" : ", ") + std::string(value);
      }
      EXPECT_EQ(error_of(prefix + ":nonsense"), "--engines " + prefix + ":nonsense: unknown " +
                                                    std::string(option.name) + " (" + listed + ")");
      EXPECT_EQ(engines::option_value(engines::parse_engine(std::string(info->kind)), option.name),
                option.fallback);
      prefix += ":";  // the next option comes after an empty one
    }
  }
}

std::string spelled(std::string_view name) { return "--" + std::string(name); }

std::string with_options_error(const std::string& kind, const engines::OptionValues& given,
                               double model_dt = 0.0) {
  try {
    engines::engine_with_options(kind, given, model_dt, "s.toml", spelled);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Registry, OptionsGivenOneByOneAreCheckedAgainstTheEngine) {
  EXPECT_EQ(with_options_error("ref", {{"mapping", "exact"}}),
            "--mapping exact: not an option of ref (it takes none)");
  EXPECT_EQ(with_options_error("mujoco", {{"mapping", "stiff"}}),
            "--mapping stiff: unknown mapping (seed, exact, calibrated, compensated)");
  EXPECT_EQ(with_options_error("mujoco", {{"solver", "cg"}}),
            "--solver cg: not an option of mujoco");
  EXPECT_EQ(with_options_error("ref", {}, 0.002),
            "--model_dt 0.002: ref has no Δt-dependent model values");
  EXPECT_EQ(with_options_error("ref", {{"mapping", ""}}), "");  // empty: left out
  EXPECT_EQ(with_options_error("mujoco:exact", {{"mapping", "seed"}}),
            "--mapping seed: the engine's name mujoco:exact gives mapping exact already");
  EXPECT_EQ(with_options_error("mujoco:exact", {{"geometry", "boxes"}}), "");
  const engines::EngineSpec spec = engines::engine_with_options(
      "mujoco", {{"geometry", "boxes"}, {"mapping", ""}}, 0.002, "s.toml", spelled);
  EXPECT_EQ(spec.name(), "mujoco::boxes");
  EXPECT_EQ(spec.model_dt, 0.002);
  EXPECT_EQ(spec.source, "s.toml");
  EXPECT_EQ(engines::option_value(spec, "mapping"), "calibrated");  // the fallback
}

TEST(Registry, SetReplacesOrRemovesAnOption) {
  engines::EngineSpec spec = engines::parse_engine("mujoco:exact:boxes");
  spec.set("mapping", "seed");
  EXPECT_EQ(spec.name(), "mujoco:seed:boxes");
  spec.set("geometry", "");
  EXPECT_EQ(spec.name(), "mujoco:seed");
}

TEST(Registry, HelpListsTheNamesFromTheData) {
  EXPECT_EQ(engines::engine_names_help(),
            "ref, mujoco, mujoco:MAPPING (seed, exact, calibrated, compensated; mujoco = its "
            "default), mujoco3, mujoco3:MAPPING (seed, exact, calibrated, compensated; mujoco3 = "
            "its default)");
}

// MuJoCo's implicit integrates contact forces explicitly.
TEST(Registry, ContactIntegrator) {
  EXPECT_EQ(engines::contact_integrator("mujoco", Integrator::ImplicitEuler),
            Integrator::SemiImplicitEuler);
  EXPECT_EQ(engines::contact_integrator("mujoco", Integrator::RK4), Integrator::RK4);
  EXPECT_EQ(engines::contact_integrator("ref", Integrator::ImplicitEuler),
            Integrator::ImplicitEuler);
}
#endif

TEST(Registry, EveryEngineIsListedByKind) {
  EXPECT_EQ(engines::engine_kinds(), (std::vector<std::string>{"ref", "mujoco", "mujoco3"}));
  EXPECT_EQ(error_of("nope"), "--engines nope: unknown engine (use ref, mujoco or mujoco3)");
  EXPECT_EQ(error_of("ref:x"), "--engines ref:x: unknown engine (use ref, mujoco or mujoco3)");
}

}  // namespace
}  // namespace contact2d
