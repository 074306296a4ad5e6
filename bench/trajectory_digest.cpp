// contact2d_digest: a fingerprint of every step of the reference solver, to
// check that a change to the core leaves trajectories bit for bit the same.
// The CSV of `contact2d simulate` keeps 9 significant digits; this folds the
// full 64 bits of q and v after every step (and the step status) into one
// FNV-1a hash per scene and integrator, and prints the final state exactly
// (%a), so two builds agree on a line only if every step agreed to the bit.
//
//   build/bench/contact2d_digest SCENE.toml...   (one line per scene × integrator)
//
// docs/speed.md says how to use it (two builds, or the scalar and vector tanh paths).
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>

#include "core/integrators.hpp"
#include "core/run.hpp"
#include "io/scene_file.hpp"

namespace {

using namespace contact2d;

struct Fnv {
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  }
  void add(const Vec3& v) {
    for (int i = 0; i < 3; ++i) {
      const double x = v[i];
      add(&x, sizeof x);
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s SCENE.toml...\n", argv[0]);
    return 2;
  }
  try {
    for (int a = 1; a < argc; ++a) {
      for (Integrator integrator : kAllIntegrators) {
        Scene scene = load_scene(argv[a]);
        scene.sim.integrator = integrator;
        ReferenceStepper stepper(scene);
        const long long steps = step_count(scene.sim);
        Fnv fnv;
        long long taken = 0;
        for (; taken < steps; ++taken) {
          const int status = static_cast<int>(stepper.step());
          fnv.add(&status, sizeof status);
          fnv.add(stepper.state().q);
          fnv.add(stepper.state().v);
          if (status != 0) break;
        }
        const State& s = stepper.state();
        std::printf("%s %s steps %lld digest %016llx q %a %a %a v %a %a %a\n", argv[a],
                    std::string(integrator_name(integrator)).c_str(), taken,
                    static_cast<unsigned long long>(fnv.h), s.q.x(), s.q.y(), s.q.z(), s.v.x(),
                    s.v.y(), s.v.z());
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
