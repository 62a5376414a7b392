#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "TempDir.h"
#include "bench/ExperimentTransfer.h"

namespace raycache {
namespace {

void writeFile(const std::filesystem::path& path, const std::string& content) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << content;
}

std::string readFile(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

ExperimentOutput sampleOutput() {
    ExperimentOutput output;
    output.name = "table-5.1";
    output.title = "Table 5.1";
    output.markdown = "| a | b |\n";
    output.plots = {"speed.svg"};
    output.images = {"images/frame.png"};
    output.headlines = {"CCT 2.0x", "CDCT 0.5x"};
    output.caveats = {};
    return output;
}

// What another process wrote arrives whole at process 0: the output's
// fields and every file, in subdirectories too, binary content included.
TEST(ExperimentTransfer, OutputAndFilesArriveWhole) {
    TempDir from("from"), to("to");
    const std::string binary("\x89PNG\0\r\n\x1a\n", 9);
    writeFile(from.path() / "results.md", "# Table 5.1\n");
    writeFile(from.path() / "images" / "frame.png", binary);
    writeFile(from.path() / "speed.svg", "<svg/>");
    Bytes bytes;
    packExperiment(bytes, sampleOutput(), from.path());

    ByteReader reader(bytes);
    const ExperimentOutput got = unpackExperiment(reader, to.path() / "table-5.1");
    EXPECT_TRUE(reader.atEnd());
    const ExperimentOutput want = sampleOutput();
    EXPECT_EQ(got.name, want.name);
    EXPECT_EQ(got.title, want.title);
    EXPECT_EQ(got.markdown, want.markdown);
    EXPECT_EQ(got.plots, want.plots);
    EXPECT_EQ(got.images, want.images);
    EXPECT_EQ(got.headlines, want.headlines);
    EXPECT_EQ(got.caveats, want.caveats);
    EXPECT_EQ(readFile(to.path() / "table-5.1" / "results.md"), "# Table 5.1\n");
    EXPECT_EQ(readFile(to.path() / "table-5.1" / "images" / "frame.png"), binary);
    EXPECT_EQ(readFile(to.path() / "table-5.1" / "speed.svg"), "<svg/>");
}

TEST(ExperimentTransfer, TruncatedMessageThrowsAndWritesNothingPartial) {
    TempDir from("from"), to("to");
    writeFile(from.path() / "results.md", std::string(1000, 'x'));
    Bytes bytes;
    packExperiment(bytes, sampleOutput(), from.path());
    bytes.resize(bytes.size() - 10);  // the file's content cut short
    ByteReader reader(bytes);
    EXPECT_THROW(unpackExperiment(reader, to.path()), std::out_of_range);
    EXPECT_FALSE(std::filesystem::exists(to.path() / "results.md"));
}

// A message naming a file outside the experiment's directory is refused
// before anything is written.
TEST(ExperimentTransfer, PathLeavingTheDirectoryIsRefused) {
    TempDir from("from"), to("to");
    writeFile(from.path() / "xx" / "results.md", "x");
    Bytes bytes;
    packExperiment(bytes, sampleOutput(), from.path());
    const std::string inside = "xx/results.md";
    const std::string outside = "../results.md";
    ASSERT_EQ(inside.size(), outside.size());
    const auto at = std::search(bytes.begin(), bytes.end(), reinterpret_cast<const std::byte*>(inside.data()),
                                reinterpret_cast<const std::byte*>(inside.data() + inside.size()));
    ASSERT_NE(at, bytes.end());
    std::copy(reinterpret_cast<const std::byte*>(outside.data()),
              reinterpret_cast<const std::byte*>(outside.data() + outside.size()), at);
    ByteReader reader(bytes);
    EXPECT_THROW(unpackExperiment(reader, to.path() / "exp"), std::runtime_error);
    EXPECT_FALSE(std::filesystem::exists(to.path() / "results.md"));
}

}  // namespace
}  // namespace raycache
