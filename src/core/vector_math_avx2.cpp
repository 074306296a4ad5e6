// The one translation unit compiled with -mavx2 (CMakeLists.txt): four tanh
// through SLEEF. Nothing else lives here, so no AVX2 instruction can reach
// code that runs before the CPU check in core/vector_math.cpp.
#include <immintrin.h>
#include <sleef.h>

namespace contact2d::detail {

void sleef_tanh4(const double* in, double* out) {
  _mm256_storeu_pd(out, Sleef_tanhd4_u10avx2(_mm256_loadu_pd(in)));
}

}  // namespace contact2d::detail
