// PointImage: place, clear, the margin, and keys that order as depths do.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>

#include "rendercache/PointImage.h"

using namespace raycache;

TEST(PointImage, PlaceOverridesClearEmptiesAndCoversIncludesTheMargin) {
    PointImage image;
    image.reset(5, 3, 2);
    EXPECT_EQ(image.width(), 5);
    EXPECT_EQ(image.height(), 3);
    EXPECT_EQ(image.margin(), 2);
    EXPECT_EQ(image.pixelCount(), 9u * 7u);
    EXPECT_FALSE(image.hasSample(0, 0));
    EXPECT_EQ(image.keyAt(0, 0), PointImage::emptyKey());
    image.place(1, 1, 2.0f);
    image.place(1, 1, 9.0f);  // farther, but placed unconditionally
    EXPECT_EQ(image.depthAt(1, 1), 9.0f);
    EXPECT_LT(PointImage::key(2.0f), image.keyAt(1, 1)) << "nearer is a smaller key";
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
