// contact2d — the public header of the reference solver (contact2d::core).
//
// A scene in, a trajectory or a stepper out:
//
//   #include <contact2d/contact2d.hpp>
//   contact2d::Scene scene = contact2d::default_scene(contact2d::Shape::Box);
//   scene.contact.k = 1e5;                               // plain data, SI units
//   if (auto error = contact2d::validate(scene)) { /* error->key, error->range */ }
//   contact2d::Trajectory t = contact2d::simulate(scene);  // samples every sim.output_dt
//   if (t.divergence) { std::string why = contact2d::describe(*t.divergence, scene); }
//
// or step it yourself:
//
//   const contact2d::Model model = contact2d::make_model(scene);
//   contact2d::State s = contact2d::initial_state(scene);
//   contact2d::StepWorkspace ws(model);  // the step's scratch, made once
//   for (int i = 0; i < 1000; ++i)
//     if (contact2d::step(model, contact2d::Integrator::RK4, 1e-4, s, ws) !=
//         contact2d::StepStatus::Ok) break;
//
// Both examples are compiled, as written here, by the install test's
// consumer (tests/consumer/main.cpp). The library does no I/O and allocates
// nothing per step.
#pragma once

#include "core/body.hpp"
#include "core/contact.hpp"
#include "core/divergence.hpp"
#include "core/dynamics.hpp"
#include "core/integrators.hpp"
#include "core/run.hpp"
#include "core/scene.hpp"
#include "core/stepper.hpp"
