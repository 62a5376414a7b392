#pragma once
// Four doubles computed together, for code a profile showed to be scalar
// arithmetic repeated ray after ray (trace/grids: a ray's cells). GCC's
// generic vectors: one AVX2 instruction per operation in a function compiled
// for x86-64-v3, two SSE2 ones otherwise. Every operation is the IEEE
// operation of the scalar code, lane by lane, so each lane's result is bit
// for bit the scalar one (-ffp-contract=off keeps a * b + c from becoming a
// fused multiply-add; cmake/Warnings.cmake).
//
// Used only inside functions that are always inlined: passed by value
// between functions compiled for different targets, 32-byte vectors would
// change the calling convention.

namespace raycache {

using DoubleLanes = double __attribute__((vector_size(32)));
// A comparison's result: all bits set in the lanes where it holds, 0 elsewhere.
using LaneMask = decltype(DoubleLanes{} < DoubleLanes{});

inline constexpr int kDoubleLanes = 4;

// GCC notes that returning a 32-byte vector without AVX changes the ABI;
// these helpers are always inlined, so no call ever passes one.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

// std::max(a, b) lane by lane, with its rule: a unless a < b (so a NaN in a stays).
[[gnu::always_inline]] inline DoubleLanes laneMax(DoubleLanes a, DoubleLanes b) { return a < b ? b : a; }
// std::min(a, b) lane by lane: a unless b < a.
[[gnu::always_inline]] inline DoubleLanes laneMin(DoubleLanes a, DoubleLanes b) { return b < a ? b : a; }
// std::isfinite lane by lane: v - v is 0 for finite v, NaN for infinities and NaN.
[[gnu::always_inline]] inline LaneMask laneFinite(DoubleLanes v) { return (v - v) == 0.0; }
#pragma GCC diagnostic pop

}  // namespace raycache
