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

// The first problem of a PLY file's header, and of its body as far as
// Assimp's PLY reader (5.2.5) trusts it. The header must follow the PLY
// grammar: a first line "ply", "format ascii|binary_little_endian|
// binary_big_endian 1.0" (once), "element <name> <count>" with a plain
// printable ASCII name, "property <type> <name>" and "property list
// <length type> <item type> <name>" with exactly those words, after an
// element (types: char uchar short ushort int uint float double int8 uint8
// int16 uint16 int32 uint32 float32 float64, a list's length an integer
// type), an element with a nonzero count has properties, and "end_header"
// alone on its line, ended by \n (Assimp loops forever at the end of the
// file). Assimp reads into memory it does not own, or misreads,
// some headers of that grammar, refused too: a second "vertex" or "face"
// element (written into the first one's array), "element tristrips" (one
// triangle kept per strip), "element TextureFile", a face's "texcoord"
// list without a "vertex_indices" one (read through it), an element name
// starting with a digit, and an element other than vertex, face, edge and
// material with instances before the vertex or face element (Assimp reads
// such an element's count from its name: the digits, else 0). No header line holds a control byte other than tab
// (and a line's trailing \r), comments included: Assimp's line reader ends
// a line at NUL, \r or \f and then looks for the next \n past its buffer
// (it hung and freed bad pointers on such headers, found by fuzzing,
// docs/testing.md). Comments and obj_info lines may hold any other text,
// UTF-8 too. Assimp ends an element's properties at any other line, so a
// comment, obj_info or keyword-less line followed by another property of
// the same element is refused (the body would be misread). A line without
// a keyword elsewhere (Blender 2.47 wrote one after the format line) is
// harmless: Assimp skips it. It is accepted, and when `ignoredLines` is
// given it receives what was ignored ("ignored PLY header line 3 without a
// keyword (...)"), else empty.
// The body: an ASCII one must hold as many non-blank lines as the elements
// announce (Assimp would make up the rest), each list length a count of
// the values on its line, and no control byte to the end of the file. In
// either kind, a face's texcoord list holds 2 values per vertex or none. A
// binary one (either byte order) is walked by the declared properties,
// list lengths read from the data: it must hold all the header announces
// (Assimp would read on into its buffer), with no negative list length,
// and must not start with byte 0x0a after an end_header line ending in a
// lone \n (Assimp drops that byte). Data after the last element is
// accepted, as Assimp leaves it unused (in an ASCII file it too must be
// free of control bytes). The walk takes at most one step per byte.
std::optional<MeshTextProblem> checkPlyHeader(std::string_view text, std::string* ignoredLines = nullptr);

// Whether the extension names a format checked here (.obj, .off, .ply, any case).
bool strictlyCheckedText(const std::filesystem::path& path);

// Dispatches on the extension (.obj, .off, .ply, any case); other formats:
// nullopt. `accepted`, when given, receives what a check let pass though odd
// (checkPlyHeader's ignored lines), else empty.
std::optional<MeshTextProblem> checkMeshText(const std::filesystem::path& path, std::string_view text,
                                             std::string* accepted = nullptr);

}  // namespace raycache
