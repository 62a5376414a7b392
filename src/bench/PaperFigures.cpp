#include "bench/PaperFigures.h"

namespace raycache {

std::optional<double> PaperTable::value(const std::string& label, const std::string& column) const {
    for (std::size_t c = 0; c < columns.size(); ++c) {
        if (columns[c] != column) continue;
        for (const PaperRow& row : rows)
            if (row.label == label && c < row.values.size()) return row.values[c];
    }
    return std::nullopt;
}

PaperTable paperTable51() {
    return {"Ruff, MSc thesis (UFF 2013), Table 5.1",
            "hybrid raster + ray tracing pipeline, 1024x1024, 512^2 caches, only the main sphere caches, GPU (OptiX)",
            {"standard", "cct", "speedup"},
            {{"0", {68, 125, 1.84}},
             {"1", {63, 120, 1.90}},
             {"2", {59, 117, 1.98}},
             {"4", {49, 98, 2.00}},
             {"8", {38, 85, 2.24}},
             {"16", {23, 63, 2.74}},
             {"32", {12, 42, 3.50}}}};
}

PaperTable paperTable52() {
    return {"Ruff, MSc thesis (UFF 2013), Table 5.2",
            "plain ray tracing, 1024x1024, 512^2 caches, GPU (OptiX)",
            {"standard", "cct", "speedup"},
            {{"1", {56.7, 57.8, 1.02}},
             {"2", {52.0, 55.6, 1.07}},
             {"4", {44.7, 51.8, 1.15}},
             {"8", {32.8, 43.5, 1.32}},
             {"16", {17.1, 33.4, 1.95}},
             {"32", {8.0, 21.5, 2.68}}}};
}

PaperTable paperTable53() {
    return {"Ruff, MSc thesis (UFF 2013), Table 5.3",
            "1920x1080, 32 spheres, GPU (OptiX); CDCT columns are step/epsilon",
            {"cct", "standard", "cdct-2/0.2", "cdct-0.4/0.05", "cdct-0.2/0.02", "cdct-0.02/0.002"},
            {{"Diffuse", {76.0, 69.6, 49.5, 35.3, 30.7, 19.0}}, {"Reflective", {68.2, 30.1, 13.5, 12.7, 12.1, 9.5}}}};
}

PaperTable paperFigure59() {
    return {"Ruff, MSc thesis (UFF 2013), Figure 5.9",
            "one caching sphere, camera moved around it in 9 steps of 10/3 degrees, 1024x1024",
            {"invalid-after-frame-1"},
            {{"128", {3}}, {"256", {31}}, {"512", {73}}}};
}

std::string paperFigure59Later() {
    return "about 0-1 % invalid after 7-8 frames at every resolution";
}

PaperTable paperRenderCache() {
    return {"Zhu, Wang and Luebke 2005, Section 4 and Figure 3",
            "reconstruction only (sample generation excluded), GeForce 6800, Pentium 4 2.8 GHz",
            {"fps", "ms"},
            {{"512", {123, 1000.0 / 123}}, {"1024", {38, 1000.0 / 38}}}};
}

std::string paperRenderCacheCpu() {
    return "at least four times faster than an optimised CPU implementation of the enhanced Render Cache, which "
           "runs at 512x512";
}

}  // namespace raycache
