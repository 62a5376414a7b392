#include "session/FrameReport.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

namespace raycache {

std::string formatFrameLine(const FrameResult& r, int frameCount) {
    const RayCounts& rays = r.stats.rays;
    const double mrays = static_cast<double>(rays.total()) / (r.milliseconds * 1e3);
    std::ostringstream line;
    line << "frame " << (r.frame + 1) << "/" << frameCount << "  " << formatFixed(r.milliseconds, 1)
         << " ms  rays: primary " << rays.primary << ", shadow " << rays.shadow << ", reflection " << rays.reflection
         << ", refraction " << rays.refraction;
    if (rays.prefill) line << ", pre-fill " << rays.prefill;
    if (rays.fill) line << ", visible fill " << rays.fill;
    line << "  " << formatFixed(mrays, 2) << " Mrays/s";
    if (const auto& c = r.stats.cache) {
        const double hitRate =
            c->lookups() ? 100.0 * static_cast<double>(c->hits()) / static_cast<double>(c->lookups()) : 0.0;
        line << "  cache: " << c->objects.size() << (c->objects.size() == 1 ? " cube" : " cubes") << ", hits " << formatFixed(hitRate, 1) << "% of "
             << c->lookups() << ", stores " << c->stores();
        if (c->skippedStores()) line << " (" << c->skippedStores() << " skipped: reached what moved)";
        const int aside = c->bypassedCubes(), sampling = c->samplingCubes();
        if (aside) line << ", bypassed " << aside << "/" << c->objects.size();
        if (sampling) line << ", sampling " << sampling << "/" << c->objects.size();
        // The cache policy stepped these cubes aside or had them sample: the
        // rays they did not look up were traced.
        if (c->tracedAsUncached) line << " (rendered as uncached)";
        else if (aside || sampling) line << " (" << c->bypassedRays() << " rays traced)";
        {
            // The cache policy's model of the frame, in traced rays.
            double saving = 0.0, cost = 0.0;
            for (const ObjectCacheStats& o : c->objects) {
                saving += o.policySaving;
                cost += o.policyCost;
            }
            if (saving > 0.0 || cost > 0.0)
                line << ", model: saves " << formatFixed(saving, 0) << " rays, costs " << formatFixed(cost, 0);
        }
        if (c->levels() > 1) {
            // Where the hits came from, finest level first.
            line << " (by level";
            for (int k = 0; k < c->levels(); ++k) {
                const double share = c->hits() ? 100.0 * static_cast<double>(c->hitsAtLevel(k)) / static_cast<double>(c->hits()) : 0.0;
                line << (k ? " " : ": ") << formatFixed(share, 0) << "%";
            }
            line << ")";
        }
        if (c->rejected()) line << ", rejected " << c->rejected();
        if (c->ownSurface()) line << ", own surface " << c->ownSurface();
        if (c->viewDependent()) line << ", view-dependent " << c->viewDependent();
        if (c->cdctSearches())
            line << ", CDCT steps/search "
                 << formatFixed(static_cast<double>(c->cdctSteps()) / static_cast<double>(c->cdctSearches()), 1);
        if (c->prefilledTexels()) line << ", pre-filled " << c->prefilledTexels();
        int resized = 0, smallest = 0, largest = 0;
        for (const ObjectCacheStats& o : c->objects) {
            if (o.resizedTo == 0) continue;
            smallest = resized++ ? std::min(smallest, o.resizedTo) : o.resizedTo;
            largest = std::max(largest, o.resizedTo);
        }
        if (resized) {
            line << ", resized " << resized << (resized == 1 ? " cube" : " cubes") << " to " << smallest << "²";
            if (largest != smallest) line << "–" << largest << "²";
        }
        line << ", invalid before "
             << formatFixed(c->invalidPercentBefore(), 1) << "%, "
             << formatFixed(static_cast<double>(c->bytes()) / (1024.0 * 1024.0), 1) << " MiB";
    }
    if (const auto& p = r.stats.phases)
        line << "  phases ms: raster " << formatFixed(p->raster, 1) << ", readback " << formatFixed(p->readback, 1)
             << ", shadows " << formatFixed(p->shadows, 1) << ", secondary " << formatFixed(p->secondary, 1)
             << ", compose " << formatFixed(p->compose, 1);
    if (const auto& c = r.stats.renderCache) {
        const double pixels = static_cast<double>(std::max<std::int64_t>(1, c->pixels));
        line << "  render cache: " << (c->refreshedAll ? "every pixel traced" : "traced " + formatFixed(100.0 * static_cast<double>(c->fresh) / pixels, 1) + " %")
             << ", predicted " << c->predicted << ", holes " << formatFixed(100.0 * static_cast<double>(c->holes) / pixels, 1)
             << " %, reshaded " << c->reshaded << ", ms: reconstruction " << formatFixed(c->reconstructionMs(), 1)
             << " (" << formatFixed(c->reconstructionGbPerSecond(), 1) << " GB/s counted), samples "
             << formatFixed(c->sampleGenerationMs(), 1);
    }
    if (const auto& u = r.stats.sceneUpdate)
        line << "  scene update: " << u->objectsChanged << (u->objectsChanged == 1 ? " object, " : " objects, ")
             << u->lightsChanged << (u->lightsChanged == 1 ? " light" : " lights") << " changed, "
             << formatFixed(u->milliseconds, 2) << " ms, " << u->texelsInvalidated << " texels invalidated";
    if (const auto& c = r.stats.cluster) {
        line << "  cluster: " << c->processes << " processes, " << c->assignment;
        if (!c->tilesPerProcess.empty()) {
            line << " (tiles";
            for (std::size_t p = 0; p < c->tilesPerProcess.size(); ++p) line << (p ? "/" : " ") << c->tilesPerProcess[p];
            line << ", imbalance " << formatFixed(c->imbalance, 2) << ")";
        }
        line << ", exchanged: stores " << c->storeBytes << " B";
        if (c->prefillBytes) line << ", pre-fill " << c->prefillBytes << " B";
        line << ", image " << c->imageBytes << " B, control "
             << c->controlBytes << " B";
    }
    if (const auto& g = r.stats.trace)
        line << "  grids: build ms " << formatFixed(r.stats.gridBuildMs, 1) << " (primary "
             << formatFixed(g->build.primaryBuildMs, 1) << ", shadow " << formatFixed(g->build.shadowBuildMs, 1)
             << "), pairs " << g->build.primaryPairs << " + " << g->build.shadowPairs << ", rays answered "
             << g->primaryAnswered << " primary, " << g->shadowAnswered << " shadow; refused (to Embree) "
             << g->primaryRefused << " primary, " << g->shadowRefused << " shadow";
    if (const auto& s = r.stats.stages) {
        // CPU ms, and ns per shaded hit in brackets: comparable across image sizes and scenes.
        const auto stage = [&](const char* name, double ms) {
            return std::string(name) + " " + formatFixed(ms, 1) + " (" + formatFixed(s->nsPerHit(ms), 1) + ")";
        };
        line << "  stages cpu ms (ns per hit; " << s->hitsShaded << " hits): " << stage("first hits", s->firstHits)
             << ", " << stage("surfaces", s->surfaces) << ", " << stage("shadow rays", s->shadowRays) << ", "
             << stage("direct", s->directShading) << ", " << stage("secondary rays", s->secondaryRays) << ", "
             << stage("lookups", s->reuseLookups) << ", " << stage("trace", s->traceSecondary) << ", "
             << stage("resolve", s->resolve) << ", " << stage("compose", s->compose)
             << (s->visibleFill > 0.0 ? ", " + stage("visible fill", s->visibleFill) : std::string())
             << ", cache frame end (wall) " << formatFixed(s->cacheFrameEnd, 1);
    }
    return line.str();
}

}  // namespace raycache
