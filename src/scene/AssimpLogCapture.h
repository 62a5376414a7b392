#pragma once
// Collects what Assimp says while it imports one file. Assimp repairs some
// broken files on its own and only says so in its log (faces with
// out-of-range indices dropped, normals of the wrong count ignored); without
// the log those repairs would be silent. Assimp keeps one process-wide
// logger, so this installs a collector for its own lifetime and restores the
// silent default afterwards: only one may exist at a time (mesh files are
// loaded on one thread, by the scene reader).
#include <string>
#include <vector>

namespace raycache {

class AssimpLogCapture {
public:
    AssimpLogCapture();
    ~AssimpLogCapture();
    AssimpLogCapture(const AssimpLogCapture&) = delete;
    AssimpLogCapture& operator=(const AssimpLogCapture&) = delete;

    // Warnings and errors logged so far, in order, except those known to be
    // harmless for a mesh we only take geometry from (unreferenced vertices,
    // an undefined OBJ material, a camera's field of view) and those that
    // only become part of the note (missingMaterialFiles).
    const std::vector<std::string>& problems() const { return problems_; }

    // Material files (OBJ mtllib) Assimp could not find, each once, in the
    // order met. Nothing is lost: raycache takes materials from the scene
    // file, so the object's material is used; the loader notes it.
    const std::vector<std::string>& missingMaterialFiles() const { return missingMaterialFiles_; }

private:
    std::vector<std::string> problems_;
    std::vector<std::string> missingMaterialFiles_;
};

}  // namespace raycache
