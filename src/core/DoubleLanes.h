#pragma once
// Four doubles computed together, for code a profile showed to be scalar
// arithmetic repeated ray after ray (trace/grids: a ray's cells). GCC's
// generic vectors: one AVX2 instruction per operation in a function compiled
// for x86-64-v3, two SSE2 ones otherwise. Every operation is the IEEE
// operation of the scalar code, lane by lane, so each lane's result is bit
// for bit the scalar one (-ffp-contract=off keeps a * b + c from becoming a
// fused multiply-add; cmake/Warnings.cmake).

namespace raycache {

using DoubleLanes = double __attribute__((vector_size(32)));
// A comparison's result: all bits set in the lanes where it holds, 0 elsewhere.
using LaneMask = decltype(DoubleLanes{} < DoubleLanes{});

inline constexpr int kDoubleLanes = 4;

// Four ints, one per lane of a DoubleLanes (a cell index per lane):
// __builtin_convertvector turns a DoubleLanes into them, truncating as
// static_cast<int> does, and a LaneMask into lanes of 0 or -1.
using IntLanes = int __attribute__((vector_size(16)));

// The helpers work in place, through references: a 32-byte vector passed
// or returned by value changes the calling convention of a function compiled
// without AVX (the baseline copies), which clang refuses even for a function
// that is always inlined.

// a = std::max(a, b) lane by lane, with its rule: a unless a < b (so a NaN in a stays).
[[gnu::always_inline]] inline void keepMax(DoubleLanes& a, const DoubleLanes& b) { a = a < b ? b : a; }
// a = std::min(a, b) lane by lane: a unless b < a.
[[gnu::always_inline]] inline void keepMin(DoubleLanes& a, const DoubleLanes& b) { a = b < a ? b : a; }
// Which lanes of v are finite (std::isfinite): v - v is 0 for finite v, NaN for infinities and NaN.
[[gnu::always_inline]] inline void markFinite(const DoubleLanes& v, LaneMask& finite) { finite = (v - v) == 0.0; }

}  // namespace raycache
