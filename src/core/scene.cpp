#include "core/scene.hpp"

#include <algorithm>
#include <cmath>

#include "core/ellipse.hpp"

namespace contact2d {

std::vector<BoxPart> default_tshape_parts() {
  return {BoxPart{0.6, 0.1, 0.0, 0.25, 0.6}, BoxPart{0.1, 0.4, 0.0, 0.0, 0.4}};
}

Scene default_scene(Shape shape) {
  Scene scene;
  scene.shape = shape;
  scene.initial.q = Vec3(0.0, 1.0, 0.0);
  switch (shape) {
    case Shape::PointMass:
    case Shape::Box: break;
    case Shape::TShape: scene.parts = default_tshape_parts(); break;
    case Shape::Circle: scene.initial.q = Vec3(0.0, scene.radius, 0.0); break;
    case Shape::Ellipse: break;
  }
  return scene;
}

namespace {

// Range rules as small predicates so every message has the same form.
std::optional<ValidationError> require(bool ok, double value, std::string key, std::string range) {
  if (ok) return std::nullopt;
  return ValidationError{std::move(key), std::move(range), value};
}

bool positive(double x) { return std::isfinite(x) && x > 0.0; }
bool non_negative(double x) { return std::isfinite(x) && x >= 0.0; }
bool bounded(double x, double limit) { return std::isfinite(x) && std::abs(x) <= limit; }

// The contact law's ranges; `prefix` names its table ("contact." or
// "obstacle[2]." for an obstacle's own keys).
std::optional<ValidationError> validate_contact(const ContactParams& p, const std::string& prefix) {
  const std::optional<ValidationError> checks[] = {
      require(non_negative(p.k) && p.k <= 1e12, p.k, prefix + "k", "must be in [0, 1e12] N/m"),
      require(non_negative(p.c) && p.c <= 1e9, p.c, prefix + "c", "must be in [0, 1e9] N·s/m"),
      require(non_negative(p.mu) && p.mu <= 100, p.mu, prefix + "mu", "must be in [0, 100]"),
      require(positive(p.alpha) && p.alpha <= 1e9, p.alpha, prefix + "alpha",
              "must be in (0, 1e9] s/m"),
      require(non_negative(p.mu_roll) && p.mu_roll <= 10, p.mu_roll, prefix + "mu_roll",
              "must be in [0, 10] m"),
      require(non_negative(p.mu_torsion) && p.mu_torsion <= 10, p.mu_torsion, prefix + "mu_torsion",
              "must be in [0, 10] m"),
      require(positive(p.cone_ratio) && p.cone_ratio <= 1e12, p.cone_ratio, prefix + "cone_ratio",
              "must be in (0, 1e12]"),
  };
  for (const auto& check : checks) {
    if (check) return check;
  }
  return std::nullopt;
}

// Obstacles are stored as corners (box) or ends (segment); the messages name
// the scene file's keys: a box's x, y (centre), width, height; a segment's
// x1, y1, x2, y2, radius.
std::optional<ValidationError> validate_obstacle(const Obstacle& o, const std::string& name) {
  constexpr double kMaxCoord = 1e6;
  const std::string key = name + ".";
  if (o.shape == ObstacleShape::Box) {
    const Vec2 centre = 0.5 * (o.a + o.b);
    const Vec2 size = o.b - o.a;
    const std::optional<ValidationError> checks[] = {
        require(bounded(centre.x(), kMaxCoord), centre.x(), key + "x",
                "must be finite, |x| <= 1e6 m"),
        require(bounded(centre.y(), kMaxCoord), centre.y(), key + "y",
                "must be finite, |y| <= 1e6 m"),
        require(positive(size.x()) && size.x() <= 1e6, size.x(), key + "width",
                "must be in (0, 1e6] m"),
        require(positive(size.y()) && size.y() <= 1e6, size.y(), key + "height",
                "must be in (0, 1e6] m"),
    };
    for (const auto& check : checks) {
      if (check) return check;
    }
    return std::nullopt;
  }
  const std::optional<ValidationError> checks[] = {
      require(bounded(o.a.x(), kMaxCoord), o.a.x(), key + "x1", "must be finite, |x1| <= 1e6 m"),
      require(bounded(o.a.y(), kMaxCoord), o.a.y(), key + "y1", "must be finite, |y1| <= 1e6 m"),
      require(bounded(o.b.x(), kMaxCoord), o.b.x(), key + "x2", "must be finite, |x2| <= 1e6 m"),
      require(bounded(o.b.y(), kMaxCoord), o.b.y(), key + "y2", "must be finite, |y2| <= 1e6 m"),
      require(non_negative(o.radius) && o.radius <= 1e3, o.radius, key + "radius",
              "must be in [0, 1e3] m"),
      require(o.radius > 0.0 || o.a != o.b, o.radius, key + "radius",
              "must be > 0 when the two ends coincide (a segment of no length and no thickness)"),
  };
  for (const auto& check : checks) {
    if (check) return check;
  }
  return std::nullopt;
}

}  // namespace

std::optional<ValidationError> validate(const Scene& s) {
  constexpr double kMaxCoord = 1e6;
  const std::optional<ValidationError> checks[] = {
      require(positive(s.mass) && s.mass <= 1e9, s.mass, "body.mass", "must be in (0, 1e9] kg"),
      require(non_negative(s.half_height) && s.half_height <= 1e3, s.half_height,
              "body.half_height", "must be in [0, 1e3] m"),
      require(positive(s.width) && s.width <= 1e3, s.width, "body.width", "must be in (0, 1e3] m"),
      require(positive(s.height) && s.height <= 1e3, s.height, "body.height",
              "must be in (0, 1e3] m"),
      require(positive(s.radius) && s.radius <= 1e3, s.radius, "body.radius",
              "must be in (0, 1e3] m"),
      require(positive(s.a) && s.a <= 1e3, s.a, "body.a", "must be in (0, 1e3] m"),
      require(positive(s.b) && s.b <= 1e3, s.b, "body.b", "must be in (0, 1e3] m"),
      require(non_negative(s.inertia) && s.inertia <= 1e15, s.inertia, "body.inertia",
              "must be in [0, 1e15] kg·m² (0: a uniform plate's m·(a² + b²)/4)"),
      require(bounded(s.initial.q.x(), kMaxCoord), s.initial.q.x(), "initial.x",
              "must be finite, |x| <= 1e6 m"),
      require(bounded(s.initial.q.y(), kMaxCoord), s.initial.q.y(), "initial.y",
              "must be finite, |y| <= 1e6 m"),
      require(bounded(s.initial.q.z(), 1e3), s.initial.q.z(), "initial.theta",
              "must be finite, |theta| <= 1e3 rad"),
      require(bounded(s.initial.v.x(), kMaxCoord), s.initial.v.x(), "initial.vx",
              "must be finite, |vx| <= 1e6 m/s"),
      require(bounded(s.initial.v.y(), kMaxCoord), s.initial.v.y(), "initial.vy",
              "must be finite, |vy| <= 1e6 m/s"),
      require(bounded(s.initial.v.z(), 1e6), s.initial.v.z(), "initial.omega",
              "must be finite, |omega| <= 1e6 rad/s"),
      require(shape_features(s.shape).turns || (s.initial.q.z() == 0.0 && s.initial.v.z() == 0.0),
              s.initial.q.z(), "initial.theta",
              "must be 0 with omega = 0 for a point_mass (it does not rotate)"),
      require(positive(s.sim.duration) && s.sim.duration <= 1e5, s.sim.duration, "sim.duration",
              "must be in (0, 1e5] s"),
      require(positive(s.sim.dt) && s.sim.dt <= s.sim.duration, s.sim.dt, "sim.dt",
              "must be in (0, sim.duration] s"),
      require(positive(s.sim.output_dt), s.sim.output_dt, "sim.output_dt", "must be > 0 s"),
      require(s.sim.duration / s.sim.dt <= 1e9, s.sim.dt, "sim.dt",
              "must be >= sim.duration / 1e9 (at most 1e9 steps)"),
      // Every sample is kept in memory (a trajectory, 56 bytes each): a
      // sampling of 1e9 took the machine's memory before the first line was
      // written. 1e7 samples are 0.56 GB.
      require(!(positive(s.sim.dt) && positive(s.sim.output_dt) && positive(s.sim.duration) &&
                s.sim.duration / s.sim.dt <= 1e9) ||
                  step_count(s.sim) / sample_stride(s.sim) + 1 <= kMaxSamples,
              s.sim.output_dt, "sim.output_dt",
              "must be >= sim.duration / 1e7 (at most 1e7 samples are kept, 0.56 GB)"),
      require(non_negative(s.sim.gravity) && s.sim.gravity <= 1e4, s.sim.gravity, "sim.gravity",
              "must be in [0, 1e4] m/s²"),
  };
  for (const auto& check : checks) {
    if (check) return check;
  }
  if (shape_features(s.shape).compound) {
    if (s.parts.empty()) return ValidationError{"body.parts", "must list at least one part"};
    // MuJoCo 2.2's mjData holds dense njmax × njmax matrices (efc_AR), and
    // the generated model's njmax grows with the 4 corners of every part
    // (mujoco/mjcf.cpp: nconmax_of, njmax_of): measured, 64 parts take 141 MB
    // and 0.19 s to generate, 128 parts 492 MB, 256 parts 1.9 GB and 2.8 s,
    // and from about 300 parts MuJoCo cannot create the mjData at all.
    if (s.parts.size() > kMaxParts) {
      return ValidationError{"body.parts", "must list 1 to " + std::to_string(kMaxParts) + " parts",
                             static_cast<double>(s.parts.size())};
    }
    for (size_t i = 0; i < s.parts.size(); ++i) {
      const BoxPart& p = s.parts[i];
      const std::string key = "body.parts[" + std::to_string(i) + "].";
      const std::optional<ValidationError> part_checks[] = {
          require(positive(p.width) && p.width <= 1e3, p.width, key + "width",
                  "must be in (0, 1e3] m"),
          require(positive(p.height) && p.height <= 1e3, p.height, key + "height",
                  "must be in (0, 1e3] m"),
          require(positive(p.mass) && p.mass <= 1e9, p.mass, key + "mass",
                  "must be in (0, 1e9] kg"),
          require(bounded(p.x, 1e3), p.x, key + "x", "must be finite, |x| <= 1e3 m"),
          require(bounded(p.y, 1e3), p.y, key + "y", "must be finite, |y| <= 1e3 m"),
      };
      for (const auto& check : part_checks) {
        if (check) return check;
      }
    }
  }
  // Rolling resistance is a circle's or an ellipse's: the dynamics of the
  // others never read μ_roll, and the MJCF would give their contacts a
  // rolling friction the reference does not have (a box's corner spheres
  // then resist the box's turning), so a value there is refused, not dropped.
  const bool rolls = shape_features(s.shape).resists_rolling;
  const auto rolling = [&](const ContactParams& p, const std::string& prefix) {
    return require(rolls || p.mu_roll == 0.0, p.mu_roll, prefix + "mu_roll",
                   "must be 0 for a " + std::string(shape_name(s.shape)) +
                       " (rolling resistance acts on a circle or an ellipse)");
  };
  if (auto error = validate_contact(s.contact, "contact.")) return error;
  if (auto error = rolling(s.contact, "contact.")) return error;
  for (size_t i = 0; i < s.obstacles.size(); ++i) {
    const std::string name = "obstacle[" + std::to_string(i) + "]";
    if (auto error = validate_obstacle(s.obstacles[i], name)) return error;
    const ContactParams law = s.obstacles[i].contact.apply(s.contact);
    if (auto error = validate_contact(law, name + ".")) return error;
    if (auto error = rolling(law, name + ".")) return error;
  }
  return std::nullopt;
}

RigidBody make_body(const Scene& s) {
  switch (s.shape) {
    case Shape::PointMass: return make_point_mass(s.mass, s.half_height);
    case Shape::Box: return make_box(s.mass, s.width, s.height);
    case Shape::TShape: return make_compound(s.parts.empty() ? default_tshape_parts() : s.parts);
    case Shape::Circle: return make_circle(s.mass, s.radius);
    case Shape::Ellipse:
      return make_ellipse(s.mass, s.a, s.b,
                          s.inertia > 0.0 ? s.inertia : ellipse_plate_inertia(s.mass, s.a, s.b));
  }
  return {};
}

Model make_model(const Scene& s) {
  Model model;
  model.body = make_body(s);
  model.contact = s.contact;
  model.gravity = s.sim.gravity;
  model.obstacles = s.obstacles;
  for (const Obstacle& o : s.obstacles) model.obstacle_laws.push_back(o.contact.apply(s.contact));
  return model;
}

long long step_count(const SimParams& sim) { return std::llround(sim.duration / sim.dt); }

long long sample_stride(const SimParams& sim) {
  // A stride of the run's steps or more samples only t = 0 and the end, so
  // it is clamped there: llround's result is unspecified beyond long long's
  // range (output_dt above ~9.2e18·dt sampled every step).
  const double ratio = sim.output_dt / sim.dt;
  const long long steps = step_count(sim);
  if (!(ratio < static_cast<double>(steps))) return std::max(steps, 1LL);
  const long long stride = std::llround(ratio);
  return stride < 1 ? 1 : stride;
}

}  // namespace contact2d
