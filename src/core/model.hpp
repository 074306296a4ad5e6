// The data every stage reads (MuJoCo's mjModel/mjData at the ground): the
// state of the body, the model it moves in, and one contact as the
// position stage finds it. Nothing here computes; the stages above it do:
//
//   core/contacts.hpp    position stage: find_contacts fills a ContactSet
//   core/dynamics.hpp    force stage: acceleration, energy
//   core/integrators.hpp the step
#pragma once

#include <vector>

#include "core/body.hpp"
#include "core/contact.hpp"
#include "core/obstacles.hpp"

namespace contact2d {

struct State {
  Vec3 q = Vec3::Zero();  // x, y, θ
  Vec3 v = Vec3::Zero();  // vx, vy, ω
};

// Plain doubles, read and written one at a time: as two-lane vectors they
// were stored in halves and loaded whole (or the reverse) between the two
// stages, which the CPU cannot forward from its store buffer — a stall that
// cost 10–15 ns a step.
struct Contact {
  double depth = 0.0;         // penetration d > 0, m
  double nx = 0.0, ny = 1.0;  // unit normal out of the touched surface
  double rx = 0.0, ry = 0.0;  // lever arm: contact point − COM, world frame
  int obstacle = -1;          // index of the obstacle touched; −1: the ground
  Vec2 normal() const { return {nx, ny}; }
  Vec2 r() const { return {rx, ry}; }
};

struct Model {
  RigidBody body;
  ContactParams contact;
  double gravity = 9.81;
  Vec3 applied = Vec3::Zero();      // external (Fx, Fy, τ), e.g. from a player
  std::vector<Obstacle> obstacles;  // static geometry
  // The law of each obstacle (its ContactOverride applied to `contact`);
  // an obstacle without an entry uses `contact`. make_model fills it.
  std::vector<ContactParams> obstacle_laws;

  // The law a contact is computed with.
  const ContactParams& law(const Contact& c) const {
    return c.obstacle >= 0 && static_cast<size_t>(c.obstacle) < obstacle_laws.size()
               ? obstacle_laws[static_cast<size_t>(c.obstacle)]
               : contact;
  }
  // Smallest and largest k of the ground's and the obstacles' laws.
  double min_k() const;
  double max_k() const;
  // Whether any contact law uses a cone friction law (core/contact.hpp).
  bool uses_cone_law() const;
};

}  // namespace contact2d
