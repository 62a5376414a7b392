// PointImage: the nearest offer wins a pixel whatever the order or thread,
// equal depths go to the lower slot.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <thread>
#include <vector>

#include "rendercache/PointImage.h"

using namespace raycache;

namespace {

struct Offer {
    float depth;
    std::uint32_t slot;
};

}  // namespace

TEST(PointImage, NearestOfferWinsInEveryOrderAndEqualDepthsGoToTheLowerSlot) {
    std::array<Offer, 5> offers{{{3.0f, 7}, {1.5f, 9}, {2.0f, 1}, {1.5f, 4}, {1.5000001f, 0}}};
    std::sort(offers.begin(), offers.end(), [](const Offer& a, const Offer& b) { return a.slot < b.slot; });
    int permutations = 0;
    do {
        PointImage image;
        image.reset(4, 3, 1);
        for (const Offer& o : offers) image.offer(2, 1, o.depth, o.slot);
        ASSERT_TRUE(image.hasSample(2, 1));
        ASSERT_EQ(image.slotAt(2, 1), 4u) << "depth 1.5 twice: slot 4 before slot 9";
        ASSERT_EQ(image.depthAt(2, 1), 1.5f);
        ++permutations;
    } while (std::next_permutation(offers.begin(), offers.end(),
                                   [](const Offer& a, const Offer& b) { return a.slot < b.slot; }));
    EXPECT_EQ(permutations, 120);
}

TEST(PointImage, OffersFromTwoThreadsLeaveTheSameImageAsOneThread) {
    constexpr int kWidth = 16, kHeight = 8, kMargin = 2;
    // Many offers per pixel, depths with ties, in an order that differs per thread.
    std::vector<std::array<int, 2>> where;
    std::vector<Offer> offers;
    for (std::uint32_t slot = 0; slot < 20000; ++slot) {
        const std::uint32_t h = slot * 2654435761u;
        where.push_back({static_cast<int>(h % (kWidth + 2 * kMargin)) - kMargin,
                         static_cast<int>((h >> 8) % (kHeight + 2 * kMargin)) - kMargin});
        offers.push_back({1.0f + static_cast<float>((h >> 16) % 13), slot});
    }
    PointImage reference;
    reference.reset(kWidth, kHeight, kMargin);
    for (std::size_t i = offers.size(); i-- > 0;)
        reference.offer(where[i][0], where[i][1], offers[i].depth, offers[i].slot);
    for (int round = 0; round < 20; ++round) {
        PointImage image;
        image.reset(kWidth, kHeight, kMargin);
        const auto run = [&](std::size_t begin, std::size_t step) {
            for (std::size_t i = begin; i < offers.size(); i += step)
                image.offer(where[i][0], where[i][1], offers[i].depth, offers[i].slot);
        };
        std::thread a(run, 0, 2), b(run, 1, 2);
        a.join();
        b.join();
        for (int y = -kMargin; y < kHeight + kMargin; ++y)
            for (int x = -kMargin; x < kWidth + kMargin; ++x)
                ASSERT_EQ(image.keyAt(x, y), reference.keyAt(x, y)) << x << "," << y;
    }
    // The oracle: the nearest depth offered to each pixel, the lowest slot among those.
    for (int y = -kMargin; y < kHeight + kMargin; ++y)
        for (int x = -kMargin; x < kWidth + kMargin; ++x) {
            float best = 1e30f;
            std::uint32_t bestSlot = 0;
            for (std::size_t i = 0; i < offers.size(); ++i)
                if (where[i][0] == x && where[i][1] == y &&
                    (offers[i].depth < best || (offers[i].depth == best && offers[i].slot < bestSlot))) {
                    best = offers[i].depth;
                    bestSlot = offers[i].slot;
                }
            ASSERT_TRUE(reference.hasSample(x, y));
            ASSERT_EQ(reference.depthAt(x, y), best);
            ASSERT_EQ(reference.slotAt(x, y), bestSlot);
        }
}

TEST(PointImage, PlaceOverridesClearEmptiesAndCoversIncludesTheMargin) {
    PointImage image;
    image.reset(5, 3, 2);
    EXPECT_EQ(image.width(), 5);
    EXPECT_EQ(image.height(), 3);
    EXPECT_EQ(image.margin(), 2);
    EXPECT_FALSE(image.hasSample(0, 0));
    EXPECT_EQ(image.keyAt(0, 0), PointImage::emptyKey());
    image.offer(1, 1, 2.0f, 3);
    image.place(1, 1, 9.0f, 5);  // farther, but placed unconditionally
    EXPECT_EQ(image.slotAt(1, 1), 5u);
    EXPECT_EQ(image.depthAt(1, 1), 9.0f);
    image.offer(1, 1, 10.0f, 0);
    EXPECT_EQ(image.slotAt(1, 1), 5u) << "a farther offer loses to a placed sample";
    image.clear(1, 1);
    EXPECT_FALSE(image.hasSample(1, 1));
    image.offer(-2, -2, 1.0f, 8);
    image.offer(6, 4, 1.0f, 9);
    EXPECT_EQ(image.slotAt(-2, -2), 8u);
    EXPECT_EQ(image.slotAt(6, 4), 9u);
    EXPECT_FALSE(image.hasSample(4, 2)) << "margin corners do not alias image pixels";
    // covers(): [-margin, width + margin) x [-margin, height + margin).
    EXPECT_TRUE(image.covers(-2, -2));
    EXPECT_TRUE(image.covers(6, 4));
    EXPECT_FALSE(image.covers(-3, 0));
    EXPECT_FALSE(image.covers(0, -3));
    EXPECT_FALSE(image.covers(7, 0));
    EXPECT_FALSE(image.covers(0, 5));
    // nearerThan(d): every key of a depth below d, none at d.
    image.offer(0, 0, 4.0f, 0xfffffffeu);
    EXPECT_LE(image.keyAt(0, 0), PointImage::nearerThan(4.0000005f));
    EXPECT_GT(image.keyAt(0, 0), PointImage::nearerThan(4.0f));
}
