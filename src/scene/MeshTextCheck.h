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

// The first problem of a PLY header: a first line other than "ply", a
// missing or unknown format line, a malformed element line, a line without
// a PLY keyword among an element's properties, no end_header, and, in an
// ASCII file, fewer lines of data than the elements announced (Assimp would
// make up the rest). Assimp loops forever on a header whose end_header is
// damaged (found by fuzzing, tests/fuzz/findings/assimp-ply-hang.ply).
// A line without a keyword elsewhere (Blender 2.47 wrote one after the
// format line) is harmless: Assimp skips it. It is accepted, and when
// `ignoredLines` is given it receives what was ignored
// ("ignored PLY header line 3 without a keyword (...)"), else empty.
std::optional<MeshTextProblem> checkPlyHeader(std::string_view text, std::string* ignoredLines = nullptr);

// Whether the extension names a format checked here (.obj, .off, .ply, any case).
bool strictlyCheckedText(const std::filesystem::path& path);

// Dispatches on the extension (.obj, .off, .ply, any case); other formats:
// nullopt. `accepted`, when given, receives what a check let pass though odd
// (checkPlyHeader's ignored lines), else empty.
std::optional<MeshTextProblem> checkMeshText(const std::filesystem::path& path, std::string_view text,
                                             std::string* accepted = nullptr);

}  // namespace raycache
