#pragma once
// The source documents' own figures (from
// Ruff's MSc thesis, UFF 2013, and the SIBGRAPI 2013 paper), kept as data in
// this one place so every experiment prints them beside its own results.
// They were measured on a GPU (OptiX) at 1024x1024 with 512^2 caches unless
// noted: compare ratios (speed-ups), not absolute frame rates.
#include <optional>
#include <string>
#include <vector>

namespace raycache {

struct PaperRow {
    std::string label;           // e.g. "0" (N) or "Diffuse"
    std::vector<double> values;  // one per PaperTable::columns
};

struct PaperTable {
    std::string source;                // where in the documents
    std::string conditions;            // resolution, pipeline, GPU
    std::vector<std::string> columns;  // keys, e.g. "standard", "cct", "speedup"
    std::vector<PaperRow> rows;

    // The value in row `label`, column `column`, if the documents give one.
    std::optional<double> value(const std::string& label, const std::string& column) const;
};

// Table 5.1: hybrid pipeline, behind-N; columns standard, cct (fps), speedup.
PaperTable paperTable51();
// Table 5.2: plain ray tracing, grid-N; columns standard, cct (fps), speedup.
PaperTable paperTable52();
// Table 5.3: 1920x1080, 32 spheres; rows Diffuse, Reflective; columns cct,
// standard, cdct-2/0.2, cdct-0.4/0.05, cdct-0.2/0.02, cdct-0.02/0.002 (fps).
PaperTable paperTable53();
// Figure 5.9: invalid texels (%) after the first frame per face resolution;
// rows "128", "256", "512"; column invalid-after-frame-1.
PaperTable paperFigure59();
// What Figure 5.9 says about later frames, in words (no numbers per frame).
std::string paperFigure59Later();

// The GPU Render Cache (Zhu, Wang and Luebke 2005, Section 4 and Figure 3):
// reconstruction alone (sample generation excluded) on a GeForce 6800 with a
// 2.8 GHz Pentium 4; rows "512", "1024" (image side); columns fps, ms.
PaperTable paperRenderCache();
// What the same section says about the optimised CPU version, in words.
std::string paperRenderCacheCpu();

}  // namespace raycache
