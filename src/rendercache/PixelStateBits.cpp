#include "rendercache/PixelStateBits.h"

#include <emmintrin.h>

namespace raycache {

void pixelStateBits(const PixelState* states, int width, PixelState first, PixelState last, std::uint64_t* bits) {
    static_assert(sizeof(PixelState) == 1);
    const auto low = static_cast<unsigned char>(first),
               span = static_cast<unsigned char>(static_cast<unsigned char>(last) - low);
    const auto* bytes = reinterpret_cast<const unsigned char*>(states);
    const std::size_t words = pixelStateWords(width);
    // Sixteen states at a time (SSE2, every x86-64): state - first <= last - first, unsigned.
    const __m128i lows = _mm_set1_epi8(static_cast<char>(low)), spans = _mm_set1_epi8(static_cast<char>(span));
    const auto sixteen = [&](int x) {
        const __m128i offset = _mm_sub_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(bytes + x)), lows);
        return static_cast<std::uint64_t>(
            static_cast<unsigned>(_mm_movemask_epi8(_mm_cmpeq_epi8(_mm_min_epu8(offset, spans), offset))));
    };
    int x = 0;
    std::size_t w = 0;
    for (; x + 64 <= width; x += 64, ++w)
        bits[w] = sixteen(x) | sixteen(x + 16) << 16 | sixteen(x + 32) << 32 | sixteen(x + 48) << 48;
    for (; w < words; ++w) bits[w] = 0;
    for (; x < width; ++x)
        if (static_cast<unsigned char>(bytes[x] - low) <= span) bits[x / 64] |= std::uint64_t{1} << (x % 64);
}

}  // namespace raycache
