#pragma once
// The caching techniques the viewer's combo offers, and what each sets.
#include <array>
#include <optional>
#include <span>
#include <string_view>

#include "scene/Material.h"

namespace raycache {

struct TechniqueChoice {
    const char* label;
    std::optional<CacheTechnique> technique;  // empty: every material's own setting
};

// "scene" first, then every technique of the table (scene/CacheTechnique.h).
inline constexpr auto kTechniqueChoices = [] {
    std::array<TechniqueChoice, kCacheTechniques.size() + 1> choices{};
    choices[0] = {"scene", std::nullopt};
    for (std::size_t i = 0; i < kCacheTechniques.size(); ++i)
        choices[i + 1] = {kCacheTechniques[i].name.data(), kCacheTechniques[i].technique};
    return choices;
}();

// Index of the choice labelled `label`, or of "scene" for an empty label;
// -1 if there is no such choice.
inline int techniqueChoiceIndex(std::string_view label) {
    if (label.empty()) return 0;
    for (std::size_t i = 0; i < kTechniqueChoices.size(); ++i)
        if (label == kTechniqueChoices[i].label) return static_cast<int>(i);
    return -1;
}

}  // namespace raycache
