// UninitializedAllocator: resize() leaves new elements as the memory holds
// them, explicit values are written, and blocks of a huge page or more
// start on a huge page (where the kernel can back them with one).
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/UninitializedAllocator.h"

using namespace raycache;

namespace {
struct Record {
    int value = -1;
    float weight = 2.0f;
};
template <typename T>
using Records = std::vector<T, UninitializedAllocator<T>>;
}  // namespace

TEST(UninitializedAllocator, ExplicitValuesAreWrittenAndCopiesAreExact) {
    Records<Record> records(5, Record{7, 0.5f});
    for (const Record& r : records) {
        EXPECT_EQ(r.value, 7);
        EXPECT_EQ(r.weight, 0.5f);
    }
    records.push_back(Record{});
    EXPECT_EQ(records.back().value, -1);
    const Records<Record> copy = records;
    ASSERT_EQ(copy.size(), records.size());
    for (std::size_t i = 0; i < copy.size(); ++i) EXPECT_EQ(copy[i].value, records[i].value);
}

TEST(UninitializedAllocator, ResizeKeepsWhatTheElementsHeldAndWritesNoNewOne) {
    Records<std::uint32_t> words;
    words.reserve(64);
    words.resize(64);
    for (std::uint32_t& w : words) w = 0xdeadbeefu;
    words.resize(8);
    // Growing again within the capacity: the memory is reused as it is,
    // where std::vector's own allocator would have written zeros.
    words.resize(64);
    EXPECT_EQ(words[63], 0xdeadbeefu);
    EXPECT_EQ(words[8], 0xdeadbeefu);
}

TEST(UninitializedAllocator, BlocksOfAHugePageOrMoreStartOnAHugePage) {
    constexpr std::size_t kHugePage = std::size_t{2} << 20;
    const Records<std::uint8_t> large(kHugePage + 1, 1);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(large.data()) % kHugePage, 0u);
    EXPECT_EQ(large.back(), 1);
    const Records<std::uint8_t> small(100, 3);
    EXPECT_EQ(small.front(), 3);
}
