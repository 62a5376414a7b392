#include "scene/GltfScene.h"

#include <assimp/GltfMaterial.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "core/Box3.h"
#include "core/Errors.h"
#include "core/TextFormat.h"
#include "core/Transform.h"
#include "scene/AssimpFileReader.h"
#include "scene/GltfDocument.h"
#include "scene/GltfSceneDefaults.h"
#include "scene/GltfTextureImages.h"
#include "scene/GltfTextureTransform.h"
#include "scene/ImageLoader.h"
#include "scene/MeshLimits.h"
#include "scene/MeshRepair.h"
#include "scene/PbrToBlinnPhong.h"

namespace raycache {
namespace {

namespace fs = std::filesystem;

// Blender's glTF exporter's luminous efficacy (PBR_WATTS_TO_LUMENS): the
// factor between its watts and the file's candela and lux.
constexpr float kLumensPerWatt = 683.0f;

// As many objects as a JSON scene may have (docs/scene-format.md, "Limits").
constexpr std::size_t kMaxGltfObjects = 100000;

// Extensions raycache reads (through Assimp, or from the file's JSON where
// Assimp does not: scene/GltfDocument.h): required or not, they are honoured.
constexpr std::array<std::string_view, 6> kReadExtensions{"KHR_lights_punctual", "KHR_materials_transmission",
                                                          "KHR_materials_ior", "KHR_texture_transform",
                                                          "KHR_materials_emissive_strength", "KHR_materials_specular"};
// Extensions that change only how a surface looks, which the Blinn-Phong
// mapping approximates anyway: a file that requires one still loads, with
// its note. Every other required extension refuses the file: without it
// the geometry or the textures cannot be read (Draco, meshopt and
// quantized meshes, KTX2 and WebP images, GPU instancing).
constexpr std::array<std::string_view, 9> kAppearanceExtensions{"KHR_materials_pbrSpecularGlossiness",
                                                                 "KHR_materials_unlit",
                                                                 "KHR_materials_sheen",
                                                                 "KHR_materials_clearcoat",
                                                                 "KHR_materials_volume",
                                                                 "KHR_materials_iridescence",
                                                                 "KHR_materials_anisotropy",
                                                                 "KHR_materials_dispersion",
                                                                 "KHR_materials_variants"};

template <std::size_t N>
bool listed(const std::array<std::string_view, N>& list, std::string_view name) {
    return std::find(list.begin(), list.end(), name) != list.end();
}

std::string gltfQuoted(const std::string& s) {
    return "'" + s + "'";
}

std::string gltfCounted(std::size_t n, const std::string& singular, const std::string& plural) {
    return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

Transform transformOf(const aiMatrix4x4& m) {
    return Transform::fromRows({{{m.a1, m.a2, m.a3, m.a4}, {m.b1, m.b2, m.b3, m.b4}, {m.c1, m.c2, m.c3, m.c4}}});
}

Vec3 vec3Of(const aiVector3D& v) {
    return {v.x, v.y, v.z};
}

bool isFinite(const Rgb& c) {
    return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
}

bool isGrey(const Rgb& c) {
    return c.r == c.g && c.g == c.b;
}

// A node and where the hierarchy puts it.
struct PlacedNode {
    const aiNode* node;
    Transform world;
};

// A material as the file's objects use it: the mapped material, and how an
// object's texture coordinates are read for its base colour texture.
struct MappedMaterial {
    Material textured;  // with the base colour texture, if any
    Material plain;     // the same without it, for meshes without those coordinates
    bool hasTexture = false;
    unsigned uvChannel = 0;
    std::optional<GltfTextureTransform> uvTransform;
};

// An aiMesh in its own space, ready to be placed by each node that uses it.
struct LocalMesh {
    std::shared_ptr<const TriangleMesh> mesh;  // null when it has nothing to draw
    bool textured = false;                     // has the coordinates its material's texture needs
};

class GltfSceneBuilder {
public:
    GltfSceneBuilder(const fs::path& path, const GltfDocument& document, const aiScene& scene,
                     const GltfSceneOverrides& overrides)
        : path_(path), document_(document), ai_(scene), overrides_(overrides) {}

    Scene build() {
        Scene scene;
        scene.name = path_.stem().string();
        scene.environment = Environment::constant(kGltfBackground);
        noteExtensions();
        placeNodes();
        buildObjects(scene);
        const Box3 bounds = sceneBounds(scene);
        chooseCamera(scene, bounds);
        if (!overrides_.lights) buildLights(scene);
        noteWhatIsNotDrawn();
        scene.notes = std::move(notes_);
        return scene;
    }

private:
    // ---- errors and notes -------------------------------------------------

    [[noreturn]] void fail(const std::string& what) const {
        std::string oneLine = what;
        std::replace(oneLine.begin(), oneLine.end(), '\n', ' ');
        throw InputError(InputLocation{.file = path_.string()}, oneLine);
    }

    void note(const std::string& what) { notes_.push_back(path_.string() + ": " + what); }

    static std::string nameOf(const aiString& name, const std::string& kind, std::size_t index) {
        return name.length > 0 ? kind + " " + gltfQuoted(name.C_Str()) : kind + " " + std::to_string(index);
    }

    // ---- extensions -------------------------------------------------------

    void noteExtensions() {
        for (const std::string& e : document_.extensionsUsed) {
            if (listed(kReadExtensions, e) || e == "KHR_materials_pbrSpecularGlossiness") continue;
            note("ignored extension " + e + " (raycache does not read it)");
        }
        if (document_.textureTransformSetsTexCoord)
            note(
                "ignored the texCoord of KHR_texture_transform (Assimp 5.2 does not read it): the texture's own "
                "texture coordinate set is used");
        if (document_.sceneCount > 1)
            note("the file holds " + std::to_string(document_.sceneCount) + " scenes; scene " +
                 std::to_string(document_.defaultScene) + " (its default) is drawn");
    }

    // ---- the node hierarchy -----------------------------------------------

    // Every node with its world transform, parents before children, in file order.
    void placeNodes() {
        if (!ai_.mRootNode) return;
        std::vector<PlacedNode> stack{{ai_.mRootNode, transformOf(ai_.mRootNode->mTransformation)}};
        while (!stack.empty()) {
            const PlacedNode placed = stack.back();
            stack.pop_back();
            nodes_.push_back(placed);
            // Cameras and lights name their node; the first node of a name places them.
            nodeByName_.emplace(placed.node->mName.C_Str(), nodes_.size() - 1);
            for (unsigned i = placed.node->mNumChildren; i-- > 0;) {
                const aiNode* child = placed.node->mChildren[i];
                stack.push_back({child, placed.world * transformOf(child->mTransformation)});
            }
        }
    }

    const PlacedNode* nodeNamed(const aiString& name) const {
        if (name.length == 0) return nullptr;
        const auto it = nodeByName_.find(name.C_Str());
        return it == nodeByName_.end() ? nullptr : &nodes_[it->second];
    }

    // ---- materials --------------------------------------------------------

    float factor(const aiMaterial& m, const char* key, unsigned type, unsigned index, float fallback,
                 const std::string& materialName, const char* field, float lo, float hi) const {
        float v = fallback;
        if (m.Get(key, type, index, v) != AI_SUCCESS) return fallback;
        if (!(v >= lo && v <= hi))
            fail(materialName + ": " + field + " " + formatGeneral(v) + " is outside [" + formatGeneral(lo) + ", " +
                 formatGeneral(hi) + "]");
        return v;
    }

    Rgb color(const aiMaterial& m, const char* key, unsigned type, unsigned index, const Rgb& fallback,
              const std::string& materialName, const char* field) const {
        aiColor4D c;
        if (m.Get(key, type, index, c) != AI_SUCCESS) return fallback;
        const Rgb rgb{c.r, c.g, c.b};
        if (!isFinite(rgb) || rgb.r < 0.0f || rgb.g < 0.0f || rgb.b < 0.0f)
            fail(materialName + ": " + field + " [" + formatGeneral(c.r) + ", " + formatGeneral(c.g) + ", " +
                 formatGeneral(c.b) + "] must be finite and not negative");
        return rgb;
    }

    const MappedMaterial& material(unsigned index) {
        auto it = materials_.find(index);
        if (it != materials_.end()) return it->second;
        if (index >= ai_.mNumMaterials || !ai_.mMaterials[index])
            fail("mesh refers to material " + std::to_string(index) + ", which does not exist");
        const aiMaterial& m = *ai_.mMaterials[index];
        aiString aiName;
        m.Get(AI_MATKEY_NAME, aiName);
        const std::string name = nameOf(aiName, "material", index);

        PbrMaterial pbr;
        aiTextureType textureType = aiTextureType_BASE_COLOR;
        float glossiness = 0.0f;
        if (m.Get(AI_MATKEY_GLOSSINESS_FACTOR, glossiness) == AI_SUCCESS) {
            // KHR_materials_pbrSpecularGlossiness, read as metallic-roughness:
            // its diffuse is the base colour, 1 - glossiness the roughness.
            ++specularGlossiness_;
            if (!(glossiness >= 0.0f && glossiness <= 1.0f))
                fail(name + ": glossinessFactor " + formatGeneral(glossiness) + " is outside [0, 1]");
            pbr.baseColor = color(m, AI_MATKEY_COLOR_DIFFUSE, Rgb(1.0f), name, "diffuseFactor");
            pbr.metallic = 0.0f;
            pbr.roughness = 1.0f - glossiness;
            textureType = aiTextureType_DIFFUSE;
        } else {
            pbr.baseColor = color(m, AI_MATKEY_BASE_COLOR, Rgb(1.0f), name, "baseColorFactor");
            pbr.metallic = factor(m, AI_MATKEY_METALLIC_FACTOR, 1.0f, name, "metallicFactor", 0.0f, 1.0f);
            pbr.roughness = factor(m, AI_MATKEY_ROUGHNESS_FACTOR, 1.0f, name, "roughnessFactor", 0.0f, 1.0f);
        }
        pbr.transmission = factor(m, AI_MATKEY_TRANSMISSION_FACTOR, 0.0f, name, "transmissionFactor", 0.0f, 1.0f);
        float ior = 1.5f;
        if (m.Get(AI_MATKEY_REFRACTI, ior) == AI_SUCCESS && !(ior > 0.0f && std::isfinite(ior)))
            fail(name + ": ior " + formatGeneral(ior) + " must be a finite number > 0");
        pbr.ior = ior;

        MappedMaterial mapped;
        pbr.baseColorTexture =
            materialTexture(m, textureType, ImageEncoding::Srgb, name, "base colour texture", mapped);
        if (!overrides_.blinnPhongMaterials) {
            // glTF's metallicRoughnessTexture (Assimp's key for it).
            pbr.metallicRoughnessTexture = materialTexture(m, aiTextureType_UNKNOWN, ImageEncoding::Linear, name,
                                                           "metallic-roughness texture", mapped);
            pbr.normalTexture = materialTexture(m, aiTextureType_NORMALS, ImageEncoding::Linear, name,
                                                "normal texture", mapped);
            if (pbr.normalTexture) {
                pbr.normalScale = 1.0f;
                m.Get(AI_MATKEY_GLTF_TEXTURE_SCALE(aiTextureType_NORMALS, 0), pbr.normalScale);
                if (!std::isfinite(pbr.normalScale))
                    fail(name + ": normalTexture.scale " + formatGeneral(pbr.normalScale) + " must be finite");
            }
        }
        if (!overrides_.blinnPhongMaterials) {
            const GltfMaterialExtensions extensions = index < document_.materialExtensions.size()
                                                          ? document_.materialExtensions[index]
                                                          : GltfMaterialExtensions{};
            aiColor4D emissive(0, 0, 0, 0);
            m.Get(AI_MATKEY_COLOR_EMISSIVE, emissive);
            pbr.emission = Rgb{emissive.r, emissive.g, emissive.b} * extensions.emissiveStrength;
            pbr.specularFactor = extensions.specularFactor;
            pbr.specularColor = extensions.specularColor;
            if (extensions.specularTextures) ++specularTextures_;
            if (!isFinite(pbr.emission) || pbr.emission.r < 0.0f || pbr.emission.g < 0.0f || pbr.emission.b < 0.0f)
                fail(name + ": emissiveFactor must be finite and not negative");
        }
        const auto mapping = overrides_.blinnPhongMaterials ? blinnPhongFromPbr : metallicRoughnessFromPbr;
        mapped.textured = mapping(pbr);
        const bool textured = pbr.baseColorTexture != nullptr;
        pbr.baseColorTexture = nullptr;
        pbr.metallicRoughnessTexture = nullptr;
        pbr.normalTexture = nullptr;
        mapped.plain = mapping(pbr);
        const PbrMaterialKind kind = pbrMaterialKind(pbr);
        if (overrides_.blinnPhongMaterials) {
            if (kind == PbrMaterialKind::Mirror && !isGrey(pbr.baseColor)) ++tintedMirrors_;
            if (kind == PbrMaterialKind::Glass && !isGrey(pbr.baseColor)) ++tintedGlass_;
        } else if (kind == PbrMaterialKind::Glass && textured) {
            ++texturedGlass_;
        }
        noteIgnoredMaterialParts(m);
        return materials_.emplace(index, std::move(mapped)).first->second;
    }

    // The image of material `m`'s texture of `type`, decoded as `encoding`,
    // or null when it has none. A mesh carries one set of texture
    // coordinates: the material's first texture chooses it (its texCoord
    // and KHR_texture_transform, into `mapped`), and a later texture that
    // asks for another set is left out (and counted for a note).
    std::shared_ptr<const Image> materialTexture(const aiMaterial& m, aiTextureType type, ImageEncoding encoding,
                                                 const std::string& materialName, const std::string& role,
                                                 MappedMaterial& mapped) {
        aiString texture;
        if (m.GetTexture(type, 0, &texture) != AI_SUCCESS || texture.length == 0) return nullptr;
        unsigned channel = 0;
        if (int read = 0; m.Get(AI_MATKEY_UVWSRC(type, 0), read) == AI_SUCCESS && read >= 0)
            channel = static_cast<unsigned>(read);
        std::optional<GltfTextureTransform> transform;
        if (aiUVTransform read; m.Get(AI_MATKEY_UVTRANSFORM(type, 0), read) == AI_SUCCESS) {
            const GltfTextureTransform t = GltfTextureTransform::fromAssimp(read);
            if (!t.isIdentity()) transform = t;
        }
        if (mapped.hasTexture && (channel != mapped.uvChannel || transform != mapped.uvTransform)) {
            ++texturesOnOtherCoordinates_;
            return nullptr;
        }
        mapped.hasTexture = true;
        mapped.uvChannel = channel;
        mapped.uvTransform = transform;
        noteSampler(m, type);
        return textures_.image(texture.C_Str(), encoding, materialName, role);
    }

    void noteSampler(const aiMaterial& m, aiTextureType type) {
        int wrapU = aiTextureMapMode_Wrap, wrapV = aiTextureMapMode_Wrap;
        m.Get(AI_MATKEY_MAPPINGMODE_U(type, 0), wrapU);
        m.Get(AI_MATKEY_MAPPINGMODE_V(type, 0), wrapV);
        if (wrapU != aiTextureMapMode_Wrap || wrapV != aiTextureMapMode_Wrap) ++clampedOrMirroredTextures_;
        int magFilter = 0;
        constexpr int kNearest = 9728;  // glTF's (OpenGL's) NEAREST
        if (m.Get(AI_MATKEY_GLTF_MAPPINGFILTER_MAG(type, 0), magFilter) == AI_SUCCESS && magFilter == kNearest)
            ++nearestTextures_;
    }

    void noteIgnoredMaterialParts(const aiMaterial& m) {
        aiColor4D emissive(0, 0, 0, 0);
        m.Get(AI_MATKEY_COLOR_EMISSIVE, emissive);
        if (overrides_.blinnPhongMaterials && (emissive.r > 0.0f || emissive.g > 0.0f || emissive.b > 0.0f))
            ++emissive_;
        if (m.GetTextureCount(aiTextureType_EMISSIVE) > 0) ++emissiveTextures_;
        // The metallic-roughness model reads these two (materialTexture).
        if (overrides_.blinnPhongMaterials && m.GetTextureCount(aiTextureType_NORMALS) > 0) ++normalTextures_;
        if (m.GetTextureCount(aiTextureType_LIGHTMAP) > 0) ++occlusionTextures_;
        if (overrides_.blinnPhongMaterials &&
            (m.GetTextureCount(aiTextureType_METALNESS) > 0 || m.GetTextureCount(aiTextureType_DIFFUSE_ROUGHNESS) > 0))
            ++metallicRoughnessTextures_;
        aiString texture;
        if (m.GetTexture(aiTextureType_TRANSMISSION, 0, &texture) == AI_SUCCESS) ++transmissionTextures_;
        aiString alphaMode;
        if (m.Get(AI_MATKEY_GLTF_ALPHAMODE, alphaMode) == AI_SUCCESS) {
            const std::string mode = alphaMode.C_Str();
            if (mode == "BLEND" || mode == "MASK") ++alphaMaterials_;
        }
    }

    // ---- meshes -----------------------------------------------------------

    // The mesh in its own space, repaired by the mesh policy; converted once
    // however many nodes place it.
    const LocalMesh& localMesh(unsigned index) {
        auto it = meshes_.find(index);
        if (it != meshes_.end()) return it->second;
        const aiMesh& m = *ai_.mMeshes[index];
        LocalMesh local;
        std::size_t triangles = 0;
        for (unsigned f = 0; f < m.mNumFaces; ++f) triangles += m.mFaces[f].mNumIndices == 3 ? 1 : 0;
        otherPrimitives_ += m.mNumFaces - triangles;
        if (m.mNumBones > 0) ++skinnedMeshes_;
        if (m.mNumAnimMeshes > 0) ++morphedMeshes_;
        if (m.HasVertexColors(0)) ++coloredMeshes_;
        if (triangles == 0) return meshes_.emplace(index, std::move(local)).first->second;

        const MappedMaterial& mapped = material(m.mMaterialIndex);
        TriangleMesh mesh;
        mesh.positions.reserve(m.mNumVertices);
        for (unsigned i = 0; i < m.mNumVertices; ++i) mesh.positions.push_back(vec3Of(m.mVertices[i]));
        if (m.HasNormals())
            for (unsigned i = 0; i < m.mNumVertices; ++i) mesh.normals.push_back(vec3Of(m.mNormals[i]));
        const bool hasUvs = mapped.hasTexture && mapped.uvChannel < AI_MAX_NUMBER_OF_TEXTURECOORDS &&
                            m.HasTextureCoords(mapped.uvChannel);
        if (mapped.hasTexture && !hasUvs) ++texturedWithoutUvs_;
        if (hasUvs)
            for (unsigned i = 0; i < m.mNumVertices; ++i) {
                const aiVector3D& uv = m.mTextureCoords[mapped.uvChannel][i];
                const std::array<float, 2> read{uv.x, uv.y};
                mesh.uvs.push_back(mapped.uvTransform ? mapped.uvTransform->apply(read) : read);
            }
        for (unsigned f = 0; f < m.mNumFaces; ++f) {
            const aiFace& face = m.mFaces[f];
            if (face.mNumIndices == 3) mesh.triangles.push_back({face.mIndices[0], face.mIndices[1], face.mIndices[2]});
        }
        if (const std::string problem = indexOutOfRange(mesh); !problem.empty())
            fail("mesh " + gltfQuoted(m.mName.C_Str()) + ": " + problem);
        const MeshRepairs repairs = repairMesh(mesh);
        repairs_.trianglesRead += repairs.trianglesRead;
        repairs_.degenerateTriangles += repairs.degenerateTriangles;
        repairs_.vertices += repairs.vertices;
        repairs_.zeroLengthNormals += repairs.zeroLengthNormals;
        repairs_.nonFiniteNormals += repairs.nonFiniteNormals;
        if (!repairs.ignoredUvs.empty()) {
            ++meshesWithUnusableUvs_;
            if (firstUnusableUvs_.empty())
                firstUnusableUvs_ = "mesh " + gltfQuoted(m.mName.C_Str()) + ": " + repairs.ignoredUvs;
        }
        if (!validateMesh(mesh).empty()) {
            // Only degenerate triangles: nothing of it could be seen.
            allDegenerateTriangles_ += mesh.triangles.size();
            return meshes_.emplace(index, std::move(local)).first->second;
        }
        local.textured = !mesh.uvs.empty();
        local.mesh = std::make_shared<const TriangleMesh>(std::move(mesh));
        return meshes_.emplace(index, std::move(local)).first->second;
    }

    // ---- objects ----------------------------------------------------------

    void buildObjects(Scene& scene) {
        std::unordered_set<std::string> names;
        std::size_t vertices = 0, triangles = 0;
        for (const PlacedNode& placed : nodes_) {
            const aiNode& node = *placed.node;
            for (unsigned k = 0; k < node.mNumMeshes; ++k) {
                const unsigned index = node.mMeshes[k];
                const LocalMesh& local = localMesh(index);
                if (!local.mesh) continue;
                const std::string nodeName = node.mName.length > 0 ? node.mName.C_Str() : "node";
                std::shared_ptr<const TriangleMesh> world = local.mesh;
                if (!(placed.world == Transform()))
                    world = std::make_shared<const TriangleMesh>(transformed(*local.mesh, placed.world));
                checkWorldVertices(*world, nodeName);
                if (!validateMesh(*world).empty()) {
                    // A node scaled to nothing (a common way to hide a part): nothing to see.
                    ++collapsedInstances_;
                    continue;
                }
                vertices += world->positions.size();
                triangles += world->triangles.size();
                if (vertices > kMaxMeshVertices || triangles > kMaxMeshTriangles)
                    fail("the scene's meshes, every placement counted, have more than " +
                         std::to_string(kMaxMeshVertices) + " vertices or " + std::to_string(kMaxMeshTriangles) +
                         " triangles, the limit");
                if (scene.objects.size() == kMaxGltfObjects)
                    fail("the scene has more than " + std::to_string(kMaxGltfObjects) +
                         " objects (mesh placements), the limit");

                SceneObject object;
                object.name = uniqueName(node.mNumMeshes > 1 ? nodeName + "/" + std::to_string(k) : nodeName, names);
                const MappedMaterial& mapped = material(ai_.mMeshes[index]->mMaterialIndex);
                object.material = local.textured ? mapped.textured : mapped.plain;
                Box3 box;
                for (const Vec3& p : world->positions) box.add(p);
                // The caching cube is centred on the object: glTF files often
                // leave the node at the origin and place the part in its vertices.
                object.origin = (box.lo + box.hi) * 0.5f;
                object.shape = MeshShape{std::move(world)};
                scene.objects.push_back(std::move(object));
            }
        }
        if (scene.objects.empty()) {
            if (allDegenerateTriangles_ > 0)
                fail("all " + std::to_string(allDegenerateTriangles_) + " triangles are degenerate (zero area)");
            fail("the scene contains no triangles: nothing to draw");
        }
    }

    static std::string uniqueName(const std::string& wanted, std::unordered_set<std::string>& names) {
        std::string name = wanted;
        for (int n = 2; !names.insert(name).second; ++n) name = wanted + "#" + std::to_string(n);
        return name;
    }

    void checkWorldVertices(const TriangleMesh& mesh, const std::string& nodeName) const {
        std::size_t nonFinite = 0, outside = 0;
        for (const Vec3& p : mesh.positions) {
            if (!raycache::isFinite(p))
                ++nonFinite;
            else if (std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)}) > kMaxWorldCoordinate)
                ++outside;
        }
        if (nonFinite > 0)
            fail("node " + gltfQuoted(nodeName) + ": its transform makes " + std::to_string(nonFinite) + " of the mesh's " +
                 std::to_string(mesh.positions.size()) + " vertices non-finite (infinite or NaN)");
        if (outside > 0)
            fail("node " + gltfQuoted(nodeName) + ": " + std::to_string(outside) + " of the mesh's " +
                 std::to_string(mesh.positions.size()) + " vertices lie beyond ±" + formatGeneral(kMaxWorldCoordinate) +
                 " on some axis (floats are too coarse to trace beyond)");
    }

    static Box3 sceneBounds(const Scene& scene) {
        Box3 bounds;
        for (const SceneObject& o : scene.objects)
            for (const Vec3& p : std::get<MeshShape>(o.shape).mesh->positions) bounds.add(p);
        return bounds;
    }

    // ---- camera -----------------------------------------------------------

    void chooseCamera(Scene& scene, const Box3& bounds) {
        std::size_t orthographic = 0, unplaced = 0;
        std::optional<Camera> chosen;
        std::string chosenName;
        for (unsigned i = 0; i < ai_.mNumCameras; ++i) {
            const aiCamera& c = *ai_.mCameras[i];
            const std::string name = nameOf(c.mName, "camera", i);
            if (i < document_.orthographicCameras.size() && document_.orthographicCameras[i]) {
                ++orthographic;
                continue;
            }
            const PlacedNode* node = nodeNamed(c.mName);
            if (!node) {
                ++unplaced;
                continue;
            }
            if (chosen) continue;
            // Assimp 5.2 stores yfov * aspectRatio as the "horizontal" field of view; undo it.
            const float yfov = c.mAspect != 0.0f ? c.mHorizontalFOV / c.mAspect : c.mHorizontalFOV;
            const float degrees = yfov * 180.0f / std::numbers::pi_v<float>;
            if (!(degrees > 0.0f && degrees < 180.0f))
                fail(name + ": vertical field of view " + formatGeneral(degrees) + " degrees, must be between 0 and 180");
            // A glTF camera sits at its node's origin and looks down the
            // node's -z with +y up (aiCamera's mLookAt and mUp). Its
            // mPosition is not used: Assimp 5.2 copies the node's
            // translation there, which the node's transform applies again.
            Camera camera;
            camera.position = node->world.applyToPoint({0.0f, 0.0f, 0.0f});
            const Vec3 forward = node->world.applyToVector(vec3Of(c.mLookAt));
            const Vec3 up = node->world.applyToVector(vec3Of(c.mUp));
            if (!(length(forward) > 0.0f) || !raycache::isFinite(forward) || !(length(up) > 0.0f) ||
                !raycache::isFinite(camera.position) || !(length(cross(normalize(forward), normalize(up))) > 1e-4f))
                fail(name + ": its node's transform leaves no viewing direction or up direction");
            camera.lookAt = camera.position + normalize(forward);
            camera.up = normalize(up);
            camera.verticalFovDeg = degrees;
            chosen = camera;
            chosenName = name;
        }
        if (orthographic > 0)
            note("ignored " + gltfCounted(orthographic, "orthographic camera", "orthographic cameras") +
                 " (raycache's camera is a pinhole)");
        if (unplaced > 0)
            note("ignored " + gltfCounted(unplaced, "camera", "cameras") + " that no node of the scene places");
        if (chosen) {
            scene.camera = *chosen;
            const std::size_t others = ai_.mNumCameras - orthographic - unplaced - 1;
            if (others > 0)
                note("uses its first camera, " + chosenName + "; ignored " + gltfCounted(others, "other", "others"));
        } else {
            scene.camera = cameraFramingBounds(bounds);
            if (!overrides_.camera) note("no camera in the file: a camera framed on the scene's bounds is used");
        }
    }

    // ---- lights -----------------------------------------------------------

    void buildLights(Scene& scene) {
        std::size_t unplaced = 0, otherTypes = 0;
        for (unsigned i = 0; i < ai_.mNumLights; ++i) {
            const aiLight& l = *ai_.mLights[i];
            const std::string name = nameOf(l.mName, "light", i);
            Light light;
            switch (l.mType) {
                case aiLightSource_POINT:
                    light.type = LightType::Point;
                    break;
                case aiLightSource_SPOT:
                    light.type = LightType::Spot;
                    break;
                case aiLightSource_DIRECTIONAL:
                    light.type = LightType::Directional;
                    break;
                default:
                    ++otherTypes;
                    continue;
            }
            const PlacedNode* node = nodeNamed(l.mName);
            if (!node) {
                ++unplaced;
                continue;
            }
            // Assimp gives color * intensity: candela (point, spot) or lux
            // (directional), made radiometric (W/sr, W/m^2) by the 683 lm/W
            // that Blender's exporter multiplied its watts by, so that a
            // Blender scene renders at Blender's brightness (scene/Light.h).
            const Rgb power{l.mColorDiffuse.r, l.mColorDiffuse.g, l.mColorDiffuse.b};
            if (!isFinite(power) || power.r < 0.0f || power.g < 0.0f || power.b < 0.0f)
                fail(name + ": color times intensity must be finite and not negative");
            light.physical = true;
            light.intensity = power * (1.0f / kLumensPerWatt);
            float range = 0.0f;
            if (light.type != LightType::Directional && node->node->mMetaData &&
                node->node->mMetaData->Get("PBR_LightRange", range)) {
                if (!(range > 0.0f) || !std::isfinite(range)) fail(name + ": range must be finite and > 0");
                light.range = range;
            }
            if (light.type != LightType::Directional) {
                light.position = node->world.applyToPoint(vec3Of(l.mPosition));
                if (!raycache::isFinite(light.position))
                    fail(name + ": its node's transform puts it at no finite place");
            }
            if (light.type != LightType::Point) {
                const Vec3 direction = node->world.applyToVector(vec3Of(l.mDirection));
                if (!(length(direction) > 0.0f) || !raycache::isFinite(direction))
                    fail(name + ": its node's transform leaves it no direction");
                light.direction = normalize(direction);
            }
            if (light.type == LightType::Spot) {
                const float outer = l.mAngleOuterCone * 180.0f / std::numbers::pi_v<float>;
                const float inner = l.mAngleInnerCone * 180.0f / std::numbers::pi_v<float>;
                if (!(outer > 0.0f && outer <= 90.0f + 1e-3f))
                    fail(name + ": outerConeAngle " + formatGeneral(l.mAngleOuterCone) + " must lie in (0, pi/2]");
                if (!(inner >= 0.0f && inner <= outer))
                    fail(name + ": innerConeAngle " + formatGeneral(l.mAngleInnerCone) +
                         " must lie in [0, outerConeAngle]");
                light.coneAngleDeg = std::min(outer, 90.0f);
                light.falloffAngleDeg = light.coneAngleDeg - std::min(inner, light.coneAngleDeg);
            }
            if (scene.lights.size() == kMaxLights)
                fail("the file has more than " + std::to_string(kMaxLights) + " lights, the limit");
            scene.lights.push_back(light);
        }
        if (otherTypes > 0)
            note("ignored " + gltfCounted(otherTypes, "light", "lights") + " of a type glTF does not define");
        if (unplaced > 0) note("ignored " + gltfCounted(unplaced, "light", "lights") + " that no node of the scene places");
        if (scene.lights.empty()) {
            Light fallback = lightOverTheShoulder(scene.camera);
            if (!overrides_.blinnPhongMaterials) {
                // pi W/m^2: a white Lambert surface facing it shows 1, as under the Blinn-Phong mapping.
                fallback.physical = true;
                fallback.intensity = Rgb(std::numbers::pi_v<float>);
            }
            scene.lights.push_back(fallback);
            note("no lights in the file: a directional light over the camera's left shoulder is used");
        }
    }

    // ---- what is not drawn ------------------------------------------------

    void noteWhatIsNotDrawn() {
        if (skinnedMeshes_ > 0)
            note("ignored the skins of " + gltfCounted(skinnedMeshes_, "mesh", "meshes") +
                 ": drawn as stored, not posed by their joints");
        if (morphedMeshes_ > 0)
            note("ignored the morph targets of " + gltfCounted(morphedMeshes_, "mesh", "meshes") +
                 ": drawn in their base shape");
        if (ai_.mNumAnimations > 0)
            note("ignored " + gltfCounted(ai_.mNumAnimations, "animation", "animations") +
                 ": the scene is drawn still, as its nodes stand");
        if (coloredMeshes_ > 0) note("ignored the vertex colours of " + gltfCounted(coloredMeshes_, "mesh", "meshes"));
        if (otherPrimitives_ > 0)
            note("ignored " + std::to_string(otherPrimitives_) +
                 (otherPrimitives_ == 1 ? " point or line" : " points and lines") + " (only triangles are drawn)");
        if (collapsedInstances_ > 0)
            note("left out " + gltfCounted(collapsedInstances_, "mesh placement", "mesh placements") +
                 " that the node transform flattens to no area");
        if (specularGlossiness_ > 0)
            note("read " +
                 gltfCounted(specularGlossiness_, "KHR_materials_pbrSpecularGlossiness material",
                         "KHR_materials_pbrSpecularGlossiness materials") +
                 " as metallic-roughness (diffuse as base colour, 1 - glossiness as roughness, not metallic); their "
                 "specular colour and specular-glossiness texture are ignored");
        if (emissive_ > 0)
            note("ignored the emission of " + gltfCounted(emissive_, "material", "materials") +
                 " (the Blinn-Phong mapping's surfaces do not glow)");
        if (emissiveTextures_ > 0)
            note("ignored the emissive textures of " + gltfCounted(emissiveTextures_, "material", "materials") +
                 " (their factors are used)");
        if (specularTextures_ > 0)
            note("ignored the specular textures of " + gltfCounted(specularTextures_, "material", "materials") +
                 " (their factors are used)");
        if (normalTextures_ > 0)
            note("ignored the normal textures of " + gltfCounted(normalTextures_, "material", "materials") +
                 " (the Blinn-Phong mapping reads none)");
        if (occlusionTextures_ > 0)
            note("ignored the occlusion textures of " + gltfCounted(occlusionTextures_, "material", "materials"));
        if (metallicRoughnessTextures_ > 0)
            note("ignored the metallic-roughness textures of " +
                 gltfCounted(metallicRoughnessTextures_, "material", "materials") +
                 " (the Blinn-Phong mapping uses their factors)");
        if (texturesOnOtherCoordinates_ > 0)
            note("ignored " + gltfCounted(texturesOnOtherCoordinates_, "texture", "textures") +
                 " whose texture coordinates (texCoord or KHR_texture_transform) differ from their material's first "
                 "texture's: a mesh carries one set");
        if (transmissionTextures_ > 0)
            note("ignored the transmission textures of " + gltfCounted(transmissionTextures_, "material", "materials") +
                 " (their factors are used)");
        if (alphaMaterials_ > 0)
            note("ignored the alpha (BLEND or MASK) of " + gltfCounted(alphaMaterials_, "material", "materials") +
                 ": drawn opaque");
        if (clampedOrMirroredTextures_ > 0)
            note(gltfCounted(clampedOrMirroredTextures_, "texture asks", "textures ask") +
                 " to clamp or mirror at the edges: raycache's textures repeat");
        if (nearestTextures_ > 0)
            note(gltfCounted(nearestTextures_, "texture asks", "textures ask") +
                 " for nearest filtering: raycache's textures filter bilinearly");
        if (texturedWithoutUvs_ > 0)
            note(gltfCounted(texturedWithoutUvs_, "mesh has", "meshes have") +
                 " a textured material but not its texture coordinates: drawn with the material's factors");
        if (tintedMirrors_ > 0)
            note(gltfCounted(tintedMirrors_, "mirror material reflects", "mirror materials reflect") +
                 " untinted (kr is one number): the base colour tints only the highlight and the diffuse rest");
        if (tintedGlass_ > 0)
            note(gltfCounted(tintedGlass_, "glass material transmits", "glass materials transmit") +
                 " untinted (kt is one number): the base colour tints only the diffuse rest");
        if (texturedGlass_ > 0)
            note(gltfCounted(texturedGlass_, "glass material's", "glass materials'") +
                 " transmission is tinted by the base colour factor only (the base colour texture tints the "
                 "diffuse rest)");
        std::vector<std::string> repaired = repairs_.phrases();
        if (allDegenerateTriangles_ > 0)
            repaired.push_back("left out meshes of degenerate triangles only (" +
                               std::to_string(allDegenerateTriangles_) + " triangles)");
        if (meshesWithUnusableUvs_ > 0)
            repaired.push_back("ignored the texture coordinates of " +
                               gltfCounted(meshesWithUnusableUvs_, "mesh", "meshes") + " (" + firstUnusableUvs_ +
                               (meshesWithUnusableUvs_ > 1 ? ", ..." : "") + ")");
        if (!repaired.empty()) {
            std::string line;
            for (std::size_t i = 0; i < repaired.size(); ++i) line += (i ? "; " : "") + repaired[i];
            note(line);
        }
    }

    fs::path path_;
    const GltfDocument& document_;
    const aiScene& ai_;
    GltfSceneOverrides overrides_;
    std::vector<std::string> notes_;
    std::vector<PlacedNode> nodes_;
    std::unordered_map<std::string, std::size_t> nodeByName_;
    std::map<unsigned, MappedMaterial> materials_;
    std::map<unsigned, LocalMesh> meshes_;
    GltfTextureImages textures_{path_, ai_};
    MeshRepairs repairs_;  // summed over the meshes
    std::size_t allDegenerateTriangles_ = 0, meshesWithUnusableUvs_ = 0;
    std::string firstUnusableUvs_;
    std::size_t otherPrimitives_ = 0, skinnedMeshes_ = 0, morphedMeshes_ = 0, coloredMeshes_ = 0,
                collapsedInstances_ = 0, texturedWithoutUvs_ = 0, texturesOnOtherCoordinates_ = 0;
    std::size_t specularGlossiness_ = 0, emissive_ = 0, emissiveTextures_ = 0, specularTextures_ = 0,
                normalTextures_ = 0, occlusionTextures_ = 0, metallicRoughnessTextures_ = 0,
                transmissionTextures_ = 0, alphaMaterials_ = 0, clampedOrMirroredTextures_ = 0, nearestTextures_ = 0, tintedMirrors_ = 0, tintedGlass_ = 0;
    std::size_t texturedGlass_ = 0;  // metallic-roughness glass whose base colour is textured
};

}  // namespace

bool isGltfPath(const fs::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext == ".gltf" || ext == ".glb";
}

Scene loadGltfScene(const fs::path& path, const GltfSceneOverrides& overrides) {
    const InputLocation where{.file = path.string()};
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (!fs::exists(status)) throw InputError(where, "scene file not found");
    if (!fs::is_regular_file(status)) throw InputError(where, "scene file is not a regular file");

    const GltfDocument document = readGltfDocument(path);
    if (!document.isVersion2())
        throw InputError(
            where, "glTF " + (document.version.empty() ? std::string("file without asset.version") : document.version) +
                       ": raycache reads glTF 2.0 scenes (an older file still loads as a mesh of a JSON scene)");
    std::vector<std::string> unreadable;
    for (const std::string& e : document.extensionsRequired)
        if (!listed(kReadExtensions, e) && !listed(kAppearanceExtensions, e)) unreadable.push_back(e);
    if (!unreadable.empty()) {
        std::string names;
        for (std::size_t i = 0; i < unreadable.size(); ++i) names += (i ? ", " : "") + unreadable[i];
        throw InputError(where, "requires the extension" + std::string(unreadable.size() > 1 ? "s " : " ") + names +
                                    ", which raycache cannot read");
    }

    AssimpFileReader reader(path, AssimpFileReader::GltfJson::AlreadyChecked);
    // The node hierarchy is kept (no PreTransformVertices): objects, cameras
    // and lights are placed by it here. Normals are made by the mesh policy
    // (repairMesh), as for mesh files.
    const aiScene& scene = reader.postProcess(aiProcess_Triangulate);
    return GltfSceneBuilder(path, document, scene, overrides).build();
}

}  // namespace raycache
