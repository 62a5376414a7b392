#pragma once
// Sixteen floats computed together: the width of Embree's ray packets on
// this project's machines (trace/TraceScene.cpp) and of the tile kernel's
// hit batches. GCC's generic vectors: one AVX-512 instruction per operation
// in a function compiled for x86-64-v4, two AVX2 ones for x86-64-v3, four
// SSE2 ones otherwise. Every operation is the IEEE operation of the scalar
// code, lane by lane (-ffp-contract=off keeps a * b + c from becoming a fused
// multiply-add; cmake/Warnings.cmake), so each lane's result is bit for bit
// the scalar one on every target.
//
// The helpers work in place, through references, for the reason
// core/DoubleLanes.h gives (a 64-byte vector passed by value changes the
// calling convention of the baseline clones).

namespace raycache {

inline constexpr int kFloatLanes = 16;
using FloatLanes = float __attribute__((vector_size(64)));
// A comparison's result: all bits set in the lanes where it holds, 0 elsewhere.
using FloatMask = decltype(FloatLanes{} < FloatLanes{});

// Sixteen ints, the type of a comparison's result (FloatMask).
using IntLanes16 = FloatMask;

[[gnu::always_inline]] inline void loadLanes(const int* from, IntLanes16& to) { __builtin_memcpy(&to, from, sizeof to); }
[[gnu::always_inline]] inline void storeLanes(const IntLanes16& from, int* to) { __builtin_memcpy(to, &from, sizeof from); }
// Whether any lane of `mask` is set.
[[gnu::always_inline]] inline bool anyLane(const FloatMask& mask) {
    unsigned long long words[8];
    __builtin_memcpy(words, &mask, sizeof words);
    return (words[0] | words[1] | words[2] | words[3] | words[4] | words[5] | words[6] | words[7]) != 0;
}
[[gnu::always_inline]] inline void loadLanes(const float* from, FloatLanes& to) {
    __builtin_memcpy(&to, from, sizeof to);
}
[[gnu::always_inline]] inline void storeLanes(const FloatLanes& from, float* to) {
    __builtin_memcpy(to, &from, sizeof from);
}
// r = std::fabs(a) lane by lane: the sign bit cleared.
[[gnu::always_inline]] inline void absLanes(const FloatLanes& a, FloatLanes& r) {
    using Bits = unsigned __attribute__((vector_size(64)));
    Bits bits;
    __builtin_memcpy(&bits, &a, sizeof bits);
    bits &= 0x7fffffffu;
    __builtin_memcpy(&r, &bits, sizeof r);
}
// r = std::sqrt(a) lane by lane (IEEE square root, correctly rounded). GCC
// makes it one vector instruction only where errno is not set by sqrt: the
// files that use it are compiled with -fno-math-errno (src/CMakeLists.txt).
[[gnu::always_inline]] inline void sqrtLanes(const FloatLanes& a, FloatLanes& r) {
    for (int k = 0; k < kFloatLanes; ++k) r[k] = __builtin_sqrtf(a[k]);
}

}  // namespace raycache
