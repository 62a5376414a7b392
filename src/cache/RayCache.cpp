// RayCache: the cubes made, checked and planned within the memory budget,
// and their sizes. The other concepts of the class have files of
// their own: RayCacheLookup.cpp, RayCacheStores.cpp, RayCacheInvalidation.cpp,
// RayCachePrefill.cpp.
#include "cache/RayCache.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <variant>

#include "core/Errors.h"
#include "core/TextFormat.h"
#include "scene/ObjectBounds.h"

namespace raycache {

namespace {

// "between 16 and 2048": the face resolutions a cube may be asked for.
std::string faceResolutionRange() {
    return "between " + std::to_string(CacheSettings::kMinFaceResolution) + " and " +
           std::to_string(CacheSettings::kMaxFaceResolution);
}

bool allowedFaceResolution(int resolution) {
    return resolution >= CacheSettings::kMinFaceResolution && resolution <= CacheSettings::kMaxFaceResolution;
}

}  // namespace

CdctParameters RayCache::cdctParametersFor(const SceneObject& object, const RayCacheSettings& settings) {
    CdctParameters p = object.material.cache.cdct;
    if (settings.cdctStepOverride) p.step = *settings.cdctStepOverride;
    if (settings.cdctEpsilonOverride) p.epsilon = *settings.cdctEpsilonOverride;
    if (settings.cdctMaxDepthOverride) p.maxDepth = *settings.cdctMaxDepthOverride;
    if (settings.cdctToleranceOverride) p.tolerance = *settings.cdctToleranceOverride;
    return p;
}

void RayCache::validateCdct(const CdctParameters& p, const std::string& what) {
    const auto positive = [&](float v, const char* name) {
        if (!(std::isfinite(v) && v > 0.0f))
            throw InputError(what + ": cdct " + name + " must be a finite number > 0 (got " + formatGeneral(v) + ")");
    };
    positive(p.step, "step");
    positive(p.epsilon, "epsilon");
    positive(p.maxDepth, "maxDepth");
    positive(p.tolerance, "tolerance");
    if (p.tolerance > 1e6f)
        throw InputError(what + ": cdct tolerance must be at most 1e6 texels (got " + formatGeneral(p.tolerance) + ")");
    if (!(p.epsilon < p.step))
        throw InputError(what + ": cdct epsilon (" + formatGeneral(p.epsilon) + ") must be smaller than step (" +
                         formatGeneral(p.step) + ")");
    if (std::ceil(2.0 * p.maxDepth / p.step) > kMaxCdctLinearSteps)
        throw InputError(what + ": cdct step " + formatGeneral(p.step) + " is too small for maxDepth " +
                         formatGeneral(p.maxDepth) + " (at most 1e6 search steps: step >= maxDepth / 500000)");
}

Vec3 RayCache::boundingHalfSize(const SceneObject& object) {
    Vec3 half;
    if (const auto* sphere = std::get_if<Sphere>(&object.shape)) {
        const Vec3 d = sphere->center - object.origin;
        half =
            Vec3{std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)} + Vec3{sphere->radius, sphere->radius, sphere->radius};
    } else if (const auto* mesh = std::get_if<MeshShape>(&object.shape); mesh && mesh->mesh) {
        for (const Vec3& p : mesh->mesh->positions) {
            const Vec3 d = p - object.origin;
            half = max(half, Vec3{std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)});
        }
    }
    // A flat object still gets a box of some thickness, and the ray origins,
    // offset slightly off the surface, stay inside it.
    const float extent = std::max({half.x, half.y, half.z, 1e-3f});
    const float margin = 1e-3f * extent;
    return half + Vec3{margin, margin, margin};
}

float RayCache::boundingRadius(const SceneObject& object) {
    float radius = 0.0f;
    if (const auto* sphere = std::get_if<Sphere>(&object.shape)) {
        radius = length(sphere->center - object.origin) + sphere->radius;
    } else if (const auto* mesh = std::get_if<MeshShape>(&object.shape); mesh && mesh->mesh) {
        for (const Vec3& p : mesh->mesh->positions) radius = std::max(radius, length(p - object.origin));
    }
    return radius;
}

CacheTechnique RayCache::techniqueFor(const SceneObject& object, const RayCacheSettings& settings) {
    const Material& m = object.material;
    if (!m.reflects() && !m.refracts()) return CacheTechnique::None;
    return settings.techniqueOverride.value_or(m.cache.technique);
}

CubeBudgetPlan RayCache::validate(const Scene& scene, const RayCacheSettings& settings) {
    if (settings.resolutionOverride && !allowedFaceResolution(*settings.resolutionOverride))
        throw InputError("cache resolution must be " + faceResolutionRange() + " (got " +
                         std::to_string(*settings.resolutionOverride) + ")");
    if (settings.cubeLevels < 1 || settings.cubeLevels > kMaxCubeLevels)
        throw InputError("cache levels must be between 1 and " + std::to_string(kMaxCubeLevels) + " (got " +
                         std::to_string(settings.cubeLevels) + ")");
    if (!(std::isfinite(settings.levelErrorBound) && settings.levelErrorBound > 0.0f &&
          settings.levelErrorBound <= 1000.0f))
        throw InputError("cache level error bound must be a finite number in (0, 1000] (got " +
                         formatGeneral(settings.levelErrorBound) + ")");
    if (settings.prefillTexelsPerFrame < 0)
        throw InputError("pre-fill texels per frame must be 0 (whole cubes) or more (got " +
                         std::to_string(settings.prefillTexelsPerFrame) + ")");
    for (const SceneObject& object : scene.objects) {
        const CacheTechnique technique = techniqueFor(object, settings);
        if (technique == CacheTechnique::Cdct || technique == CacheTechnique::CdctParity)
            validateCdct(cdctParametersFor(object, settings), "object '" + object.name + "'");
        const int resolution = settings.resolutionOverride.value_or(object.material.cache.faceResolution);
        if (technique != CacheTechnique::None && !allowedFaceResolution(resolution))
            throw InputError("object '" + object.name + "': cache resolution must be " + faceResolutionRange());
    }
    return planBudget(scene, settings);
}

CubeBudgetPlan RayCache::planBudget(const Scene& scene, const RayCacheSettings& settings) {
    std::vector<CubeRequest> requests;
    for (const SceneObject& object : scene.objects) {
        const CacheTechnique technique = techniqueFor(object, settings);
        if (technique == CacheTechnique::None) continue;
        requests.push_back({object.name, technique != CacheTechnique::Cct,
                            settings.resolutionOverride.value_or(object.material.cache.faceResolution),
                            std::max(length(boundingHalfSize(object)), 1e-6f),
                            settings.resolutionFromView && technique == CacheTechnique::Cct});
    }
    const bool tracks = !scene.animation.empty() || settings.invalidationOracle;
    return planCubeBudget(requests, settings.memoryBudget, settings.cubeLevels, tracks, kMinBudgetResolution);
}

RayCache::RayCache(const Scene& scene, const RayCacheSettings& settings)
    : ideal_(settings.ideal), oracle_(settings.invalidationOracle), levelErrorBound_(settings.levelErrorBound),
      cubeLevels_(settings.cubeLevels), viewSized_(settings.resolutionFromView),
      tracksDependencies_(!scene.animation.empty() || settings.invalidationOracle),
      improvements_(settings.cdctImprovements), prefillTexelsPerFrame_(settings.prefillTexelsPerFrame),
      skipStoresReachingChanges_(settings.skipStoresReachingChanges && !settings.invalidationOracle) {
    const CubeBudgetPlan plan = validate(scene, settings);
    budgetNote_ = plan.note;
    cubeOfObject_.assign(scene.objects.size(), -1);
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const SceneObject& object = scene.objects[i];
        const CacheTechnique technique = techniqueFor(object, settings);
        if (technique == CacheTechnique::None) continue;
        const int resolution = plan.resolutions[cubes_.size()];
        cubeOfObject_[i] = static_cast<int>(cubes_.size());
        if (technique == CacheTechnique::Cct)
            cubes_.push_back(Entry{static_cast<int>(i), object.name, technique, CachingCube(object.origin, resolution)});
        else
            cubes_.push_back(Entry{static_cast<int>(i), object.name, technique,
                                   CachingCube(object.origin, resolution, boundingHalfSize(object)),
                                   cdctParametersFor(object, settings)});
        Entry& e = cubes_.back();
        if (technique == CacheTechnique::Cct && viewSized_) e.view = ViewSizedResolution(resolution);
        if (technique == CacheTechnique::Cct && settings.cubeLevels > 1) {
            e.coarse = CoarseLevels(object.origin, resolution, settings.cubeLevels);
            multiLevel_ = multiLevel_ || e.coarse.levelCount() > 1;
        }
        if (tracksDependencies_ && technique == CacheTechnique::Cct) {
            e.blocksPerSide = (resolution + kBlockSize - 1) / kBlockSize;
            e.blocks.resize(6u * static_cast<std::size_t>(e.blocksPerSide) * static_cast<std::size_t>(e.blocksPerSide));
        }
        if (oracle_) e.storedTrees.resize(e.cube.texelCount());
        if (tracksDependencies_) e.droppedBits.assign((e.cube.texelCount() + 63) / 64, 0);
        const bool mayStepAside = !settings.ideal && !settings.invalidationOracle;
        // A CCT lookup reads the one texel its store would write, so a sample
        // of texels shows what full caching would hit; a CDCT search does not.
        e.policy = CubePolicy(mayStepAside ? settings.policy : CachePolicyMode::Always,
                              tracksDependencies_ ? settings.policyCosts.tracked() : settings.policyCosts,
                              technique == CacheTechnique::Cct);
        if (mayStepAside && settings.policy == CachePolicyMode::Auto && technique == CacheTechnique::Cct)
            e.treeRays.assign(e.cube.texelCount(), 0);
    }
    const bool anyCct = std::any_of(cubes_.begin(), cubes_.end(), [](const Entry& e) { return e.technique == CacheTechnique::Cct; });
    if (anyCct) visibleFill_ = settings.visibleFill;
    if (tracksDependencies_) {
        // Only animated objects ever change.
        objectBounds_.resize(scene.objects.size());
        for (const ObjectAnimation& a : scene.animation.objects)
            objectBounds_[static_cast<std::size_t>(a.object)] =
                partedBounds(scene.objects[static_cast<std::size_t>(a.object)], kTrianglesPerPart);
        if (scene.objects.size() <= kMostObjectsForMovedEscapes)
            for (const SceneObject& object : scene.objects) {
                const Box3 box = worldBounds(object);
                wholeBounds_.push_back(box.empty() ? box : PartedBounds{box, {}, {}}.grownRelative(kRegionGrowth).whole);
            }
        lights_ = scene.lights;
    }
}

std::size_t RayCache::bytes() const {
    std::size_t total = dependencyBytes();
    for (const Entry& e : cubes_) total += e.cube.bytes() + e.coarse.bytes();
    return total;
}

std::size_t RayCache::dependencyBytes() const {
    std::size_t total = 0;
    for (const Entry& e : cubes_)
        total += e.blocks.size() * sizeof(RayTreeBounds) + e.storedTrees.size() * sizeof(RayTreeRecord);
    return total;
}

}  // namespace raycache
