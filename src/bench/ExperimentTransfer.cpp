#include "bench/ExperimentTransfer.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/AtomicFile.h"
#include "core/Errors.h"

namespace raycache {

namespace {

void appendString(Bytes& out, const std::string& text) {
    appendBytes(out, static_cast<std::uint64_t>(text.size()));
    appendBytes(out, std::span<const char>(text.data(), text.size()));
}

std::string readString(ByteReader& reader) {
    std::string text(static_cast<std::size_t>(reader.read<std::uint64_t>()), '\0');
    // A corrupt length makes readInto throw before anything is read.
    reader.readInto(std::span<char>(text.data(), text.size()));
    return text;
}

void appendStrings(Bytes& out, const std::vector<std::string>& texts) {
    appendBytes(out, static_cast<std::uint64_t>(texts.size()));
    for (const std::string& t : texts) appendString(out, t);
}

std::vector<std::string> readStrings(ByteReader& reader) {
    const auto count = reader.read<std::uint64_t>();
    std::vector<std::string> texts;
    for (std::uint64_t i = 0; i < count; ++i) texts.push_back(readString(reader));
    return texts;
}

std::string fileContent(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string content((std::istreambuf_iterator<char>(in)), {});
    if (!in.eof() && in.fail()) throw RuntimeError(path.string() + ": cannot read it back to send it to process 0");
    return content;
}

// `relative` as a path inside `dir`, refusing anything that would leave it.
std::filesystem::path inside(const std::filesystem::path& dir, const std::string& relative) {
    const std::filesystem::path rel = std::filesystem::path(relative).lexically_normal();
    if (relative.empty() || rel.is_absolute() || rel.has_root_name() || *rel.begin() == "..")
        throw std::runtime_error("experiment file from another process with a path outside its directory: " + relative);
    return dir / rel;
}

}  // namespace

void packExperiment(Bytes& out, const ExperimentOutput& output, const std::filesystem::path& dir) {
    appendString(out, output.name);
    appendString(out, output.title);
    appendString(out, output.markdown);
    appendStrings(out, output.plots);
    appendStrings(out, output.images);
    appendStrings(out, output.headlines);
    appendStrings(out, output.caveats);
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
        if (entry.is_regular_file()) files.push_back(entry.path());
    std::sort(files.begin(), files.end());  // the same message whatever the directory order
    appendBytes(out, static_cast<std::uint64_t>(files.size()));
    for (const std::filesystem::path& file : files) {
        appendString(out, file.lexically_relative(dir).generic_string());
        appendString(out, fileContent(file));
    }
}

ExperimentOutput unpackExperiment(ByteReader& reader, const std::filesystem::path& dir) {
    ExperimentOutput output;
    output.name = readString(reader);
    output.title = readString(reader);
    output.markdown = readString(reader);
    output.plots = readStrings(reader);
    output.images = readStrings(reader);
    output.headlines = readStrings(reader);
    output.caveats = readStrings(reader);
    const auto files = reader.read<std::uint64_t>();
    for (std::uint64_t i = 0; i < files; ++i) {
        const std::filesystem::path path = inside(dir, readString(reader));
        const std::string content = readString(reader);
        std::error_code ec;
        std::filesystem::create_directories(path.parent_path(), ec);
        if (ec) throw RuntimeError("cannot create " + path.parent_path().string() + ": " + ec.message());
        writeFileAtomically(path, [&](const std::filesystem::path& temp) {
            std::ofstream file(temp, std::ios::binary);
            file.write(content.data(), static_cast<std::streamsize>(content.size()));
            file.close();
            if (!file) throw RuntimeError(temp.string() + ": cannot write");
        });
    }
    return output;
}

}  // namespace raycache
