// The asan, tsan and fuzz presets (and every preset's tests) compile unity
// batches: eight .cpp files of one target in one translation unit, grouped by
// their order in CMakeLists.txt. Two files of a target that define the same
// name at the top of an anonymous namespace compile alone but not side by
// side, and which files share a batch changes whenever a file is added. This
// test names every such pair now, whatever the batches are today.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "TextPattern.h"
#include "scene/SourceTreePaths.h"

namespace raycache {
namespace {

std::string readSourceText(const std::filesystem::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Names declared at the top level of the file's anonymous namespaces
// (constants, functions, types); aliases are left out, since repeating an
// alias of the same thing is allowed.
std::set<std::string> anonymousNames(const std::string& text) {
    static const test::TextPattern type(R"(^(?:template\s*<[^>]*>\s*)?(?:struct|class|enum class|enum)\s+(\w+))");
    static const test::TextPattern value(
        R"(^(?:constexpr\s+|const\s+|static\s+|inline\s+)*[\w:<>,\s\*&]+?\s+[\*&]?(\w+)\s*(?:=|\(|\{|\[))");
    std::set<std::string> names;
    std::size_t at = 0;
    while ((at = text.find("\nnamespace {\n", at)) != std::string::npos) {
        std::size_t i = at + 13;
        int depth = 1;
        std::size_t j = i;
        while (depth > 0 && j < text.size()) {
            if (text[j] == '{') ++depth;
            else if (text[j] == '}') --depth;
            ++j;
        }
        std::istringstream block(text.substr(i, j - i));
        std::string line;
        while (std::getline(block, line)) {
            if (line.empty() || std::string(" \t}/#").find(line[0]) != std::string::npos) continue;
            if (line.rfind("using ", 0) == 0 || line.rfind("namespace ", 0) == 0) continue;
            std::optional<std::vector<std::string>> m = type.firstMatch(line);
            if (!m) m = value.firstMatch(line);
            if (m) names.insert((*m)[1]);
        }
        at = j;
    }
    return names;
}

// "name" of every file the same target compiles (`files`), told apart: one
// message per name that two or more of them define.
std::vector<std::string> repeatedNames(const std::string& target, const std::vector<std::filesystem::path>& files) {
    std::map<std::string, std::vector<std::string>> where;
    for (const auto& f : files)
        for (const std::string& n : anonymousNames(readSourceText(f))) where[n].push_back(f.filename().string());
    std::vector<std::string> out;
    for (const auto& [name, in] : where)
        if (in.size() > 1) {
            std::string message = target + ": '" + name + "' in";
            for (const std::string& f : in) message += " " + f;
            out.push_back(message);
        }
    return out;
}

}  // namespace

TEST(UnityBatchNames, NoTwoLibraryFilesShareAnAnonymousName) {
    const std::filesystem::path src = sourceTreeDir() / "src";
    ASSERT_TRUE(std::filesystem::is_directory(src)) << src;
    // src/viewer is a library of its own (raycache_viewer); the rest is raycache_lib.
    std::vector<std::filesystem::path> library, viewer;
    for (const auto& e : std::filesystem::recursive_directory_iterator(src))
        if (e.path().extension() == ".cpp")
            (e.path().parent_path().filename() == "viewer" ? viewer : library).push_back(e.path());
    ASSERT_GT(library.size(), 50u);
    std::vector<std::string> found = repeatedNames("raycache_lib", library);
    for (const std::string& m : repeatedNames("raycache_viewer", viewer)) found.push_back(m);
    for (const std::string& m : found) ADD_FAILURE() << m << ": rename one (unity batches would meet them)";
}

TEST(UnityBatchNames, NoTwoFilesOfATestTargetShareAnAnonymousName) {
    const std::filesystem::path tests = sourceTreeDir() / "tests";
    const std::string cmake = readSourceText(tests / "CMakeLists.txt");
    // raycache_add_test(<target> ... SOURCES a.cpp b.cpp) and target_sources(<target> PRIVATE ...).
    static const test::TextPattern call(R"((?:raycache_add_test|target_sources)\((\w+)([^)]*)\))");
    static const test::TextPattern cpp(R"([\w/]+\.cpp)");
    std::map<std::string, std::vector<std::filesystem::path>> targets;
    for (const std::vector<std::string>& c : call.everyMatch(cmake))
        for (const std::vector<std::string>& file : cpp.everyMatch(c[2]))
            if (std::filesystem::exists(tests / file[0])) targets[c[1]].push_back(tests / file[0]);
    ASSERT_GT(targets.size(), 10u);
    for (const auto& [target, files] : targets)
        for (const std::string& m : repeatedNames(target, files))
            ADD_FAILURE() << m << ": rename one (unity batches would meet them)";
}

// A file that includes core/LaneLevelsInclude.h defines each lane level's
// pieces (core/LanePieces.inc): two such files in one batch do not compile,
// so src/CMakeLists.txt keeps every one of them out of the batches.
TEST(UnityBatchNames, EveryLaneLevelFileIsKeptOutOfUnityBatches) {
    const std::filesystem::path src = sourceTreeDir() / "src";
    const std::string cmake = readSourceText(src / "CMakeLists.txt");
    const std::size_t skip = cmake.find("SKIP_UNITY_BUILD_INCLUSION");
    ASSERT_NE(skip, std::string::npos);
    const std::size_t listStart = cmake.rfind("set_source_files_properties(", skip);
    ASSERT_NE(listStart, std::string::npos);
    const std::string skipped = cmake.substr(listStart, skip - listStart);
    int laneFiles = 0;
    for (const auto& e : std::filesystem::recursive_directory_iterator(src)) {
        if (e.path().extension() != ".cpp") continue;
        if (readSourceText(e.path()).find("#include \"core/LaneLevelsInclude.h\"") == std::string::npos) continue;
        ++laneFiles;
        const std::string relative = std::filesystem::relative(e.path(), src).generic_string();
        EXPECT_NE(skipped.find(relative), std::string::npos)
            << relative << " includes core/LaneLevelsInclude.h: add it to the SKIP_UNITY_BUILD_INCLUSION list";
    }
    EXPECT_GE(laneFiles, 10);
}

TEST(UnityBatchNames, FindsARepeatedConstantAndIgnoresAliases) {
    const std::string a = "x\nnamespace {\nconstexpr float kLimit = 1.0f;\nusing Clock = int;\n}\n";
    const std::string b = "y\nnamespace {\nint helper(int v) {\n    return v;\n}\nusing Clock = int;\n}\n";
    EXPECT_EQ(anonymousNames(a), (std::set<std::string>{"kLimit"}));
    EXPECT_EQ(anonymousNames(b), (std::set<std::string>{"helper"}));
}

}  // namespace raycache
