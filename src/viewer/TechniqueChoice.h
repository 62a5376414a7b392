#pragma once
// The caching techniques the viewer's combo offers, and what each sets.
#include <array>
#include <optional>

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

// Index of the choice that sets `technique`: "scene" for none.
inline int techniqueChoiceIndex(std::optional<CacheTechnique> technique) {
    for (std::size_t i = 0; i < kTechniqueChoices.size(); ++i)
        if (kTechniqueChoices[i].technique == technique) return static_cast<int>(i);
    return 0;
}

}  // namespace raycache
