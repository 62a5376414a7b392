// The oracle for cube addressing: real OpenGL (Mesa llvmpipe through headless
// EGL) samples a cubemap whose every texel stores its own (face, x, y), with
// nearest filtering, for a few hundred thousand directions per size; raycache
// must name the same texel for every one of them.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <epoxy/gl.h>

#include "CiRequirement.h"
#include "raster/GlContext.h"
#include "cache/CubeAddressing.h"

namespace raycache {
namespace {

// Why a direction is in the set, for statistics and failure messages.
enum class Kind { Random, RandomInCube, Tie, NearTie, SignedZero, Boundary, Scaled, Extreme, kCount };

const char* kindName(Kind k) {
    switch (k) {
    case Kind::Random: return "random unit";
    case Kind::RandomInCube: return "random in cube";
    case Kind::Tie: return "exact tie";
    case Kind::NearTie: return "tie +-1 ulp";
    case Kind::SignedZero: return "signed zero";
    case Kind::Boundary: return "texel boundary";
    case Kind::Scaled: return "scaled";
    case Kind::Extreme: return "extreme magnitude";
    case Kind::kCount: break;
    }
    return "?";
}

struct Probes {
    std::vector<Vec3> directions;
    std::vector<Kind> kinds;

    void add(const Vec3& d, Kind k) {
        directions.push_back(d);
        kinds.push_back(k);
    }
};

float stepUlps(float x, int ulps) {
    const float toward = ulps > 0 ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
    for (int i = 0; i < std::abs(ulps); ++i) x = std::nextafter(x, toward);
    return x;
}

// The direction whose face `face` coordinates are (sc, tc) with |major| = ma:
// GL table 8.19 read backwards.
Vec3 fromFaceCoords(int face, float ma, float sc, float tc) {
    switch (face) {
    case 0: return {ma, -tc, -sc};
    case 1: return {-ma, -tc, sc};
    case 2: return {sc, ma, tc};
    case 3: return {sc, -ma, -tc};
    case 4: return {sc, -tc, ma};
    default: return {-sc, -tc, -ma};
    }
}

Vec3 withComponents(int i, float a, int j, float b, int k, float c) {
    float v[3];
    v[i] = a;
    v[j] = b;
    v[k] = c;
    return {v[0], v[1], v[2]};
}

Probes makeProbes(int size, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> gauss(0.0f, 1.0f);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_real_distribution<float> logMagnitude(-3.0f, 3.0f);
    auto randomUnit = [&] {
        Vec3 v;
        do v = {gauss(rng), gauss(rng), gauss(rng)};
        while (dot(v, v) < 1e-6f);
        return normalize(v);
    };
    Probes p;

    for (int i = 0; i < 100000; ++i) p.add(randomUnit(), Kind::Random);
    for (int i = 0; i < 20000; ++i) p.add({unit(rng), unit(rng), unit(rng)}, Kind::RandomInCube);

    // Two- and three-way ties of |components| with every sign combination, and
    // the same one ulp apart.
    std::vector<float> magnitudes = {1.0f, 0.5f, 0.70710677f, 1e-20f, 1e20f, 3.0f};
    for (int i = 0; i < 200; ++i) magnitudes.push_back(std::pow(10.0f, logMagnitude(rng)));
    const int pairs[3][3] = {{0, 1, 2}, {0, 2, 1}, {1, 2, 0}};
    for (const float m : magnitudes) {
        const float below = std::abs(unit(rng)) * m;
        const float thirds[] = {0.0f, 0.25f * m, below, m, std::nextafter(m, 0.0f), stepUlps(m, 1), 2.0f * m};
        for (const auto& [i, j, k] : pairs) {
            for (int signs = 0; signs < 4; ++signs) {
                const float a = (signs & 1) ? -m : m;
                const float b = (signs & 2) ? -m : m;
                for (const float t : thirds) {
                    p.add(withComponents(i, a, j, b, k, t), Kind::Tie);
                    p.add(withComponents(i, a, j, b, k, -t), Kind::Tie);
                }
                for (const int ulps : {-1, 1}) {
                    const float bNear = (signs & 2) ? -stepUlps(m, ulps) : stepUlps(m, ulps);
                    for (const float t : {0.0f, -0.0f, below, -below}) {
                        p.add(withComponents(i, a, j, bNear, k, t), Kind::NearTie);
                    }
                }
            }
        }
    }

    // Signed zeros: every face, minor components from {+0, -0, random}, and the
    // all-zero vectors (GL still picks a texel for them).
    for (int face = 0; face < 6; ++face) {
        for (const float ma : {1.0f, 0.5f, 7.0f, 1e-20f, 1e20f}) {
            const float r1 = unit(rng) * ma, r2 = unit(rng) * ma;
            const float minors[] = {0.0f, -0.0f, r1, r2};
            for (const float sc : minors) {
                for (const float tc : minors) p.add(fromFaceCoords(face, ma, sc, tc), Kind::SignedZero);
            }
        }
    }
    p.add({-0.0f, 1.0f, 0.5f}, Kind::SignedZero);
    for (int signs = 0; signs < 8; ++signs) {
        p.add({(signs & 1) ? -0.0f : 0.0f, (signs & 2) ? -0.0f : 0.0f, (signs & 4) ? -0.0f : 0.0f}, Kind::SignedZero);
    }

    // Texel boundaries on every face: s (or t) = k / size for every k, one and
    // two ulps either side, for |major| = 1 (where the arithmetic is exact) and
    // for arbitrary |major| (where it rounds).
    std::array<float, 4> boundaryMajors = {1.0f};
    for (std::size_t i = 1; i < boundaryMajors.size(); ++i) boundaryMajors[i] = 0.3f + 2.7f * std::abs(unit(rng));
    for (int face = 0; face < 6; ++face) {
        for (const float ma : boundaryMajors) {
            for (int k = 0; k <= size; ++k) {
                const float onBoundary = static_cast<float>((2.0 * k / size - 1.0) * ma);
                const float other = unit(rng) * ma;
                // Every third boundary also puts the other coordinate on one.
                const int k2 = static_cast<int>(rng() % static_cast<std::uint32_t>(size + 1));
                const float otherOnBoundary = static_cast<float>((2.0 * k2 / size - 1.0) * ma);
                const float second = k % 3 == 0 ? otherOnBoundary : other;
                for (int ulps = -2; ulps <= 2; ++ulps) {
                    const float c = stepUlps(onBoundary, ulps);
                    p.add(fromFaceCoords(face, ma, c, second), Kind::Boundary);
                    p.add(fromFaceCoords(face, ma, second, c), Kind::Boundary);
                }
            }
        }
    }

    // Lengths far from 1.
    for (const float scale : {1e-20f, 1e20f, 1e-30f, 1e30f, 1e-3f, 1e3f, 0x1p-60f, 0x1p60f}) {
        for (int i = 0; i < 4000; ++i) p.add(randomUnit() * scale, Kind::Scaled);
    }
    // Where llvmpipe's flush-to-zero / denormals-are-zero shows: components
    // below FLT_MIN, and |major| above 2^125 where 0.5/|major| is subnormal.
    for (const float scale : {1e-36f, 1e-38f, 1e-40f, 4.5e37f, 1e38f, 3e38f}) {
        for (int i = 0; i < 2000; ++i) p.add(randomUnit() * scale, Kind::Extreme);
    }
    const float denorm = std::numeric_limits<float>::denorm_min();
    for (const Vec3& d : {Vec3{1.0f, 1e-40f, -1e-42f}, Vec3{1e-38f, 1e-40f, -3e-39f}, Vec3{1e-40f, 2e-40f, -3e-40f},
                          Vec3{-1e-40f, 0.0f, 0.0f}, Vec3{denorm, -denorm, denorm}, Vec3{-denorm, 0.0f, -0.0f},
                          Vec3{3.4e38f, 3.4e38f, -1.0f}, Vec3{-3.4e38f, 1e38f, 2e38f}}) {
        p.add(d, Kind::Extreme);
    }
    return p;
}

// What every texel stores: its own address, with a marker bit so that a
// texel GL did not fetch (e.g. an incomplete texture reads as 0) is obvious.
constexpr std::uint32_t kMarker = 0x80000000u;
std::uint32_t texelCode(const CubeTexel& t) {
    return kMarker | static_cast<std::uint32_t>(t.face) << 24 | static_cast<std::uint32_t>(t.y) << 12 |
           static_cast<std::uint32_t>(t.x);
}
std::string describeCode(std::uint32_t code) {
    if ((code & kMarker) == 0) return "no texel (code " + std::to_string(code) + ")";
    char buf[64];
    std::snprintf(buf, sizeof buf, "face %u (x %u, y %u)", (code >> 24) & 0x7Fu, code & 0xFFFu, (code >> 12) & 0xFFFu);
    return buf;
}

constexpr const char* kVertexShader = R"(#version 330 core
void main() {
    // One triangle covering the viewport.
    vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
    gl_Position = vec4(p, 0.0, 1.0);
}
)";

// One direction per pixel. Both texture() (implicit LOD) and textureLod()
// are sampled: each is a way a renderer would read the cube. The direction is
// echoed back to prove GL saw exactly the bits we sent.
constexpr const char* kFragmentShader = R"(#version 330 core
uniform sampler2D directions;
uniform usamplerCube codes;
layout(location = 0) out uvec4 sampled;
layout(location = 1) out uvec4 echoed;
void main() {
    vec3 d = texelFetch(directions, ivec2(gl_FragCoord.xy), 0).xyz;
    sampled = uvec4(texture(codes, d).r, textureLod(codes, d, 0.0).r, 0u, 0u);
    echoed = uvec4(floatBitsToUint(d), 0u);
}
)";

struct GlAnswer {
    std::uint32_t viaTexture = 0;
    std::uint32_t viaTextureLod = 0;
    std::array<std::uint32_t, 3> echoedBits{};
};

// GL objects for one oracle run; deleted with it.
class CubeSampler {
public:
    CubeSampler() {
        program_ = glCreateProgram();
        attach(GL_VERTEX_SHADER, kVertexShader);
        attach(GL_FRAGMENT_SHADER, kFragmentShader);
        glLinkProgram(program_);
        GLint ok = 0;
        glGetProgramiv(program_, GL_LINK_STATUS, &ok);
        if (!ok) error_ += "link: " + programLog();
        glGenVertexArrays(1, &vertexArray_);
        glGenTextures(1, &cube_);
        glGenTextures(1, &directions_);
        glGenTextures(2, targets_);
        glGenFramebuffers(1, &framebuffer_);
    }
    ~CubeSampler() {
        glDeleteFramebuffers(1, &framebuffer_);
        glDeleteTextures(2, targets_);
        glDeleteTextures(1, &directions_);
        glDeleteTextures(1, &cube_);
        glDeleteVertexArrays(1, &vertexArray_);
        glDeleteProgram(program_);
    }
    CubeSampler(const CubeSampler&) = delete;
    CubeSampler& operator=(const CubeSampler&) = delete;

    // Empty unless shader compilation or linking failed.
    const std::string& error() const { return error_; }

    // A size x size cubemap, texel (face, x, y) storing texelCode(face, x, y):
    // rows uploaded in order, so GL's row 0 (t near 0) is raycache's y = 0.
    void uploadCube(int size) {
        glBindTexture(GL_TEXTURE_CUBE_MAP, cube_);
        std::vector<std::uint32_t> face(static_cast<std::size_t>(size) * size);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        for (int f = 0; f < 6; ++f) {
            for (int y = 0; y < size; ++y) {
                for (int x = 0; x < size; ++x) {
                    face[static_cast<std::size_t>(y) * size + x] = texelCode({static_cast<CubeFace>(f), x, y});
                }
            }
            glTexImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f, 0, GL_R32UI, size, size, 0, GL_RED_INTEGER,
                         GL_UNSIGNED_INT, face.data());
        }
        glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
        glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BASE_LEVEL, 0);
        glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, 0);
    }

    // Samples the cube once per direction. Empty on a GL error (see error()).
    std::vector<GlAnswer> sample(const std::vector<Vec3>& dirs) {
        constexpr int kWidth = 1024;
        const int count = static_cast<int>(dirs.size());
        const int height = (count + kWidth - 1) / kWidth;
        GLint maxSize = 0;
        glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
        if (height > maxSize) {
            error_ = "too many directions for GL_MAX_TEXTURE_SIZE " + std::to_string(maxSize);
            return {};
        }

        std::vector<float> texels(static_cast<std::size_t>(kWidth) * height * 4, 0.0f);
        for (std::size_t i = 0; i < texels.size() / 4; ++i) {
            const Vec3 d = i < dirs.size() ? dirs[i] : Vec3{1.0f, 0.0f, 0.0f};
            texels[4 * i] = d.x;
            texels[4 * i + 1] = d.y;
            texels[4 * i + 2] = d.z;
        }
        glBindTexture(GL_TEXTURE_2D, directions_);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kWidth, height, 0, GL_RGBA, GL_FLOAT, texels.data());
        setNearestSingleLevel();

        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
        for (int i = 0; i < 2; ++i) {
            glBindTexture(GL_TEXTURE_2D, targets_[i]);
            glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32UI, kWidth, height, 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, nullptr);
            setNearestSingleLevel();
            glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D, targets_[i], 0);
        }
        const GLenum drawBuffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
        glDrawBuffers(2, drawBuffers);
        if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
            error_ = "integer framebuffer incomplete";
            return {};
        }

        glUseProgram(program_);
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, directions_);
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_CUBE_MAP, cube_);
        glUniform1i(glGetUniformLocation(program_, "directions"), 0);
        glUniform1i(glGetUniformLocation(program_, "codes"), 1);
        glViewport(0, 0, kWidth, height);
        glBindVertexArray(vertexArray_);
        glDrawArrays(GL_TRIANGLES, 0, 3);

        std::vector<std::uint32_t> sampled(static_cast<std::size_t>(kWidth) * height * 4);
        std::vector<std::uint32_t> echoed(sampled.size());
        glPixelStorei(GL_PACK_ALIGNMENT, 4);
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glReadPixels(0, 0, kWidth, height, GL_RGBA_INTEGER, GL_UNSIGNED_INT, sampled.data());
        glReadBuffer(GL_COLOR_ATTACHMENT1);
        glReadPixels(0, 0, kWidth, height, GL_RGBA_INTEGER, GL_UNSIGNED_INT, echoed.data());
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
            error_ = "GL error " + std::to_string(e);
            return {};
        }

        std::vector<GlAnswer> answers(dirs.size());
        for (std::size_t i = 0; i < answers.size(); ++i) {
            answers[i].viaTexture = sampled[4 * i];
            answers[i].viaTextureLod = sampled[4 * i + 1];
            answers[i].echoedBits = {echoed[4 * i], echoed[4 * i + 1], echoed[4 * i + 2]};
        }
        return answers;
    }

private:
    void attach(GLenum type, const char* source) {
        const GLuint shader = glCreateShader(type);
        glShaderSource(shader, 1, &source, nullptr);
        glCompileShader(shader);
        GLint ok = 0;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            GLchar log[2048] = {};
            glGetShaderInfoLog(shader, sizeof log, nullptr, log);
            error_ += std::string("compile: ") + log;
        }
        glAttachShader(program_, shader);
        glDeleteShader(shader);  // freed with the program
    }
    std::string programLog() const {
        GLchar log[2048] = {};
        glGetProgramInfoLog(program_, sizeof log, nullptr, log);
        return log;
    }
    static void setNearestSingleLevel() {
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    }

    GLuint program_ = 0, vertexArray_ = 0, cube_ = 0, directions_ = 0, framebuffer_ = 0;
    GLuint targets_[2] = {0, 0};
    std::string error_;
};

bool sameBits(const Vec3& d, const std::array<std::uint32_t, 3>& bits) {
    return std::bit_cast<std::uint32_t>(d.x) == bits[0] && std::bit_cast<std::uint32_t>(d.y) == bits[1] &&
           std::bit_cast<std::uint32_t>(d.z) == bits[2];
}

class CubeAddressingGl : public ::testing::TestWithParam<int> {
protected:
    void SetUp() override {
        // The oracle is Mesa's software rasterizer specifically (GPUs address
        // cubes with their own arithmetic); keep Mesa off any GPU it finds.
        setenv("LIBGL_ALWAYS_SOFTWARE", "1", /*overwrite=*/0);
        std::string whyNot;
        gl_ = GlContext::create(whyNot);
        if (!gl_) {
            RAYCACHE_SKIP_OR_FAIL_IN_CI("No headless OpenGL 3.3+ context through EGL, so no GL oracle: " << whyNot);
        }
        if (gl_->renderer().find("llvmpipe") == std::string::npos) {
            GTEST_SKIP() << "The oracle is Mesa llvmpipe, but the context renders with '" << gl_->renderer() << "'";
        }
    }
    void TearDown() override { gl_.reset(); }

    std::unique_ptr<GlContext> gl_;
};

TEST_P(CubeAddressingGl, NearestTexelMatchesOpenGl) {
    const int size = GetParam();
    const auto start = std::chrono::steady_clock::now();
    const Probes probes = makeProbes(size, 0xC0BE0000u + static_cast<std::uint32_t>(size));

    CubeSampler sampler;
    ASSERT_EQ(sampler.error(), "");
    sampler.uploadCube(size);
    const std::vector<GlAnswer> answers = sampler.sample(probes.directions);
    ASSERT_EQ(sampler.error(), "");
    ASSERT_EQ(answers.size(), probes.directions.size());

    constexpr int kShown = 12;
    std::array<int, static_cast<int>(Kind::kCount)> perKind{}, mismatchesPerKind{};
    int mismatches = 0, garbled = 0, exactBoundaries = 0;
    const float n = static_cast<float>(size);
    for (std::size_t i = 0; i < answers.size(); ++i) {
        const Vec3& d = probes.directions[i];
        const Kind kind = probes.kinds[i];
        ++perKind[static_cast<int>(kind)];
        if (!sameBits(d, answers[i].echoedBits)) {
            if (++garbled <= kShown) {
                ADD_FAILURE() << "GL did not receive direction (" << d.x << ", " << d.y << ", " << d.z << ") intact";
            }
            continue;
        }
        const CubeCoord c = cubeCoordFromDirection(d);
        if (c.s * n == std::floor(c.s * n) || c.t * n == std::floor(c.t * n)) ++exactBoundaries;

        const std::uint32_t ours = texelCode(cubeTexelFromDirection(d, size));
        if (answers[i].viaTexture == ours && answers[i].viaTextureLod == ours) continue;
        ++mismatchesPerKind[static_cast<int>(kind)];
        if (++mismatches <= kShown) {
            char buf[512];
            std::snprintf(buf, sizeof buf,
                          "size %d, %s direction (%a, %a, %a): GL texture() %s, textureLod() %s; "
                          "raycache %s (s %a, t %a)",
                          size, kindName(kind), static_cast<double>(d.x), static_cast<double>(d.y),
                          static_cast<double>(d.z), describeCode(answers[i].viaTexture).c_str(),
                          describeCode(answers[i].viaTextureLod).c_str(), describeCode(ours).c_str(),
                          static_cast<double>(c.s), static_cast<double>(c.t));
            ADD_FAILURE() << buf;
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    std::printf(
        "[ oracle   ] %s\n[ oracle   ] size %d: %zu directions, %d with s*size or t*size integral; "
        "%d mismatches; %.2f s\n",
        gl_->description().c_str(), size, probes.directions.size(), exactBoundaries, mismatches, seconds);
    for (int k = 0; k < static_cast<int>(Kind::kCount); ++k) {
        std::printf("[ oracle   ]   %-18s %7d directions, %d mismatches\n", kindName(static_cast<Kind>(k)), perKind[k],
                    mismatchesPerKind[k]);
    }
    EXPECT_EQ(garbled, 0) << "directions changed on their way into GL";
    EXPECT_EQ(mismatches, 0) << "texels where raycache and OpenGL disagree";
    // Guards the test itself: the boundary probes must really sit on boundaries.
    EXPECT_GT(exactBoundaries, 6 * size);
}

INSTANTIATE_TEST_SUITE_P(Sizes, CubeAddressingGl, ::testing::Values(1, 2, 16, 100, 128, 512, 1000),
                         [](const ::testing::TestParamInfo<int>& p) { return "size" + std::to_string(p.param); });

}  // namespace
}  // namespace raycache
