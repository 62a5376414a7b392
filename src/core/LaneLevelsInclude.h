// Includes the file RAYCACHE_LANE_KERNELS names (a string, e.g.
// "render/HitLaneKernels.inc") once per x86-64 level, inside namespaces
// avx512 and avx2 under `#pragma GCC target` and baseline without, as
// core/LaneLevels.h explains; with RAYCACHE_BASELINE_LANES the baseline copy
// alone. Include it inside namespace raycache, then call the copies with
// RAYCACHE_LANE_DISPATCH. No include guard: each lane file includes it once.
#if !defined(RAYCACHE_LANE_KERNELS)
#error "define RAYCACHE_LANE_KERNELS before including core/LaneLevelsInclude.h"
#endif

#if !defined(RAYCACHE_BASELINE_LANES)
#define RAYCACHE_LANE_LEVEL avx512
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
#include RAYCACHE_LANE_KERNELS
#pragma GCC pop_options
#undef RAYCACHE_LANE_LEVEL

#define RAYCACHE_LANE_LEVEL avx2
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v3")
#include RAYCACHE_LANE_KERNELS
#pragma GCC pop_options
#undef RAYCACHE_LANE_LEVEL
#endif

#define RAYCACHE_LANE_LEVEL baseline
#include RAYCACHE_LANE_KERNELS
#undef RAYCACHE_LANE_LEVEL
#undef RAYCACHE_LANE_KERNELS
