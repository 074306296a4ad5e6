#include "game/keeper.hpp"

#include <algorithm>

namespace contact2d::game {

double keeper_target(const KeeperRule& rule, const State& ball) {
  const double x = ball.q.x(), y = ball.q.y();
  const double vx = rule.direction * ball.v.x();          // towards the goal
  const double gap = rule.direction * (rule.face_x - x);  // centre to face
  double height = y;
  if (vx > 0.0 && gap > 0.0) {
    const double t = gap / vx;
    height = std::max(rule.radius, y + ball.v.y() * t - 0.5 * rule.gravity * t * t);
  }
  return std::clamp(height - rule.centre_y, 0.0, rule.max_offset);
}

double keeper_step(const KeeperRule& rule, double offset, const State& ball, double dt) {
  const double most = rule.speed * dt;
  return offset + std::clamp(keeper_target(rule, ball) - offset, -most, most);
}

}  // namespace contact2d::game
