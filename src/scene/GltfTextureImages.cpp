#include "scene/GltfTextureImages.h"

#include <algorithm>
#include <fstream>
#include <span>
#include <system_error>
#include <vector>

#include "core/ColorSpace.h"
#include "core/Errors.h"
#include "scene/GltfUri.h"
#include "scene/MeshLimits.h"

namespace raycache {
namespace fs = std::filesystem;

namespace {

// An embedded texture Assimp holds as BGRA texels (no glTF importer does,
// but the structure allows it), taken as 8-bit sRGB or data.
Image uncompressedImage(const aiTexture& texture, ImageEncoding encoding) {
    Image image(static_cast<int>(texture.mWidth), static_cast<int>(texture.mHeight));
    const auto decode = [encoding](unsigned char c) {
        const float v = static_cast<float>(c) / 255.0f;
        return encoding == ImageEncoding::Linear ? v : srgbToLinear(v);
    };
    for (unsigned y = 0; y < texture.mHeight; ++y)
        for (unsigned x = 0; x < texture.mWidth; ++x) {
            const aiTexel& t = texture.pcData[y * texture.mWidth + x];
            image.at(static_cast<int>(x), static_cast<int>(y)) = Rgb(decode(t.r), decode(t.g), decode(t.b));
        }
    return image;
}

}  // namespace

void GltfTextureImages::fail(const std::string& what) const {
    std::string oneLine = what;
    std::replace(oneLine.begin(), oneLine.end(), '\n', ' ');
    throw InputError(InputLocation{.file = path_.string()}, oneLine);
}

std::shared_ptr<const Image> GltfTextureImages::image(const std::string& reference, ImageEncoding encoding,
                                                      const std::string& materialName, const std::string& role) {
    std::shared_ptr<const Image>& cached = decoded_[{reference, encoding}];
    if (!cached)
        cached = std::make_shared<const Image>(reference[0] == '*'
                                                   ? embedded(reference, encoding, materialName, role)
                                                   : external(reference, encoding, materialName, role));
    return cached;
}

Image GltfTextureImages::embedded(const std::string& reference, ImageEncoding encoding,
                                  const std::string& materialName, const std::string& role) const {
    // In a .glb's buffer or a data: URI, decoded by Assimp into bytes.
    const auto [texture, index] = ai_.GetEmbeddedTextureAndIndex(reference.c_str());
    if (!texture) fail(materialName + ": " + role + " " + reference + " is not among the file's images");
    const std::string label = path_.string() + ": " + materialName + ": embedded image " + std::to_string(index);
    if (texture->mHeight != 0) return uncompressedImage(*texture, encoding);
    const auto* bytes = reinterpret_cast<const unsigned char*>(texture->pcData);
    return decodeImageBytes({bytes, texture->mWidth}, label, encoding);
}

Image GltfTextureImages::external(const std::string& reference, ImageEncoding encoding,
                                  const std::string& materialName, const std::string& role) const {
    const fs::path file = path_.parent_path() / fs::path(percentDecodedUri(reference));
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        fail(materialName + ": " + role + " file not found: \"" + reference + "\" (looked for " + file.string() + ")");
    const std::uintmax_t size = fs::file_size(file, ec);
    if (ec || size > kMaxMeshFileBytes)
        fail(materialName + ": cannot load " + role + " \"" + reference +
             "\": " + (ec ? ec.message() : "larger than " + std::to_string(kMaxMeshFileBytes) + " bytes"));
    // glTF names PNG and JPEG images by URI, not always with their extension:
    // the content decides.
    std::vector<unsigned char> bytes(static_cast<std::size_t>(size));
    std::ifstream in(file, std::ios::binary);
    in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!in || in.gcount() != static_cast<std::streamsize>(bytes.size()))
        fail(materialName + ": cannot read " + role + " \"" + reference + "\"");
    try {
        return decodeImageBytes(bytes, file.string(), encoding);
    } catch (const InputError& e) {
        fail(materialName + ": cannot load " + role + " \"" + reference + "\": " + e.what());
    }
}

}  // namespace raycache
