#pragma once
// The reuse techniques for secondary rays: the one table that names them.
// The scene format, the command line, the viewer and the reports all read
// their names and summaries from here; the cache (cache/RayCache) decides
// what each does. A new technique is one row here plus its code in src/cache/
// (docs/architecture.md, "Adding a reuse technique").
#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace raycache {

// Cct: color only (Ruff, Clua and Fernandes 2013). CdctParity: color + depth with the thesis's
// search as specified (Ruff's MSc thesis, 2013). Cdct: the improved color + depth technique
// (pre-filled cubes, texel-space search, error control; docs/caching.md).
enum class CacheTechnique { None, Cct, CdctParity, Cdct };

struct CacheTechniqueInfo {
    CacheTechnique technique;
    std::string_view name;     // on the command line and in scene files
    std::string_view summary;  // one line for help texts
};

inline constexpr std::array<CacheTechniqueInfo, 4> kCacheTechniques{{
    {CacheTechnique::None, "none", "no caching: every secondary ray is traced"},
    {CacheTechnique::Cct, "cct", "color caching cube, addressed by the ray's direction"},
    {CacheTechnique::Cdct, "cdct", "color and depth caching cube, improved search (pre-filled, error-controlled)"},
    {CacheTechnique::CdctParity, "cdct-parity", "color and depth caching cube, the thesis's search as specified"},
}};

// The techniques alone, in kCacheTechniques's order: the choices of an option.
inline constexpr std::array<CacheTechnique, kCacheTechniques.size()> kCacheTechniqueValues = [] {
    std::array<CacheTechnique, kCacheTechniques.size()> values{};
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = kCacheTechniques[i].technique;
    return values;
}();

// The name a technique has on the command line and in scene files.
constexpr const char* cacheTechniqueName(CacheTechnique technique) {
    for (const CacheTechniqueInfo& info : kCacheTechniques)
        if (info.technique == technique) return info.name.data();
    return "unknown";
}

// The technique called `name`, if any.
constexpr std::optional<CacheTechnique> parseCacheTechnique(std::string_view name) {
    for (const CacheTechniqueInfo& info : kCacheTechniques)
        if (info.name == name) return info.technique;
    return std::nullopt;
}

// "none, cct, cdct or cdct-parity", for messages.
inline std::string cacheTechniqueNameList() {
    std::string list;
    for (std::size_t i = 0; i < kCacheTechniques.size(); ++i) {
        if (i > 0) list += i + 1 == kCacheTechniques.size() ? " or " : ", ";
        list += kCacheTechniques[i].name;
    }
    return list;
}

}  // namespace raycache
