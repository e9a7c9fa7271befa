#include "deformable_sim/core/base/cpu_features.h"

namespace deformable_sim::core {

bool hasAvx2Fma() {
#if defined(__x86_64__)
  static const bool has = [] {
    __builtin_cpu_init();  // may run before the constructors that would otherwise do it
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  return has;
#else
  return false;
#endif
}

}  // namespace deformable_sim::core
