#pragma once
// The documents' frame-rate tables (5.1, 5.2, 5.3) as one kind of experiment:
// a list of scenes, a list of variants (uncached, CCT, CDCT with parameters),
// each scene's variants timed interleaved in one run —
//  * still camera, caches filled by warm-up frames first (the documents' protocol);
//  * optionally the scene's moving camera path from empty caches, filling as it goes —
// and the documents' figures placed beside ours. The three tables are defined
// in Table51Experiment.cpp, Table52Experiment.cpp and Table53Experiment.cpp.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench/Experiment.h"
#include "bench/PaperFigures.h"
#include "render/RenderSettings.h"
#include "scene/Scene.h"

namespace raycache {

struct TimingVariant {
    std::string key;    // the documents' column for it (PaperTable::columns), e.g. "standard", "cct"
    std::string label;  // as printed, e.g. "uncached", "CDCT parity 2/0.2"
    // Replaces every mirror/glass object's technique; nullopt keeps the
    // scene's own materials (e.g. Table 5.1, where only `main` caches).
    std::optional<CacheTechnique> technique;
    std::optional<CdctParameters> cdct;
    // Non-empty: this build cannot run the variant; it is listed, not measured, with this reason.
    std::string unavailable;
    double costWeight = 1.0;  // rough cost of a frame relative to uncached, for the ETA only
};

struct TimingScene {
    std::string scene;  // built-in scene
    std::string label;  // the documents' row label, e.g. "8" or "Reflective"
};

struct TimingSize {
    int width = 0;
    int height = 0;
    int warmupFrames = 0;  // untimed, fill the caches
    int timedFrames = 0;
    int movingFrames = 0;       // 0 = no moving-camera run
    int movingRounds = 0;       // each renders the whole path per variant
    int scenes = 0;             // how many of the table's scenes to run (0 = all)
    int cacheResolution = 512;  // cube face side (the documents': 512)
    // Still camera, adaptive: after `timedFrames` rounds, more rounds until every
    // speed-up's 95 % interval is within ±5 %, at most `maxTimedFrames` rounds
    // (0 = exactly timedFrames) and no new round once the timed rounds of a
    // scene took `timeCapSeconds` (0 = no cap).
    int maxTimedFrames = 0;
    double timeCapSeconds = 0.0;
};

struct TimingTableSpec {
    std::string name;
    std::string title;
    std::string description;  // what is measured, in a few sentences (goes into results.md)
    std::string rowHeader;    // "N" or "scene"
    std::vector<TimingScene> scenes;
    std::vector<TimingVariant> variants;  // variants[0] is the baseline speed-ups are relative to
    PaperTable documents;
    std::string documentsSpeedupColumn;  // the documents' printed speed-up column, if any
    // Rows = scenes with the baseline and variants[1] side by side (5.1, 5.2);
    // otherwise rows = variants with a column group per scene (5.3).
    bool rowsAreScenes = true;
    TimingSize tiny, quick, full;
    std::string pipeline = "ray";  // recorded in results.json
    // Applied to every variant's settings (e.g. choosing the render pipeline).
    std::function<void(RenderSettings&)> configure;
    // Applied to each built-in scene before it is rendered (e.g. only `main` caches).
    std::function<void(Scene&)> adjustScene;
    std::vector<std::string> caveats;  // printed in the output and the report
};

// The sizes of the documents' 1024x1024 tables (5.1, 5.2): full, quick (its
// time cap keeps `bench all --quick` within 3 minutes on 2 cores) and tiny.
void setSquareTableSizes(TimingTableSpec& spec);

class TimingTableExperiment : public Experiment {
public:
    explicit TimingTableExperiment(TimingTableSpec spec) : spec_(std::move(spec)) {}
    std::string name() const override { return spec_.name; }
    std::string title() const override { return spec_.title; }
    double estimatedWork(const BenchSettings& settings) const override;
    ExperimentOutput run(ExperimentContext& context) const override;
    const TimingTableSpec& spec() const { return spec_; }

private:
    const TimingSize& sizeFor(BenchSize size) const;
    TimingTableSpec spec_;
};

std::unique_ptr<Experiment> makeTable51Experiment();
std::unique_ptr<Experiment> makeTable52Experiment();
std::unique_ptr<Experiment> makeTable53Experiment();

}  // namespace raycache
