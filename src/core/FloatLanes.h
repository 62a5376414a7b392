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
// calling convention of the baseline copies).
#include <type_traits>

namespace raycache {

inline constexpr int kFloatLanes = 16;
using FloatLanes = float __attribute__((vector_size(64)));
// A comparison's result: all bits set in the lanes where it holds, 0 elsewhere.
using FloatMask = decltype(FloatLanes{} < FloatLanes{});

// Sixteen ints, the type of a comparison's result (FloatMask).
using IntLanes16 = FloatMask;

[[gnu::always_inline]] inline void loadLanes(const int* from, IntLanes16& to) { __builtin_memcpy(&to, from, sizeof to); }
[[gnu::always_inline]] inline void storeLanes(const IntLanes16& from, int* to) { __builtin_memcpy(to, &from, sizeof from); }
[[gnu::always_inline]] inline void loadLanes(const float* from, FloatLanes& to) {
    __builtin_memcpy(&to, from, sizeof to);
}
[[gnu::always_inline]] inline void storeLanes(const FloatLanes& from, float* to) {
    __builtin_memcpy(to, &from, sizeof from);
}

// Floats in a vector `Bytes` wide (16, 32 or 64): a piece of the sixteen
// lanes as wide as one register of a level (core/LaneLevelsInclude.h's
// RAYCACHE_LANE_BYTES). GCC 12 lowers a 16-lane mask's logic (compares,
// &, |, ~, ?:) into one scalar compare per lane where sixteen floats do not
// fill one register, so a lane kernel compiled for AVX2 or baseline x86-64
// works on its lanes in such pieces (LanePiece). FloatVector<64> is FloatLanes.
// (A struct's member aliases: GCC drops vector_size from an alias template.)
template <int Bytes>
struct FloatVectorOf {
    using Type [[gnu::vector_size(Bytes)]] = float;
    using Mask [[gnu::vector_size(Bytes)]] = int;  // what a comparison of two Types gives
};
template <int Bytes>
using FloatVector = typename FloatVectorOf<Bytes>::Type;
// A comparison's result on a FloatVector<Bytes>: ints, all bits set where it holds.
template <int Bytes>
using MaskVector = typename FloatVectorOf<Bytes>::Mask;
static_assert(std::is_same_v<FloatVector<64>, FloatLanes> && std::is_same_v<MaskVector<64>, FloatMask>);
static_assert(std::is_same_v<decltype(FloatVector<32>{} < FloatVector<32>{}), MaskVector<32>>);
// FloatLanes or FloatMask, or a piece of them: the helpers below take any of these.
template <class Floats>
concept FloatLaneVector = std::is_same_v<Floats, FloatVector<static_cast<int>(sizeof(Floats))>>;
template <class Mask>
concept LaneMaskVector = std::is_same_v<Mask, MaskVector<static_cast<int>(sizeof(Mask))>>;

// Whether any lane of `mask` is set.
template <LaneMaskVector Mask>
[[gnu::always_inline]] inline bool anyLane(const Mask& mask) {
    constexpr int kWords = static_cast<int>(sizeof(Mask) / 8);
    unsigned long long words[kWords];
    __builtin_memcpy(words, &mask, sizeof words);
    unsigned long long any = 0;
    for (int i = 0; i < kWords; ++i) any |= words[i];
    return any != 0;
}
// r = std::fabs(a) lane by lane: the sign bit cleared.
template <FloatLaneVector Floats>
[[gnu::always_inline]] inline void absLanes(const Floats& a, Floats& r) {
    using Bits = decltype(a < a);
    Bits bits;
    __builtin_memcpy(&bits, &a, sizeof bits);
    bits &= 0x7fffffff;
    __builtin_memcpy(&r, &bits, sizeof r);
}
// r = std::sqrt(a) lane by lane (IEEE square root, correctly rounded). GCC
// makes it one vector instruction only where errno is not set by sqrt: the
// files that use it are compiled with -fno-math-errno (src/CMakeLists.txt).
template <FloatLaneVector Floats>
[[gnu::always_inline]] inline void sqrtLanes(const Floats& a, Floats& r) {
    for (int k = 0; k < static_cast<int>(sizeof(Floats) / sizeof(float)); ++k) r[k] = __builtin_sqrtf(a[k]);
}

template <int Bytes>
struct LanePieces;

// Lanes [base, base + kLanes) of the sixteen, as one vector `Bytes` wide. A
// lane kernel loops `for (const LanePiece<Bytes> piece : LanePiece<Bytes>::all())`
// and loads, computes and stores one piece at a time: each lane goes
// through the same IEEE operations as in a sixteen-lane vector, so it gets
// the same bits. With Bytes = 64 the one piece is all sixteen lanes, and
// the loop goes away. Helpers that make or apply masks live in
// core/LanePieces.inc, compiled for each level: a comparison written in a
// function compiled for baseline x86-64 (as this header's are) stays one
// scalar compare per lane even when inlined into AVX-512 code.
template <int Bytes>
struct LanePiece {
    static_assert(Bytes == 16 || Bytes == 32 || Bytes == 64);
    static constexpr int kLanes = Bytes / static_cast<int>(sizeof(float));
    using Floats = FloatVector<Bytes>;
    // A comparison's result, or ints: all bits set where it holds, 0 elsewhere.
    using Mask = MaskVector<Bytes>;

    int base;

    // The pieces that hold the sixteen lanes, or lanes [0, count), in order.
    [[gnu::always_inline]] static LanePieces<Bytes> all() { return {kFloatLanes}; }
    [[gnu::always_inline]] static LanePieces<Bytes> holding(int count) {
        return {count < kFloatLanes ? count : kFloatLanes};  // at most sixteen: one AVX-512 piece, no loop
    }

    // How many of the lanes [0, count) this piece holds.
    [[gnu::always_inline]] int lanesBelow(int count) const { return count - base < kLanes ? count - base : kLanes; }
    [[gnu::always_inline]] void load(const float* lanes, Floats& to) const {
        __builtin_memcpy(&to, lanes + base, sizeof to);
    }
    [[gnu::always_inline]] void load(const int* lanes, Mask& to) const {
        __builtin_memcpy(&to, lanes + base, sizeof to);
    }
    [[gnu::always_inline]] void store(const Floats& from, float* lanes) const {
        __builtin_memcpy(lanes + base, &from, sizeof from);
    }
    [[gnu::always_inline]] void store(const Mask& from, int* lanes) const {
        __builtin_memcpy(lanes + base, &from, sizeof from);
    }
};

// LanePiece::all's and holding's range.
template <int Bytes>
struct LanePieces {
    struct Iterator {
        int base;
        [[gnu::always_inline]] LanePiece<Bytes> operator*() const { return {base}; }
        [[gnu::always_inline]] Iterator& operator++() {
            base += LanePiece<Bytes>::kLanes;
            return *this;
        }
        [[gnu::always_inline]] bool operator!=(const Iterator& end) const { return base < end.base; }
    };
    int count;
    [[gnu::always_inline]] Iterator begin() const { return {0}; }
    [[gnu::always_inline]] Iterator end() const { return {count}; }
};

}  // namespace raycache
