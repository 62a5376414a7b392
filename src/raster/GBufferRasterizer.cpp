#include "raster/GBufferRasterizer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "core/Errors.h"
#include "raster/GlContext.h"

namespace raycache {

namespace {

// What every fragment shader shares: the pixel's camera ray, built exactly as
// render/CameraRays.h builds it, the material's albedo, and the outputs in
// the layout of raster/GBuffer.h.
constexpr const char* kFragmentCommon = R"(
#version 450 core
uniform vec3 cameraOrigin;
uniform vec3 cameraForward;
uniform vec3 cameraRight;   // scaled to the image plane at distance 1
uniform vec3 cameraUp;
uniform vec2 invSize;       // 1 / width, 1 / height
uniform float invFar;       // depth = ray distance * invFar
uniform int objectId;
uniform vec3 diffuse;
uniform int textureKind;    // 0 none, 1 checkerboard, 2 image
uniform vec3 checkerEven;
uniform vec3 checkerOdd;
uniform float squaresPerUnit;
uniform sampler2D image;

layout(location = 0) out vec4 outPositionDepth;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out ivec2 outIds;

// Row 0 of the framebuffer is the image's top row (the projection flips y),
// so gl_FragCoord is the pixel centre (x + 0.5, y + 0.5) in image terms.
vec3 cameraRayDirection() {
    float sx = 2.0 * gl_FragCoord.x * invSize.x - 1.0;
    float sy = 1.0 - 2.0 * gl_FragCoord.y * invSize.y;
    return normalize(cameraForward + cameraRight * sx + cameraUp * sy);
}

vec3 albedoAt(vec2 uv) {
    if (textureKind == 1) {
        float parity = mod(floor(uv.x * squaresPerUnit) + floor(uv.y * squaresPerUnit), 2.0);
        return parity == 0.0 ? checkerEven : checkerOdd;
    }
    if (textureKind == 2) return texture(image, uv).rgb;
    return diffuse;
}

void writeSurface(vec3 position, float t, vec3 normal, vec2 uv, int primitiveId) {
    outPositionDepth = vec4(position, t);
    outNormal = vec4(normal, 0.0);
    outAlbedo = vec4(albedoAt(uv), 1.0);
    outIds = ivec2(objectId, primitiveId);
    gl_FragDepth = min(t * invFar, 1.0);
}
)";

constexpr const char* kMeshVertex = R"(
#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 uv;
uniform mat4 viewProjection;
out vec3 worldPosition;
out vec3 worldNormal;
out vec2 texCoord;
void main() {
    worldPosition = position;
    worldNormal = normal;
    texCoord = uv;
    gl_Position = viewProjection * vec4(position, 1.0);
}
)";

constexpr const char* kMeshFragment = R"(
in vec3 worldPosition;
in vec3 worldNormal;
in vec2 texCoord;
uniform int hasNormals;
void main() {
    // Zero when the mesh has no vertex normals: the deferred pass then uses
    // the triangle's own normal, as the tracer does.
    vec3 n = vec3(0.0);
    if (hasNormals != 0) {
        float len = length(worldNormal);
        if (len > 0.0) n = worldNormal / len;
    }
    writeSurface(worldPosition, length(worldPosition - cameraOrigin), n, texCoord, gl_PrimitiveID);
}
)";

constexpr const char* kSphereVertex = R"(
#version 450 core
layout(location = 0) in vec3 corner;  // of the cube [-1, 1]^3
uniform mat4 viewProjection;
uniform vec3 sphereCenter;
uniform float boxHalfSize;
void main() {
    gl_Position = viewProjection * vec4(sphereCenter + corner * boxHalfSize, 1.0);
}
)";

// The ray-sphere root as trace/TraceScene.cpp computes it (relative to the
// centre, stable quadratic form), so both find the same hits.
constexpr const char* kSphereFragment = R"(
uniform vec3 sphereCenter;
uniform float sphereRadius;
void main() {
    vec3 d = cameraRayDirection();
    vec3 p = cameraOrigin - sphereCenter;
    float a = dot(d, d);
    float b = dot(p, d);
    vec3 q = p - (b / a) * d;
    float disc = sphereRadius * sphereRadius - dot(q, q);
    if (disc < 0.0) discard;
    float h = sqrt(a * disc);
    float qq = b > 0.0 ? -(b + h) : -(b - h);
    float c = dot(p, p) - sphereRadius * sphereRadius;
    float t0 = b > 0.0 ? qq / a : c / qq;
    float t1 = b > 0.0 ? c / qq : qq / a;
    if (t0 > t1) { float s = t0; t0 = t1; t1 = s; }
    float t = t0 >= 0.0 ? t0 : t1;
    if (!(t >= 0.0)) discard;
    vec3 hit = cameraOrigin + d * t;
    vec3 n = (hit - sphereCenter) * (1.0 / sphereRadius);
    vec2 uv = vec2(0.0);
    if (textureKind != 0) {
        const float pi = 3.14159265358979;
        uv = vec2(0.5 + atan(n.z, n.x) / (2.0 * pi), 0.5 + asin(clamp(n.y, -1.0, 1.0)) / pi);
    }
    writeSurface(hit, t, n, uv, 0);
}
)";

GLuint compileShader(GLenum kind, const std::vector<const char*>& sources) {
    const GLuint shader = glCreateShader(kind);
    glShaderSource(shader, static_cast<GLsizei>(sources.size()), sources.data(), nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        std::array<char, 4096> log{};
        glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
        glDeleteShader(shader);
        throw RuntimeError(std::string("OpenGL: G-buffer shader does not compile: ") + log.data());
    }
    return shader;
}

GLuint linkProgram(const char* vertex, const char* fragment) {
    const GLuint vs = compileShader(GL_VERTEX_SHADER, {vertex});
    const GLuint fs = compileShader(GL_FRAGMENT_SHADER, {kFragmentCommon, fragment});
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        std::array<char, 4096> log{};
        glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
        glDeleteProgram(program);
        throw RuntimeError(std::string("OpenGL: G-buffer program does not link: ") + log.data());
    }
    return program;
}

void checkGl(const char* what) {
    const GLenum error = glGetError();
    if (error != GL_NO_ERROR)
        throw RuntimeError(std::string("OpenGL error 0x") + [&] {
            char buf[16];
            std::snprintf(buf, sizeof buf, "%04x", static_cast<unsigned>(error));
            return std::string(buf);
        }() + " while " + what);
}

// Uniform locations of one program, looked up once.
struct ProgramUniforms {
    GLint viewProjection, cameraOrigin, cameraForward, cameraRight, cameraUp, invSize, invFar, objectId, diffuse,
        textureKind, checkerEven, checkerOdd, squaresPerUnit, image;
    GLint hasNormals = -1, sphereCenter = -1, sphereRadius = -1, boxHalfSize = -1;

    explicit ProgramUniforms(GLuint p) {
        const auto at = [p](const char* name) { return glGetUniformLocation(p, name); };
        viewProjection = at("viewProjection");
        cameraOrigin = at("cameraOrigin");
        cameraForward = at("cameraForward");
        cameraRight = at("cameraRight");
        cameraUp = at("cameraUp");
        invSize = at("invSize");
        invFar = at("invFar");
        objectId = at("objectId");
        diffuse = at("diffuse");
        textureKind = at("textureKind");
        checkerEven = at("checkerEven");
        checkerOdd = at("checkerOdd");
        squaresPerUnit = at("squaresPerUnit");
        image = at("image");
        hasNormals = at("hasNormals");
        sphereCenter = at("sphereCenter");
        sphereRadius = at("sphereRadius");
        boxHalfSize = at("boxHalfSize");
    }
};

struct MeshBuffers {
    GLuint vertexArray = 0, vertices = 0, indices = 0;
    GLsizei indexCount = 0;
    bool hasNormals = false;
};

constexpr int kTargets = 4;  // position+depth, normal, albedo, ids
constexpr std::array<std::size_t, kTargets> kBytesPerPixel{16, 16, 16, 8};

void uniform3(GLint location, const Vec3& v) { glUniform3f(location, v.x, v.y, v.z); }

}  // namespace

struct GBufferRasterizer::Impl {
    std::unique_ptr<GlContext> context;
    const Scene* scene = nullptr;
    GLuint meshProgram = 0, sphereProgram = 0;
    std::unique_ptr<ProgramUniforms> meshUniforms, sphereUniforms;
    std::vector<MeshBuffers> meshes;           // per object; empty buffers for spheres
    std::vector<GLuint> textures;              // per object; 0 unless it has an image texture
    GLuint cubeArray = 0, cubeVertices = 0, cubeIndices = 0;
    float sceneLower[3] = {0, 0, 0}, sceneUpper[3] = {0, 0, 0};

    // Size-dependent: framebuffer, targets, the persistently mapped readback buffer.
    int width = 0, height = 0;
    GLuint framebuffer = 0, depth = 0;
    std::array<GLuint, kTargets> targets{};
    GLuint readback = 0;
    const unsigned char* mapped = nullptr;

    ~Impl() {
        if (!context) return;
        context->makeCurrent();
        releaseTargets();
        for (MeshBuffers& m : meshes) releaseMesh(m);
        for (GLuint t : textures) glDeleteTextures(1, &t);
        glDeleteVertexArrays(1, &cubeArray);
        glDeleteBuffers(1, &cubeVertices);
        glDeleteBuffers(1, &cubeIndices);
        glDeleteProgram(meshProgram);
        glDeleteProgram(sphereProgram);
    }

    void releaseTargets() {
        if (readback) {
            glBindBuffer(GL_PIXEL_PACK_BUFFER, readback);
            glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
            glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
            glDeleteBuffers(1, &readback);
        }
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteTextures(kTargets, targets.data());
        glDeleteTextures(1, &depth);
        readback = framebuffer = depth = 0;
        targets = {};
        mapped = nullptr;
        width = height = 0;
    }

    std::size_t targetOffset(int target) const {
        std::size_t offset = 0;
        for (int i = 0; i < target; ++i) offset += kBytesPerPixel[static_cast<std::size_t>(i)];
        return offset * static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    }

    void makeTargets(int w, int h) {
        releaseTargets();
        width = w;
        height = h;
        glCreateFramebuffers(1, &framebuffer);
        glCreateTextures(GL_TEXTURE_2D, kTargets, targets.data());
        const std::array<GLenum, kTargets> formats{GL_RGBA32F, GL_RGBA32F, GL_RGBA32F, GL_RG32I};
        std::array<GLenum, kTargets> drawBuffers{};
        for (int i = 0; i < kTargets; ++i) {
            const auto k = static_cast<std::size_t>(i);
            glTextureStorage2D(targets[k], 1, formats[k], w, h);
            glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i), targets[k], 0);
            drawBuffers[k] = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
        }
        glCreateTextures(GL_TEXTURE_2D, 1, &depth);
        glTextureStorage2D(depth, 1, GL_DEPTH_COMPONENT32F, w, h);
        glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, depth, 0);
        glNamedFramebufferDrawBuffers(framebuffer, kTargets, drawBuffers.data());
        if (glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            throw RuntimeError("OpenGL: the G-buffer framebuffer is incomplete");

        // One buffer for all targets, mapped once for as long as the size
        // holds: each frame's readback lands where the deferred passes read.
        const auto bytes = static_cast<GLsizeiptr>(targetOffset(kTargets));
        glCreateBuffers(1, &readback);
        const GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        glNamedBufferStorage(readback, bytes, nullptr, flags);
        mapped = static_cast<const unsigned char*>(glMapNamedBufferRange(readback, 0, bytes, flags));
        if (!mapped) throw RuntimeError("OpenGL: cannot map the G-buffer readback buffer");
        checkGl("creating the G-buffer targets");
    }

    void uploadScene(const Scene& s) {
        scene = &s;
        meshProgram = linkProgram(kMeshVertex, kMeshFragment);
        sphereProgram = linkProgram(kSphereVertex, kSphereFragment);
        meshUniforms = std::make_unique<ProgramUniforms>(meshProgram);
        sphereUniforms = std::make_unique<ProgramUniforms>(sphereProgram);

        // The unit cube [-1,1]^3, outward-facing counter-clockwise triangles.
        const float corners[] = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1};
        const GLuint faces[] = {0, 3, 2, 0, 2, 1,  4, 5, 6, 4, 6, 7,  0, 1, 5, 0, 5, 4,
                                3, 7, 6, 3, 6, 2,  0, 4, 7, 0, 7, 3,  1, 2, 6, 1, 6, 5};
        glCreateVertexArrays(1, &cubeArray);
        glCreateBuffers(1, &cubeVertices);
        glCreateBuffers(1, &cubeIndices);
        glNamedBufferStorage(cubeVertices, sizeof corners, corners, 0);
        glNamedBufferStorage(cubeIndices, sizeof faces, faces, 0);
        glVertexArrayVertexBuffer(cubeArray, 0, cubeVertices, 0, 3 * sizeof(float));
        glVertexArrayElementBuffer(cubeArray, cubeIndices);
        glEnableVertexArrayAttrib(cubeArray, 0);
        glVertexArrayAttribFormat(cubeArray, 0, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(cubeArray, 0, 0);

        meshes.resize(s.objects.size());
        textures.assign(s.objects.size(), 0);
        for (std::size_t i = 0; i < s.objects.size(); ++i) {
            const SceneObject& object = s.objects[i];
            if (const auto* mesh = std::get_if<MeshShape>(&object.shape)) uploadMesh(*mesh->mesh, meshes[i]);
            if (const auto& texture = object.material.diffuseTexture; texture && texture->pixels())
                textures[i] = uploadImage(*texture->pixels());
        }
        measureBounds();
        checkGl("uploading the scene");
    }

    // The box around every object, which sets the depth range drawn.
    void measureBounds() {
        bool first = true;
        const auto grow = [&](const Vec3& lo, const Vec3& hi) {
            for (int a = 0; a < 3; ++a) {
                sceneLower[a] = first ? lo[a] : std::min(sceneLower[a], lo[a]);
                sceneUpper[a] = first ? hi[a] : std::max(sceneUpper[a], hi[a]);
            }
            first = false;
        };
        for (const SceneObject& object : scene->objects) {
            if (const auto* sphere = std::get_if<Sphere>(&object.shape)) {
                const Vec3 r{sphere->radius, sphere->radius, sphere->radius};
                grow(sphere->center - r, sphere->center + r);
            } else {
                for (const Vec3& p : std::get<MeshShape>(object.shape).mesh->positions) grow(p, p);
            }
        }
    }

    static void releaseMesh(MeshBuffers& m) {
        glDeleteVertexArrays(1, &m.vertexArray);
        glDeleteBuffers(1, &m.vertices);
        glDeleteBuffers(1, &m.indices);
        m = MeshBuffers{};
    }

    static void uploadMesh(const TriangleMesh& mesh, MeshBuffers& out) {
        // Interleaved position, normal, uv; absent normals/uvs are zero.
        std::vector<float> data(mesh.positions.size() * 8, 0.0f);
        for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
            float* d = &data[8 * v];
            d[0] = mesh.positions[v].x;
            d[1] = mesh.positions[v].y;
            d[2] = mesh.positions[v].z;
            if (!mesh.normals.empty()) {
                d[3] = mesh.normals[v].x;
                d[4] = mesh.normals[v].y;
                d[5] = mesh.normals[v].z;
            }
            if (!mesh.uvs.empty()) {
                d[6] = mesh.uvs[v][0];
                d[7] = mesh.uvs[v][1];
            }
        }
        glCreateVertexArrays(1, &out.vertexArray);
        glCreateBuffers(1, &out.vertices);
        glCreateBuffers(1, &out.indices);
        glNamedBufferStorage(out.vertices, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data(), 0);
        glNamedBufferStorage(out.indices, static_cast<GLsizeiptr>(mesh.triangles.size() * sizeof(mesh.triangles[0])),
                             mesh.triangles.data(), 0);
        glVertexArrayVertexBuffer(out.vertexArray, 0, out.vertices, 0, 8 * sizeof(float));
        glVertexArrayElementBuffer(out.vertexArray, out.indices);
        const GLint sizes[] = {3, 3, 2};
        const GLuint offsets[] = {0, 3 * sizeof(float), 6 * sizeof(float)};
        for (GLuint a = 0; a < 3; ++a) {
            glEnableVertexArrayAttrib(out.vertexArray, a);
            glVertexArrayAttribFormat(out.vertexArray, a, sizes[a], GL_FLOAT, GL_FALSE, offsets[a]);
            glVertexArrayAttribBinding(out.vertexArray, a, 0);
        }
        out.indexCount = static_cast<GLsizei>(3 * mesh.triangles.size());
        out.hasNormals = !mesh.normals.empty();
    }

    // Texture::sample filters bilinearly with texel centres at half-integers,
    // repeating, v = 0 at the image's bottom row: GL's own linear/repeat
    // sampling once the rows go in bottom first.
    static GLuint uploadImage(const Image& image) {
        std::vector<float> rgb(static_cast<std::size_t>(image.width()) * static_cast<std::size_t>(image.height()) * 3);
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) {
                const Rgb& c = image.at(x, image.height() - 1 - y);
                float* d = &rgb[3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width()) +
                                     static_cast<std::size_t>(x))];
                d[0] = c.r;
                d[1] = c.g;
                d[2] = c.b;
            }
        GLuint texture = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &texture);
        glTextureStorage2D(texture, 1, GL_RGB32F, image.width(), image.height());
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTextureSubImage2D(texture, 0, 0, 0, image.width(), image.height(), GL_RGB, GL_FLOAT, rgb.data());
        glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_REPEAT);
        glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_REPEAT);
        return texture;
    }

    // Per-frame camera uniforms of one program. The matrix maps the camera's
    // frame exactly as CameraRays does (pixel centres at the same NDC), with
    // y flipped so framebuffer row 0 is the image's top row.
    void setCamera(const ProgramUniforms& u, const Camera& camera, int w, int h, float farDistance) const {
        const Vec3 o = camera.position;
        const Vec3 forward = normalize(camera.lookAt - camera.position);
        const Vec3 right = normalize(cross(forward, camera.up));
        const Vec3 up = cross(right, forward);
        const float tanHalf = std::tan(0.5f * camera.verticalFovDeg * std::numbers::pi_v<float> / 180.0f);
        const float aspect = static_cast<float>(w) / static_cast<float>(h);
        const double sx = static_cast<double>(tanHalf) * static_cast<double>(aspect);
        const double sy = static_cast<double>(tanHalf);
        const double n = static_cast<double>(farDistance) * 1e-5, f = static_cast<double>(farDistance);
        const double a = (f + n) / (f - n), b = -2.0 * f * n / (f - n);
        const auto row = [&](const Vec3& axis, double scale, double* out) {
            out[0] = axis.x * scale;
            out[1] = axis.y * scale;
            out[2] = axis.z * scale;
            out[3] = -static_cast<double>(dot(axis, o)) * scale;
        };
        double m[4][4];
        row(right, 1.0 / sx, m[0]);
        row(up, -1.0 / sy, m[1]);
        row(forward, 1.0, m[3]);
        for (int c = 0; c < 4; ++c) m[2][c] = a * m[3][c] + (c == 3 ? b : 0.0);
        float columnMajor[16];
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) columnMajor[c * 4 + r] = static_cast<float>(m[r][c]);
        glUniformMatrix4fv(u.viewProjection, 1, GL_FALSE, columnMajor);
        uniform3(u.cameraOrigin, o);
        uniform3(u.cameraForward, forward);
        uniform3(u.cameraRight, right * (tanHalf * aspect));
        uniform3(u.cameraUp, up * tanHalf);
        glUniform2f(u.invSize, 1.0f / static_cast<float>(w), 1.0f / static_cast<float>(h));
        glUniform1f(u.invFar, 1.0f / farDistance);
        glUniform1i(u.image, 0);
    }

    void setMaterial(const ProgramUniforms& u, std::size_t objectIndex) const {
        const Material& m = scene->objects[objectIndex].material;
        glUniform1i(u.objectId, static_cast<GLint>(objectIndex));
        glUniform3f(u.diffuse, m.diffuse.r, m.diffuse.g, m.diffuse.b);
        int kind = 0;
        if (m.diffuseTexture) {
            if (textures[objectIndex]) {
                kind = 2;
                glBindTextureUnit(0, textures[objectIndex]);
            } else {
                kind = 1;
                const Checkerboard& c = *m.diffuseTexture->checkerboardPattern();
                glUniform3f(u.checkerEven, c.even.r, c.even.g, c.even.b);
                glUniform3f(u.checkerOdd, c.odd.r, c.odd.g, c.odd.b);
                glUniform1f(u.squaresPerUnit, c.squaresPerUnit);
            }
        }
        glUniform1i(u.textureKind, kind);
    }

    // Distance from `o` to the farthest corner of the scene's box: the far plane.
    float farthestDistance(const Vec3& o) const {
        float far2 = 0.0f;
        for (int corner = 0; corner < 8; ++corner) {
            const Vec3 p{(corner & 1) ? sceneUpper[0] : sceneLower[0], (corner & 2) ? sceneUpper[1] : sceneLower[1],
                         (corner & 4) ? sceneUpper[2] : sceneLower[2]};
            far2 = std::max(far2, dot(p - o, p - o));
        }
        return std::sqrt(far2) * 1.01f + 1e-3f;
    }
};

GBufferRasterizer::GBufferRasterizer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GBufferRasterizer::~GBufferRasterizer() = default;

void GBufferRasterizer::sceneChanged(std::span<const int> changed) {
    Impl& g = *impl_;
    g.context->makeCurrent();
    for (const int id : changed) {
        const auto i = static_cast<std::size_t>(id);
        // Spheres are drawn from the scene every frame; meshes live in buffers.
        if (const auto* mesh = std::get_if<MeshShape>(&g.scene->objects[i].shape)) {
            Impl::releaseMesh(g.meshes[i]);
            Impl::uploadMesh(*mesh->mesh, g.meshes[i]);
        }
    }
    g.measureBounds();
    checkGl("updating the scene");
}

std::unique_ptr<GBufferRasterizer> GBufferRasterizer::create(const Scene& scene, std::string& whyNot) {
    auto impl = std::make_unique<Impl>();
    impl->context = GlContext::create(whyNot, 4, 5);
    if (!impl->context) return nullptr;
    impl->uploadScene(scene);
    std::unique_ptr<GBufferRasterizer> rasterizer(new GBufferRasterizer(std::move(impl)));
    // Mesa compiles shader variants at their first draw; one tiny frame here
    // keeps that (about 0.2 s on llvmpipe) out of the first real frame.
    RasterTimes ignored;
    rasterizer->rasterize(scene.camera, 8, 8, ignored);
    return rasterizer;
}

const std::string& GBufferRasterizer::description() const { return impl_->context->description(); }

GBufferView GBufferRasterizer::rasterize(const Camera& camera, int width, int height, RasterTimes& times) {
    Impl& g = *impl_;
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    g.context->makeCurrent();
    if (width != g.width || height != g.height) g.makeTargets(width, height);

    glBindFramebuffer(GL_FRAMEBUFFER, g.framebuffer);
    glViewport(0, 0, width, height);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    // The projection flips y, which flips the winding seen on screen.
    glFrontFace(GL_CW);
    const float background[4] = {0.0f, 0.0f, 0.0f, -1.0f};
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const GLint noIds[4] = {-1, -1, 0, 0};
    const float farDepth = 1.0f;
    glClearBufferfv(GL_COLOR, 0, background);
    glClearBufferfv(GL_COLOR, 1, zero);
    glClearBufferfv(GL_COLOR, 2, zero);
    glClearBufferiv(GL_COLOR, 3, noIds);
    glClearBufferfv(GL_DEPTH, 0, &farDepth);

    const float farDistance = g.farthestDistance(camera.position);
    const Scene& scene = *g.scene;

    // Meshes: both sides drawn (glass is seen from inside, planes from both sides).
    glDisable(GL_CULL_FACE);
    glUseProgram(g.meshProgram);
    g.setCamera(*g.meshUniforms, camera, width, height, farDistance);
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        if (std::holds_alternative<Sphere>(scene.objects[i].shape)) continue;
        const MeshBuffers& m = g.meshes[i];
        g.setMaterial(*g.meshUniforms, i);
        glUniform1i(g.meshUniforms->hasNormals, m.hasNormals ? 1 : 0);
        glBindVertexArray(m.vertexArray);
        glDrawElements(GL_TRIANGLES, m.indexCount, GL_UNSIGNED_INT, nullptr);
    }

    // Spheres: the back faces of a box around each one, so every pixel whose
    // ray meets the sphere gets exactly one fragment, wherever the camera is.
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glUseProgram(g.sphereProgram);
    g.setCamera(*g.sphereUniforms, camera, width, height, farDistance);
    glBindVertexArray(g.cubeArray);
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
        const auto* sphere = std::get_if<Sphere>(&scene.objects[i].shape);
        if (!sphere) continue;
        g.setMaterial(*g.sphereUniforms, i);
        uniform3(g.sphereUniforms->sphereCenter, sphere->center);
        glUniform1f(g.sphereUniforms->sphereRadius, sphere->radius);
        glUniform1f(g.sphereUniforms->boxHalfSize, sphere->radius * 1.001f + 1e-4f);
        glDrawElements(GL_TRIANGLES, 36, GL_UNSIGNED_INT, nullptr);
    }
    glBindVertexArray(0);
    glFinish();
    checkGl("drawing the G-buffer");
    const auto drawn = Clock::now();

    // One readback per frame: every target into its slice of the mapped
    // buffer, then a single fence to wait on.
    glBindBuffer(GL_PIXEL_PACK_BUFFER, g.readback);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    for (int t = 0; t < kTargets; ++t) {
        glReadBuffer(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(t));
        const bool ids = t == kTargets - 1;
        glReadPixels(0, 0, width, height, ids ? GL_RG_INTEGER : GL_RGBA, ids ? GL_INT : GL_FLOAT,
                     reinterpret_cast<void*>(g.targetOffset(t)));
    }
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    const GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    const GLenum waited = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, 60'000'000'000ull);
    glDeleteSync(fence);
    checkGl("reading the G-buffer back");
    if (waited != GL_ALREADY_SIGNALED && waited != GL_CONDITION_SATISFIED)
        throw RuntimeError("OpenGL: the G-buffer readback did not complete");
    const auto readBack = Clock::now();

    times.raster = std::chrono::duration<double, std::milli>(drawn - start).count();
    times.readback = std::chrono::duration<double, std::milli>(readBack - drawn).count();
    GBufferView view;
    view.width = width;
    view.height = height;
    view.positionDepth = reinterpret_cast<const float*>(g.mapped + g.targetOffset(0));
    view.normal = reinterpret_cast<const float*>(g.mapped + g.targetOffset(1));
    view.albedo = reinterpret_cast<const float*>(g.mapped + g.targetOffset(2));
    view.ids = reinterpret_cast<const std::int32_t*>(g.mapped + g.targetOffset(3));
    return view;
}

}  // namespace raycache
