// Mutated scene files must be rejected with an InputError (or load), never
// crash or throw anything else. Deterministic: fixed seed, fixed mutations.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "TempDir.h"
#include "core/Errors.h"
#include "scene/SceneFile.h"

namespace fs = std::filesystem;
using namespace raycache;

namespace {

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace

TEST(SceneFileRobustness, MutatedExampleNeverCrashes) {
    const fs::path source = fs::path(RAYCACHE_SOURCE_DIR) / "examples" / "scenes";
    const std::string original = readFile(source / "example.json");
    ASSERT_FALSE(original.empty());
    // Written next to the example so its relative mesh paths still resolve.
    const fs::path dir = scratchPathForThisTest("raycache-scene-fuzz-");
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy(source / "meshes", dir / "meshes", fs::copy_options::recursive);
    const fs::path file = dir / "mutated.json";

    std::mt19937 rng(20261121u);
    const std::string alphabet = "{}[]\":,0123456789.-eE+ tfnaluxyz\\\n";
    int loaded = 0, rejected = 0;
    for (int i = 0; i < 400; ++i) {
        std::string text = original;
        const int edits = 1 + static_cast<int>(rng() % 4);
        for (int e = 0; e < edits; ++e) {
            const std::size_t at = rng() % text.size();
            switch (rng() % 4) {
            case 0: text[at] = alphabet[rng() % alphabet.size()]; break;           // replace
            case 1: text.erase(at, 1 + rng() % 8); break;                           // delete
            case 2: text.insert(at, 1, alphabet[rng() % alphabet.size()]); break;  // insert
            default: text.resize(at); break;                                         // truncate
            }
            if (text.empty()) text = "{";
        }
        std::ofstream(file, std::ios::binary) << text;
        try {
            (void)loadSceneFile(file);
            ++loaded;
        } catch (const InputError& error) {
            ++rejected;
            const std::string what = error.what();
            EXPECT_EQ(what.find('\n'), std::string::npos) << "multi-line error: " << what;
            EXPECT_NE(what.find("mutated.json"), std::string::npos) << "error does not name the file: " << what;
        } catch (const std::exception& other) {
            ADD_FAILURE() << "mutation " << i << " threw a non-InputError: " << other.what();
        }
    }
    fs::remove_all(dir);
    EXPECT_GT(rejected, 300);  // most mutations break the file
    RecordProperty("loaded", loaded);
}
