// What the processor can do beyond the x86-64 baseline the library is compiled for, checked once
// at run time: the hot loops that gain from it have a second version compiled for it.
#pragma once

namespace deformable_sim::core {

/// True on an x86-64 processor with AVX2 and FMA (false elsewhere).
bool hasAvx2Fma();

}  // namespace deformable_sim::core
