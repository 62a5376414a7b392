// predictNextCamera(): the last step repeated, exactly.
#include <gtest/gtest.h>

#include "rendercache/CameraPrediction.h"

using namespace raycache;

TEST(CameraPrediction, RepeatsTheLastStepOfEyeAndLookAt) {
    const Camera previous{{1.0f, 2.0f, 3.0f}, {0.0f, 0.5f, -1.0f}, {0.0f, 1.0f, 0.0f}, 45.0f};
    const Camera current{{1.5f, 2.0f, 2.25f}, {0.25f, 0.5f, -1.0f}, {0.0f, 0.0f, 1.0f}, 30.0f};
    const Camera next = predictNextCamera(previous, current);
    EXPECT_EQ(next.position, (Vec3{2.0f, 2.0f, 1.5f}));
    EXPECT_EQ(next.lookAt, (Vec3{0.5f, 0.5f, -1.0f}));
    EXPECT_EQ(next.up, current.up);
    EXPECT_EQ(next.verticalFovDeg, 30.0f);
    // A still camera predicts itself.
    EXPECT_EQ(predictNextCamera(current, current), current);
}
