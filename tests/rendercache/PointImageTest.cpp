// PointImage: the depth test keeps the nearest offer whatever the order and
// leaves ties to its caller; place, clear and the margin.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

#include "rendercache/PointImage.h"

using namespace raycache;

TEST(PointImage, NearestOfferWinsInEveryOrderAndAnEqualDepthDoesNotDisplaceTheHolder) {
    std::array<float, 5> depths{3.0f, 1.5f, 2.0f, 1.5f, 1.5000001f};
    std::sort(depths.begin(), depths.end());
    int permutations = 0;
    do {
        PointImage image;
        image.reset(4, 3, 1);
        int wins = 0;
        for (float d : depths) {
            std::uint32_t held;
            const bool won = image.offerUnshared(2, 1, PointImage::key(d), held);
            ASSERT_EQ(won, PointImage::key(d) < held);
            wins += won ? 1 : 0;
        }
        ASSERT_TRUE(image.hasSample(2, 1));
        ASSERT_EQ(image.depthAt(2, 1), 1.5f);
        ASSERT_GE(wins, 1);
        ++permutations;
    } while (std::next_permutation(depths.begin(), depths.end()));
    EXPECT_EQ(permutations, 60);  // 5! / 2! (two equal depths)
    PointImage image;
    image.reset(4, 3, 1);
    std::uint32_t held;
    EXPECT_TRUE(image.offerUnshared(0, 0, PointImage::key(2.0f), held));
    EXPECT_EQ(held, PointImage::emptyKey());
    EXPECT_FALSE(image.offerUnshared(0, 0, PointImage::key(2.0f), held)) << "a tie is the caller's to break";
    EXPECT_EQ(held, PointImage::key(2.0f));
    EXPECT_FALSE(image.offerUnshared(0, 0, PointImage::key(std::numeric_limits<float>::infinity()), held));
    EXPECT_TRUE(image.offerUnshared(1, 0, PointImage::key(std::numeric_limits<float>::infinity()), held))
        << "the background (infinitely far) wins an empty pixel";
}

TEST(PointImage, PlaceOverridesClearEmptiesAndCoversIncludesTheMargin) {
    PointImage image;
    image.reset(5, 3, 2);
    EXPECT_EQ(image.width(), 5);
    EXPECT_EQ(image.height(), 3);
    EXPECT_EQ(image.margin(), 2);
    EXPECT_EQ(image.pixelCount(), 9u * 7u);
    EXPECT_FALSE(image.hasSample(0, 0));
    EXPECT_EQ(image.keyAt(0, 0), PointImage::emptyKey());
    std::uint32_t held;
    image.offerUnshared(1, 1, PointImage::key(2.0f), held);
    image.place(1, 1, 9.0f);  // farther, but placed unconditionally
    EXPECT_EQ(image.depthAt(1, 1), 9.0f);
    EXPECT_FALSE(image.offerUnshared(1, 1, PointImage::key(10.0f), held)) << "a farther offer loses to a placed sample";
    EXPECT_EQ(image.depthAt(1, 1), 9.0f);
    image.clear(1, 1);
    EXPECT_FALSE(image.hasSample(1, 1));
    image.place(-2, -2, 1.0f);
    image.place(6, 4, 2.0f);
    EXPECT_EQ(image.depthAt(-2, -2), 1.0f);
    EXPECT_EQ(image.depthAt(6, 4), 2.0f);
    EXPECT_EQ(image.pixelIndex(-2, -2), 0u);
    EXPECT_EQ(image.pixelIndex(6, 4), image.pixelCount() - 1);
    EXPECT_FALSE(image.hasSample(4, 2)) << "margin corners do not alias image pixels";
    // covers(): [-margin, width + margin) x [-margin, height + margin).
    EXPECT_TRUE(image.covers(-2, -2));
    EXPECT_TRUE(image.covers(6, 4));
    EXPECT_FALSE(image.covers(-3, 0));
    EXPECT_FALSE(image.covers(0, -3));
    EXPECT_FALSE(image.covers(7, 0));
    EXPECT_FALSE(image.covers(0, 5));
    // nearerThan(d): every key of a depth below d, none at d.
    image.place(0, 0, 4.0f);
    EXPECT_LE(image.keyAt(0, 0), PointImage::nearerThan(4.0000005f));
    EXPECT_GT(image.keyAt(0, 0), PointImage::nearerThan(4.0f));
    EXPECT_LT(PointImage::key(std::numeric_limits<float>::infinity()), PointImage::emptyKey())
        << "infinitely far is still nearer than no sample";
}
