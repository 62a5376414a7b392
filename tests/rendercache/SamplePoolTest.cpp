// SamplePool::reset(): every pixel slot empty and fresh, on one thread or
// several, and an overflow slot fresh when it is taken, whatever its memory
// held before.
#include <gtest/gtest.h>

#include "core/Parallel.h"
#include "rendercache/SamplePool.h"

using namespace raycache;

namespace {

void expectFresh(const SamplePool& pool, std::size_t slot) {
    EXPECT_TRUE(pool.empty(slot)) << slot;
    EXPECT_EQ(pool.point[slot], SamplePoint{}) << slot;
    EXPECT_EQ(pool.look[slot], SampleLook{}) << slot;
    EXPECT_EQ(pool.reshade[slot], ReshadeInputs{}) << slot;
    EXPECT_EQ(pool.texturing[slot], SampleTexturing{}) << slot;
}

// Every record of `slot` written with values no fresh record has.
void scribble(SamplePool& pool, std::size_t slot) {
    pool.point[slot] = {Vec3{1, 2, 3}, 5};
    pool.look[slot] = {Rgb{1, 1, 1}, 9, kViewDependent, 1};
    pool.reshade[slot] = {4, 0.5f, 0.25f, Rgb{1, 0, 0}, 3};
    pool.texturing[slot] = {Rgb{0, 1, 0}, Rgb{0, 0, 1}, 8};
}

}  // namespace

TEST(SamplePool, ResetEmptiesEveryPixelSlotOnAnyThreadCount) {
    // More slots than one chunk of the parallel reset, and not a multiple of it.
    constexpr std::size_t kSlots = (std::size_t{1} << 17) + 123;
    for (const int threads : {0, 1, 2}) {
        SamplePool pool;
        pool.reset(kSlots, 10);
        for (std::size_t slot = 0; slot < kSlots; slot += 997) scribble(pool, slot);
        const Parallel parallel(threads == 0 ? 1 : threads);
        pool.reset(kSlots, 10, threads == 0 ? nullptr : &parallel);
        EXPECT_EQ(pool.capacity(), kSlots + 10);
        EXPECT_EQ(pool.used(), kSlots);
        for (std::size_t slot = 0; slot < kSlots; ++slot) {
            expectFresh(pool, slot);
            if (::testing::Test::HasFailure()) return;
        }
    }
}

TEST(SamplePool, AnOverflowSlotIsFreshWhenTakenAndTheLastOneTakenIsTheLast) {
    SamplePool pool;
    pool.reset(4, 3);
    // Memory that held samples before (the slot taken, written, and the pool
    // emptied by hand, as reprojection empties it every frame).
    const std::size_t first = pool.takeOverflowSlot();
    EXPECT_EQ(first, 4u);
    scribble(pool, first);
    pool.overflowUsed = 0;
    EXPECT_EQ(pool.takeOverflowSlot(), first);
    expectFresh(pool, first);
    EXPECT_EQ(pool.takeOverflowSlot(), 5u);
    EXPECT_EQ(pool.takeOverflowSlot(), 6u);
    EXPECT_EQ(pool.used(), pool.capacity());
    EXPECT_THROW(pool.takeOverflowSlot(), std::exception);
}
