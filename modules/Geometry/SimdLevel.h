#ifndef bender_SimdLevel_h
#define bender_SimdLevel_h

namespace bender
{

/// The instruction sets the vectorised kernels (FastWarpKernel, ExactWarpKernel, the batched
/// projection and binding) are compiled for; the best one the CPU supports is chosen at run time
/// (the build itself targets the portable baseline). FastWarpKernel::Supports and BestLevel
/// tell which are available.
enum class SimdLevel
{
  Baseline, ///< the build's own flags (SSE2 on x86-64)
  Avx2,     ///< AVX2 with FMA
  Avx512    ///< AVX-512 F/VL/DQ/BW
};

} // namespace bender

#endif
