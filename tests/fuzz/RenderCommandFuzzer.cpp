// libFuzzer target: the `render` command's library function (runRenderCommand)
// on fuzzed option values, as main() would pass them after parsing argv. The
// input is decoded field by field (FuzzedDataProvider): out-of-range numbers,
// NaNs, unknown names and odd frame-name patterns all reach the validation
// (options held as enums get one of their values: main() has refused other names).
// Sizes, frames (at most 3, never the scene's own count), threads and cache
// resolutions are kept small so an input costs milliseconds; --out and
// --stats always name files inside the scratch directory (no '/' can get
// into the name), so no input writes elsewhere.
// InputError and RuntimeError are the documented answers; anything else is a finding.
#include <fuzzer/FuzzedDataProvider.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <sstream>
#include <string>

#include "FuzzScratchDir.h"
#include "app/RenderCommand.h"
#include "core/Errors.h"
#include "scene/BuiltinScenes.h"

namespace {

// Keeps only characters that cannot leave the directory or reach the shell.
std::string fileNameChars(const std::string& s, const char* allowed) {
    std::string kept;
    for (const char c : s)
        if (std::string_view(allowed).find(c) != std::string_view::npos) kept += c;
    return kept;
}

// One of `names`, or a short fuzzed string (which the command must reject).
std::string pickName(FuzzedDataProvider& fdp, std::initializer_list<const char*> names) {
    const std::size_t i = fdp.ConsumeIntegralInRange<std::size_t>(0, names.size());
    if (i < names.size()) return *(names.begin() + i);
    return fileNameChars(fdp.ConsumeRandomLengthString(12), "abcdefghijklmnopqrstuvwxyz-0123456789");
}

// One of `values`.
template <class T, std::size_t N>
T pickValue(FuzzedDataProvider& fdp, const std::array<T, N>& values) {
    return values[fdp.ConsumeIntegralInRange<std::size_t>(0, N - 1)];
}

std::optional<float> maybeFloat(FuzzedDataProvider& fdp) {
    if (!fdp.ConsumeBool()) return std::nullopt;
    return fdp.ConsumeFloatingPoint<float>();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
    FuzzedDataProvider fdp(data, size);
    const raycache::FuzzScratchDir& dir = raycache::fuzzScratchDir();
    dir.clear();

    raycache::RenderCommandOptions options;
    raycache::RenderJobOptions& job = options.job;
    const auto scenes = raycache::builtinScenes();
    const std::size_t sceneIndex = fdp.ConsumeIntegralInRange<std::size_t>(0, scenes.size());
    job.scene = sceneIndex < scenes.size()
                    ? scenes[sceneIndex].name
                    : fileNameChars(fdp.ConsumeRandomLengthString(12), "abcdefghijklmnopqrstuvwxyz-0123456789");
    job.width = fdp.ConsumeIntegralInRange(-1, 12);
    job.height = fdp.ConsumeIntegralInRange(-1, 12);
    // Never the scene's own frame count (25-60 for the built-in scenes): the
    // cloth scene poses, re-normals and refits its 90k triangles every frame,
    // and its 60 frames took 4.7-6.7 s an input under the sanitizers, 80 % of
    // a replay of 323 corpus inputs (2026-11-27; the fixed run had grown to
    // 11.5 min). At most 3 frames: cloth 0.5 s an input, the replay 9.5x
    // shorter. The flag is still drawn, so the other bytes of every input
    // keep their meaning; without it, 3 frames.
    job.frames = fdp.ConsumeBool() ? fdp.ConsumeIntegralInRange(-1, 3) : 3;
    if (fdp.ConsumeBool()) job.path = pickValue(fdp, raycache::kCameraPathKinds);  // keyframes: refused
    job.threads = fdp.ConsumeIntegralInRange(-1, 2);
    job.maxDepth = fdp.ConsumeIntegralInRange(-1, 8);
    job.minWeight = fdp.ConsumeFloatingPoint<float>();
    if (fdp.ConsumeBool()) job.technique = pickValue(fdp, raycache::kCacheTechniques).technique;
    job.cdctStep = maybeFloat(fdp);
    job.cdctEpsilon = maybeFloat(fdp);
    job.cdctMaxDepth = maybeFloat(fdp);
    job.cdctTolerance = maybeFloat(fdp);
    // Valid resolutions start at 16; up to 64 keeps a 32-object scene's cubes
    // small. Always set: the scenes' own 512² made one input pre-fill six
    // 512² CDCT faces under the sanitizers and run past the 30 s timeout.
    job.cacheResolution = fdp.ConsumeIntegralInRange(-1, 64);
    job.cacheIdeal = fdp.ConsumeBool();
    job.pipeline = pickValue(fdp, std::array{raycache::PipelineKind::Ray, raycache::PipelineKind::Hybrid});
    // Never gl or auto: making an OpenGL context per input would cost far more
    // than the parsing under test, and driver leaks would drown real findings.
    job.gbuffer = raycache::GBufferSource::Packets;
    if (fdp.ConsumeBool()) {
        const std::string ext = pickName(fdp, {".png", ".exr", ".jpg", ""});
        const std::string stem = fileNameChars(fdp.ConsumeRandomLengthString(10), "abcdefghij0123456789%d_.");
        options.out = (dir.path() / ("o" + stem + fileNameChars(ext, "abcdefghijklmnopqrstuvwxyz."))).string();
    }
    if (fdp.ConsumeBool()) options.statsPath = (dir.path() / "stats.json").string();

    std::ostringstream progress;
    try {
        raycache::runRenderCommand(options, progress, progress);
    } catch (const raycache::InputError&) {
        // The documented answer to bad options (exit status 2 in the CLI).
    } catch (const raycache::RuntimeError&) {
        // The documented answer to a failure while running (exit status 1).
    }
    return 0;
}
