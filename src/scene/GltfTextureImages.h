#pragma once
// The images of a glTF file's textures, as Assimp names them ("*N" for an
// image embedded in a .glb's buffer or a data: URI, else a URI beside the
// file), each decoded once however many materials use it: as an sRGB colour
// (base colour) or as data (metallic-roughness, normals).
#include <assimp/scene.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "core/Image.h"
#include "scene/ImageLoader.h"

namespace raycache {

class GltfTextureImages {
public:
    // `scene` is the file at `path` as Assimp read it; both outlive this.
    GltfTextureImages(const std::filesystem::path& path, const aiScene& scene) : path_(path), ai_(scene) {}

    // The image `reference` names, decoded as `encoding` says. Throws
    // InputError naming the file, the material and `role` ("base colour
    // texture") when the image is missing, too large or undecodable.
    std::shared_ptr<const Image> image(const std::string& reference, ImageEncoding encoding,
                                       const std::string& materialName, const std::string& role);

private:
    [[noreturn]] void fail(const std::string& what) const;
    Image embedded(const std::string& reference, ImageEncoding encoding, const std::string& materialName,
                   const std::string& role) const;
    Image external(const std::string& reference, ImageEncoding encoding, const std::string& materialName,
                   const std::string& role) const;

    const std::filesystem::path& path_;
    const aiScene& ai_;
    std::map<std::pair<std::string, ImageEncoding>, std::shared_ptr<const Image>> decoded_;
};

}  // namespace raycache
