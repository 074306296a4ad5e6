// The model's queries over its contact laws (core/model.hpp).
#include "core/model.hpp"

#include <algorithm>

namespace contact2d {

bool Model::uses_cone_law() const {
  if (contact.friction != FrictionLaw::Tanh) return true;
  for (const ContactParams& p : obstacle_laws)
    if (p.friction != FrictionLaw::Tanh) return true;
  return false;
}

double Model::min_k() const {
  double k = contact.k;
  for (const ContactParams& p : obstacle_laws) k = std::min(k, p.k);
  return k;
}

double Model::max_k() const {
  double k = contact.k;
  for (const ContactParams& p : obstacle_laws) k = std::max(k, p.k);
  return k;
}

}  // namespace contact2d
