#pragma once
// Strict checks of the text mesh formats Assimp reads leniently. Assimp's OBJ
// and OFF readers skip lines they do not understand, ignore texture or normal
// references to nothing, ignore data past the header's counts and read a
// face's missing index from the next line, so a broken file can load as
// garbage. These checks run on the text before Assimp sees it.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace raycache {

struct MeshTextProblem {
    int line = 0;    // 1-based
    int column = 0;  // 1-based, in bytes
    std::string message;
};

// The first problem of an OBJ text (wavefront .obj): unknown statements,
// malformed numbers, faces of fewer than 3 vertices, references to vertices,
// texture coordinates or normals that do not exist.
std::optional<MeshTextProblem> checkObjText(std::string_view text);

// The first problem of an OFF text (OFF, COFF, NOFF, CNOFF headers): counts
// that do not match the data, malformed numbers, faces of fewer than 3
// vertices, vertex indices out of range, anything after the last face.
std::optional<MeshTextProblem> checkOffText(std::string_view text);

// The first problem of a PLY header (ASCII or binary files; the body is not
// read): a first line other than "ply", a missing or unknown format line,
// header lines other than comment, obj_info, element and property, and no
// end_header. Assimp loops forever on a header whose end_header is damaged
// (found by fuzzing, tests/fuzz/findings/assimp-ply-hang.ply).
std::optional<MeshTextProblem> checkPlyHeader(std::string_view text);

// Whether the extension names a format checked here (.obj, .off, .ply, any case).
bool strictlyCheckedText(const std::filesystem::path& path);

// Dispatches on the extension (.obj, .off, .ply, any case); other formats: nullopt.
std::optional<MeshTextProblem> checkMeshText(const std::filesystem::path& path, std::string_view text);

}  // namespace raycache
