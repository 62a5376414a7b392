// Includes the file RAYCACHE_LANE_KERNELS names (a string, e.g.
// "render/HitLaneKernels.inc") once per x86-64 level, inside namespaces
// avx512 and avx2 under `#pragma GCC target` and baseline without, as
// core/LaneLevels.h explains; with RAYCACHE_BASELINE_LANES the baseline copy
// alone. Include it inside namespace raycache, then call the copies with
// RAYCACHE_LANE_DISPATCH. No include guard: each lane file includes it once.
// Inside, RAYCACHE_LANE_BYTES is the level's vector register width in bytes
// (64, 32, 16), for kernels that work in pieces of that width: GCC lowers a
// 16-lane mask's logic well only where 16 lanes fill one register.
// core/LanePieces.inc, included first in each level, gives such kernels the
// level's Piece, Floats and Mask and its mask helpers (the including file
// includes core/FloatLanes.h). With RAYCACHE_LANE_LEVELS_UP_TO_AVX2 defined
// too, the avx512 copy is left out (call them with
// RAYCACHE_LANE_DISPATCH_UP_TO_AVX2).
#if !defined(RAYCACHE_LANE_KERNELS)
#error "define RAYCACHE_LANE_KERNELS before including core/LaneLevelsInclude.h"
#endif

#if !defined(RAYCACHE_BASELINE_LANES)
#if !defined(RAYCACHE_LANE_LEVELS_UP_TO_AVX2)
#define RAYCACHE_LANE_LEVEL avx512
#define RAYCACHE_LANE_BYTES 64
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v4")
#include "core/LanePieces.inc"
#include RAYCACHE_LANE_KERNELS
#pragma GCC pop_options
#undef RAYCACHE_LANE_BYTES
#undef RAYCACHE_LANE_LEVEL
#endif

#define RAYCACHE_LANE_LEVEL avx2
#define RAYCACHE_LANE_BYTES 32
#pragma GCC push_options
#pragma GCC target("arch=x86-64-v3")
#include "core/LanePieces.inc"
#include RAYCACHE_LANE_KERNELS
#pragma GCC pop_options
#undef RAYCACHE_LANE_BYTES
#undef RAYCACHE_LANE_LEVEL
#endif

#define RAYCACHE_LANE_LEVEL baseline
#define RAYCACHE_LANE_BYTES 16
#include "core/LanePieces.inc"
#include RAYCACHE_LANE_KERNELS
#undef RAYCACHE_LANE_BYTES
#undef RAYCACHE_LANE_LEVEL
#undef RAYCACHE_LANE_KERNELS
#undef RAYCACHE_LANE_LEVELS_UP_TO_AVX2
