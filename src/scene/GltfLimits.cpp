#include "scene/GltfLimits.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "core/Errors.h"
#include "scene/GltfNodeGraph.h"
#include "scene/GltfUri.h"

namespace raycache {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();

std::uint64_t sumOrMax(std::uint64_t a, std::uint64_t b) {
    return a > kSaturated - b ? kSaturated : a + b;
}

std::uint64_t productOrMax(std::uint64_t a, std::uint64_t b) {
    return b != 0 && a > kSaturated / b ? kSaturated : a * b;
}

// A member that is an integer >= 0; nothing if it is absent or of another
// type (Assimp's reader then takes its default or refuses the file itself).
std::optional<std::uint64_t> unsignedMember(const json& object, const char* key) {
    if (!object.is_object()) return std::nullopt;
    const auto it = object.find(key);
    if (it == object.end() || !it->is_number_integer()) return std::nullopt;
    if (!it->is_number_unsigned() && it->get<std::int64_t>() < 0) return std::nullopt;
    return it->get<std::uint64_t>();
}

std::size_t entriesOf(const json& root, const char* key) {
    const auto it = root.find(key);
    return it != root.end() && (it->is_array() || it->is_object()) ? it->size() : 0;
}

// The bytes of one element of an accessor (glTF 2.0, 3.6.2), 0 for an
// unknown type. Assimp's defaults: componentType BYTE, type SCALAR.
std::uint64_t elementBytes(const json& accessor, const char* componentTypeKey = "componentType") {
    const std::uint64_t componentType = unsignedMember(accessor, componentTypeKey).value_or(5120);
    std::uint64_t componentBytes = 0;
    if (componentType == 5120 || componentType == 5121) componentBytes = 1;
    if (componentType == 5122 || componentType == 5123) componentBytes = 2;
    if (componentType == 5125 || componentType == 5126) componentBytes = 4;
    std::string type = "SCALAR";
    if (const auto it = accessor.find("type"); it != accessor.end() && it->is_string()) type = it->get<std::string>();
    static constexpr std::array<std::pair<std::string_view, std::uint64_t>, 7> kComponents{
        {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT2", 4}, {"MAT3", 9}, {"MAT4", 16}}};
    for (const auto& [name, components] : kComponents)
        if (type == name) return components * componentBytes;
    return 0;
}

// How many bytes a base64 data: URI decodes to, or nothing for another URI.
std::optional<std::uint64_t> base64DataBytes(const std::string& uri) {
    if (uri.rfind("data:", 0) != 0) return std::nullopt;
    const std::size_t comma = uri.find(',');
    if (comma == std::string::npos || comma < 7 || uri.compare(comma - 7, 7, ";base64") != 0) return std::nullopt;
    std::uint64_t digits = uri.size() - comma - 1;
    for (std::size_t i = uri.size(); i > comma + 1 && uri[i - 1] == '='; --i) --digits;
    return digits * 3 / 4;
}

class GltfLimitCheck {
public:
    GltfLimitCheck(const fs::path& path, const json& root, const GltfFileLayout& layout)
        : path_(path), root_(root), layout_(layout) {}

    void run() {
        checkCount("nodes", kMaxGltfNodes);
        checkCount("meshes", kMaxGltfMeshes);
        checkCount("accessors", kMaxGltfAccessors);
        checkCount("bufferViews", kMaxGltfBufferViews);
        checkCount("buffers", kMaxGltfBuffers);
        checkCount("images", kMaxGltfImages);
        checkGltfNodeGraph(path_, root_);
        // glTF 1.0 names its buffers, views and accessors by id, and only the
        // counts and the node graph are checked there.
        if (byIndex("buffers")) checkBuffers();
        if (byIndex("bufferViews")) checkBufferViews();
        if (byIndex("accessors")) checkAccessors();
        if (byIndex("images")) checkImageTypes();
    }

private:
    [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
        throw InputError(InputLocation{.file = path_.string(), .jsonPath = pointer}, what);
    }

    // Whether `key` is absent or an array (glTF 2.0), not glTF 1.0's object of ids.
    bool byIndex(const char* key) const {
        const auto it = root_.find(key);
        return it == root_.end() || it->is_array();
    }

    // The array under `key`, or an empty one (never a copy).
    const json& arrayOf(const char* key) const {
        const auto it = root_.find(key);
        return it != root_.end() && it->is_array() ? *it : empty_;
    }

    void checkCount(const char* key, std::size_t limit) const {
        const std::size_t count = entriesOf(root_, key);
        if (count > limit)
            fail("/" + std::string(key),
                 "has " + std::to_string(count) + " " + key + ", more than the limit of " + std::to_string(limit));
    }

    // The bytes the buffer's data holds: its GLB chunk, its data: URI, or
    // the file it names; nothing when unknown (a missing file, which
    // Assimp's reader then refuses).
    std::optional<std::uint64_t> bytesAvailable(const json& buffer, std::size_t index, std::string& where) const {
        const auto uri = buffer.find("uri");
        if (uri == buffer.end() || !uri->is_string()) {
            if (!layout_.binary || index != 0) return std::nullopt;
            where = "the file's binary chunk";
            return layout_.binaryChunkBytes;
        }
        const std::string text = uri->get<std::string>();
        if (const auto bytes = base64DataBytes(text)) {
            where = "its data: URI";
            return bytes;
        }
        if (text.rfind("data:", 0) == 0) return std::nullopt;
        for (const std::string& name : {text, percentDecodedUri(text)}) {
            std::error_code ec;
            const fs::path file = path_.parent_path() / name;
            if (!fs::is_regular_file(file, ec)) continue;
            const std::uintmax_t bytes = fs::file_size(file, ec);
            if (ec) continue;
            where = json(text).dump(-1, ' ', false, json::error_handler_t::replace);
            return bytes;
        }
        return std::nullopt;
    }

    void checkBuffers() {
        const json& buffers = arrayOf("buffers");
        std::uint64_t total = 0;
        for (std::size_t i = 0; i < buffers.size(); ++i) {
            const std::uint64_t bytes = unsignedMember(buffers[i], "byteLength").value_or(0);
            bufferBytes_.push_back(bytes);
            const std::string pointer = "/buffers/" + std::to_string(i) + "/byteLength";
            total = sumOrMax(total, bytes);
            if (total > kMaxGltfBufferBytes)
                fail(pointer, "the buffers hold " + std::to_string(total) + " bytes up to this one, more than the limit of " +
                                  std::to_string(kMaxGltfBufferBytes) + " for all together");
            std::string where;
            if (const auto available = bytesAvailable(buffers[i], i, where); available && bytes > *available)
                fail(pointer, std::to_string(bytes) + " bytes, more than the " + std::to_string(*available) +
                                  " bytes of " + where);
        }
    }

    void checkBufferViews() {
        const json& views = arrayOf("bufferViews");
        for (std::size_t i = 0; i < views.size(); ++i) {
            const json& view = views[i];
            const std::string pointer = "/bufferViews/" + std::to_string(i);
            const std::uint64_t buffer = unsignedMember(view, "buffer").value_or(kSaturated);
            if (buffer >= bufferBytes_.size())
                fail(pointer + "/buffer", "names no buffer (the file has " + std::to_string(bufferBytes_.size()) + ")");
            const std::uint64_t offset = unsignedMember(view, "byteOffset").value_or(0);
            const std::uint64_t length = unsignedMember(view, "byteLength").value_or(0);
            if (sumOrMax(offset, length) > bufferBytes_[buffer])
                fail(pointer, "bytes " + std::to_string(offset) + " to " + std::to_string(sumOrMax(offset, length)) +
                                  " lie beyond the " + std::to_string(bufferBytes_[buffer]) + " bytes of buffer " +
                                  std::to_string(buffer));
            viewBytes_.push_back(length);
            viewStrides_.push_back(unsignedMember(view, "byteStride").value_or(0));
        }
    }

    // `count` elements of `bytes` each, `stride` apart from `offset` (a
    // stride of 0: packed), must lie within buffer view `view`.
    void checkWithinView(const json& owner, const std::string& pointer, std::uint64_t view, std::uint64_t offset,
                         std::uint64_t count, std::uint64_t bytes, std::uint64_t stride) const {
        if (view >= viewBytes_.size())
            fail(pointer + "/bufferView", owner.contains("bufferView") ? "names no buffer view (the file has " +
                                                                             std::to_string(viewBytes_.size()) + ")"
                                                                       : "missing");
        if (count == 0 || bytes == 0) return;
        const std::uint64_t step = stride != 0 ? stride : bytes;
        const std::uint64_t end = sumOrMax(sumOrMax(offset, productOrMax(count - 1, step)), bytes);
        if (end > viewBytes_[view])
            fail(pointer, std::to_string(count) + " elements of " + std::to_string(bytes) + " bytes, " +
                              std::to_string(step) + " bytes apart from byte " + std::to_string(offset) +
                              ", end at byte " + std::to_string(end) + ", beyond the " +
                              std::to_string(viewBytes_[view]) + " bytes of buffer view " + std::to_string(view));
    }

    void checkAccessors() const {
        const json& accessors = arrayOf("accessors");
        for (std::size_t i = 0; i < accessors.size(); ++i) {
            const json& accessor = accessors[i];
            const std::string pointer = "/accessors/" + std::to_string(i);
            const std::uint64_t count = unsignedMember(accessor, "count").value_or(0);
            if (count > kMaxGltfAccessorElements)
                fail(pointer + "/count", std::to_string(count) + " elements, more than the limit of " +
                                             std::to_string(kMaxGltfAccessorElements));
            const std::uint64_t bytes = elementBytes(accessor);
            if (const auto view = unsignedMember(accessor, "bufferView")) {
                const std::uint64_t stride = *view < viewStrides_.size() ? viewStrides_[*view] : 0;
                checkWithinView(accessor, pointer, *view, unsignedMember(accessor, "byteOffset").value_or(0), count,
                                bytes, stride);
            } else if (productOrMax(count, bytes) > kMaxGltfBufferBytes) {
                fail(pointer + "/count", std::to_string(count) + " elements of " + std::to_string(bytes) +
                                             " bytes without a buffer view (zeros), more than the limit of " +
                                             std::to_string(kMaxGltfBufferBytes) + " bytes");
            }
            if (accessor.is_object() && accessor.contains("sparse")) checkSparse(accessor, pointer, count, bytes);
        }
    }

    // A sparse accessor replaces some of its elements: Assimp reads as many
    // indices and values as its count says from the views they name.
    void checkSparse(const json& accessor, const std::string& pointer, std::uint64_t count,
                     std::uint64_t bytes) const {
        const json& sparse = accessor["sparse"];
        const std::string sparsePointer = pointer + "/sparse";
        if (!sparse.is_object()) fail(sparsePointer, "not an object");
        const std::uint64_t replaced = unsignedMember(sparse, "count").value_or(0);
        if (replaced > count)
            fail(sparsePointer + "/count", std::to_string(replaced) + " elements, more than the accessor's " +
                                               std::to_string(count));
        for (const char* part : {"indices", "values"}) {
            const std::string partPointer = sparsePointer + "/" + part;
            const auto it = sparse.find(part);
            if (it == sparse.end() || !it->is_object()) fail(partPointer, "missing");
            const std::uint64_t partBytes = std::string_view(part) == "indices" ? elementBytes(*it) : bytes;
            checkWithinView(*it, partPointer, unsignedMember(*it, "bufferView").value_or(kSaturated),
                            unsignedMember(*it, "byteOffset").value_or(0), replaced, partBytes, 0);
        }
    }

    // Assimp 5.2 takes what follows the '/' of an embedded image's MIME type
    // as its format hint without looking whether there is one (a crash,
    // found by fuzzing): its "mimeType", or its data: URI's media type.
    void checkImageTypes() const {
        const json& images = arrayOf("images");
        for (std::size_t i = 0; i < images.size(); ++i) {
            if (!images[i].is_object()) continue;
            const std::string pointer = "/images/" + std::to_string(i);
            if (const auto type = images[i].find("mimeType"); type != images[i].end() && type->is_string()) {
                const std::string text = type->get<std::string>();
                if (text.find('/') == std::string::npos)
                    fail(pointer + "/mimeType", quoted(text) + " is not a MIME type (type/subtype, e.g. image/png)");
            }
            const auto uri = images[i].find("uri");
            if (uri == images[i].end() || !uri->is_string()) continue;
            const std::string text = uri->get<std::string>();
            const std::size_t comma = text.find(',');
            if (text.rfind("data:", 0) != 0 || comma == std::string::npos) continue;
            // The media type runs to the first ';' or ','; without one, text/plain is meant.
            const std::string mediaType = text.substr(5, std::min(text.find(';', 5), comma) - 5);
            if (!mediaType.empty() && mediaType.find('/') == std::string::npos)
                fail(pointer + "/uri", "the data: URI's media type " + quoted(mediaType) +
                                           " is not a MIME type (type/subtype, e.g. image/png)");
        }
    }

    static std::string quoted(const std::string& text) {
        return json(text).dump(-1, ' ', false, json::error_handler_t::replace);
    }

    const fs::path& path_;
    const json& root_;
    const GltfFileLayout& layout_;
    const json empty_ = json::array();
    std::vector<std::uint64_t> bufferBytes_;
    std::vector<std::uint64_t> viewBytes_;
    std::vector<std::uint64_t> viewStrides_;
};

}  // namespace

void checkGltfLimits(const fs::path& path, const json& root, const GltfFileLayout& layout) {
    GltfLimitCheck(path, root, layout).run();
}

}  // namespace raycache
