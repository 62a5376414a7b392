// Which samples the Render Cache shades again from a new eye.
#include "rendercache/ViewDependence.h"

#include <gtest/gtest.h>

using namespace raycache;

TEST(ViewDependence, MatteBlinnPhongKeepsItsColourAndHighlightsMirrorsAndGlassDoNot) {
    Material matte;  // Blinn-Phong, no highlight, no rays
    EXPECT_FALSE(dependsOnView(matte));
    Material highlight = matte;
    highlight.specular = Rgb(0.5f);
    EXPECT_TRUE(dependsOnView(highlight));
    Material mirror = matte;
    mirror.reflectivity = 0.8f;
    EXPECT_TRUE(dependsOnView(mirror));
    Material glass = matte;
    glass.transmissivity = 0.9f;
    EXPECT_TRUE(dependsOnView(glass));
}

// A rough metallic-roughness surface spawns no ray and has no Blinn-Phong
// highlight colour, yet its GGX lobe and Fresnel follow the eye.
TEST(ViewDependence, RoughMetallicRoughnessSurfacesFollowTheEye) {
    Material rough;
    rough.model = ShadingModel::MetallicRoughness;
    rough.roughness = 0.6f;
    rough.metallic = 0.0f;
    ASSERT_TRUE(rough.specular.isBlack());
    ASSERT_FALSE(rough.reflects());
    ASSERT_FALSE(rough.refracts());
    EXPECT_TRUE(dependsOnView(rough));
}
