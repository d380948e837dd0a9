// A part of bench/zbuffer_vs_llvmpipe.cpp (included by it alone): llvmpipe through OSMesa, in a
// child process of its own (LP_NUM_THREADS is read once per process), drawing the same torus
// with the same shading as luz's zbuffer.
#pragma once

#include <GL/osmesa.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/scene.h"
#include "image/image_io.h"
#include "machine_load.h"
#include "render/zbuffer.h"
#include "scene/camera.h"
#include "zbuffer_bench_workload.h"

namespace luz::zbuffer_bench {

// ---------------------------------------------------------------------------------------------
// llvmpipe through OSMesa (runs in a child process)

#define LUZ_GL_FUNCTIONS(X)                                        \
    X(PFNGLGENBUFFERSPROC, glGenBuffers)                           \
    X(PFNGLBINDBUFFERPROC, glBindBuffer)                           \
    X(PFNGLBUFFERDATAPROC, glBufferData)                           \
    X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays)                 \
    X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray)                 \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray) \
    X(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer)         \
    X(PFNGLCREATESHADERPROC, glCreateShader)                       \
    X(PFNGLSHADERSOURCEPROC, glShaderSource)                       \
    X(PFNGLCOMPILESHADERPROC, glCompileShader)                     \
    X(PFNGLGETSHADERIVPROC, glGetShaderiv)                         \
    X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)               \
    X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                     \
    X(PFNGLATTACHSHADERPROC, glAttachShader)                       \
    X(PFNGLLINKPROGRAMPROC, glLinkProgram)                         \
    X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                       \
    X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)             \
    X(PFNGLUSEPROGRAMPROC, glUseProgram)                           \
    X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)           \
    X(PFNGLUNIFORM1FPROC, glUniform1f)                             \
    X(PFNGLUNIFORM3FPROC, glUniform3f)                             \
    X(PFNGLUNIFORMMATRIX4FVPROC, glUniformMatrix4fv)               \
    X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers)                 \
    X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                 \
    X(PFNGLGENRENDERBUFFERSPROC, glGenRenderbuffers)               \
    X(PFNGLBINDRENDERBUFFERPROC, glBindRenderbuffer)               \
    X(PFNGLRENDERBUFFERSTORAGEPROC, glRenderbufferStorage)         \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, glFramebufferRenderbuffer) \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus)

struct Gl {
#define LUZ_GL_DECLARE(type, name) type name = nullptr;
    LUZ_GL_FUNCTIONS(LUZ_GL_DECLARE)
#undef LUZ_GL_DECLARE

    void load() {
#define LUZ_GL_LOAD(type, name)                                 \
    name = reinterpret_cast<type>(OSMesaGetProcAddress(#name)); \
    if (!name) throw std::runtime_error("OSMesaGetProcAddress failed: " #name);
        LUZ_GL_FUNCTIONS(LUZ_GL_LOAD)
#undef LUZ_GL_LOAD
    }
};

// The same orthographic projection as luz's camera (docs/SCENES.md#geometry), as one matrix.
const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 clip_from_world;
out vec3 P;
out vec3 N_in;
void main() {
    gl_Position = clip_from_world * vec4(position, 1.0);
    P = position;
    N_in = normal;
}
)";

// docs/SCENES.md#models phong with one light, two-sided normals, exactly as shade() computes it:
// I = Ia·Ka + Il/(d+K)·(Kd·cosθ + Ks·cosα^n).
const char* kFragmentShader = R"(#version 330 core
in vec3 P;
in vec3 N_in;
uniform vec3 S;  // towards the viewer (orthographic: the camera's w)
uniform vec3 Ia;
uniform vec3 Ka;
uniform vec3 Kd;
uniform vec3 Ks;
uniform float n;
uniform float K;
uniform vec3 Lp;
uniform vec3 Il;
out vec4 colour;
void main() {
    vec3 N = normalize(N_in);
    if (dot(N, S) < 0.0) N = -N;  // two-sided normals (docs/SCENES.md#geometry)
    vec3 I = Ia * Ka;
    vec3 to_light = Lp - P;
    float d = length(to_light);
    vec3 L = to_light / d;
    float N_dot_L = dot(N, L);
    if (N_dot_L > 0.0) {
        vec3 R = 2.0 * N_dot_L * N - L;
        float cos_alpha = max(0.0, dot(R, S));
        I += Il / (d + K) * (Kd * N_dot_L + Ks * pow(cos_alpha, n));
    }
    colour = vec4(clamp(I, 0.0, 1.0), 1.0);
}
)";

inline GLuint compile(const Gl& gl, GLenum type, const char* source) {
    const GLuint s = gl.glCreateShader(type);
    gl.glShaderSource(s, 1, &source, nullptr);
    gl.glCompileShader(s);
    GLint ok = 0;
    gl.glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096];
        gl.glGetShaderInfoLog(s, sizeof log, nullptr, log);
        throw std::runtime_error(std::string("shader compile failed: ") + log);
    }
    return s;
}

/// Renders the scene's mesh with llvmpipe at the thread count of this process's environment;
/// prints the results on standard output and writes the RGBA8 image (rows top to bottom) to
/// `image_path`.
inline int llvmpipe_child(int level, const std::string& image_path, const Options& opt) {
    const TorusScene torus = torus_scene(level);
    const ZbufferGeometry geometry = prepare_zbuffer(torus.scene, torus.desc);
    const TriangleMesh& mesh = geometry.mesh;
    static_assert(sizeof(Vec3) == 3 * sizeof(float));

    // A 3.3 core context (Mesa 22.3's OSMesa offers it); compatibility profile as a fallback.
    const int core[] = {OSMESA_FORMAT,
                        OSMESA_RGBA,
                        OSMESA_DEPTH_BITS,
                        24,
                        OSMESA_STENCIL_BITS,
                        0,
                        OSMESA_PROFILE,
                        OSMESA_CORE_PROFILE,
                        OSMESA_CONTEXT_MAJOR_VERSION,
                        3,
                        OSMESA_CONTEXT_MINOR_VERSION,
                        3,
                        0};
    OSMesaContext ctx = OSMesaCreateContextAttribs(core, nullptr);
    const char* profile = "3.3 core";
    if (!ctx) {
        const int compat[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, 0};
        ctx = OSMesaCreateContextAttribs(compat, nullptr);
        profile = "compatibility";
    }
    if (!ctx) throw std::runtime_error("OSMesaCreateContextAttribs failed");
    std::vector<uint8_t> window(static_cast<size_t>(kWidth) * kHeight * 4);
    if (!OSMesaMakeCurrent(ctx, window.data(), GL_UNSIGNED_BYTE, kWidth, kHeight))
        throw std::runtime_error("OSMesaMakeCurrent failed");
    Gl gl;
    gl.load();

    // Render target: an off-screen framebuffer (so glFinish does not copy to the OSMesa
    // buffer every frame), colour RGBA8 (or RGBA32F) and a 24-bit depth buffer.
    GLuint fbo, rb[2];
    gl.glGenFramebuffers(1, &fbo);
    gl.glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.glGenRenderbuffers(2, rb);
    gl.glBindRenderbuffer(GL_RENDERBUFFER, rb[0]);
    gl.glRenderbufferStorage(GL_RENDERBUFFER, opt.float_target ? GL_RGBA32F : GL_RGBA8, kWidth,
                             kHeight);
    gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
    gl.glBindRenderbuffer(GL_RENDERBUFFER, rb[1]);
    gl.glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, kWidth, kHeight);
    gl.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
    if (gl.glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("framebuffer incomplete");

    // The mesh in buffer objects, uploaded once (not timed, like luz's prepare_zbuffer).
    GLuint vao, vbo[3];
    gl.glGenVertexArrays(1, &vao);
    gl.glBindVertexArray(vao);
    gl.glGenBuffers(3, vbo);
    gl.glBindBuffer(GL_ARRAY_BUFFER, vbo[0]);
    gl.glBufferData(GL_ARRAY_BUFFER, mesh.positions.size() * sizeof(Vec3), mesh.positions.data(),
                    GL_STATIC_DRAW);
    gl.glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
    gl.glEnableVertexAttribArray(0);
    gl.glBindBuffer(GL_ARRAY_BUFFER, vbo[1]);
    gl.glBufferData(GL_ARRAY_BUFFER, mesh.normals.size() * sizeof(Vec3), mesh.normals.data(),
                    GL_STATIC_DRAW);
    gl.glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Vec3), nullptr);
    gl.glEnableVertexAttribArray(1);
    gl.glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, vbo[2]);
    gl.glBufferData(GL_ELEMENT_ARRAY_BUFFER, mesh.indices.size() * sizeof(uint32_t),
                    mesh.indices.data(), GL_STATIC_DRAW);

    const GLuint program = gl.glCreateProgram();
    gl.glAttachShader(program, compile(gl, GL_VERTEX_SHADER, kVertexShader));
    gl.glAttachShader(program, compile(gl, GL_FRAGMENT_SHADER, kFragmentShader));
    gl.glLinkProgram(program);
    GLint ok = 0;
    gl.glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096];
        gl.glGetProgramInfoLog(program, sizeof log, nullptr, log);
        throw std::runtime_error(std::string("program link failed: ") + log);
    }
    gl.glUseProgram(program);

    // clip_from_world: x = (p−eye)·u / half_width, y = (p−eye)·v / half_height
    // (docs/SCENES.md#geometry), z = the view depth −(p−eye)·w mapped from [near, far] (the mesh's
    // extent) to [−1, 1].
    const SceneDesc& desc = torus.desc;
    const Camera cam = Camera::from(desc.camera, kWidth, kHeight);
    float near = 1e30f, far = -1e30f;
    for (const Vec3& p : mesh.positions) {
        near = std::min(near, cam.to_view(p).z);
        far = std::max(far, cam.to_view(p).z);
    }
    near -= 0.01f * (far - near) + 1e-3f;
    far += 0.01f * (far - near) + 1e-3f;
    const float a = 2.0f / (far - near), b = -2.0f * near / (far - near) - 1.0f;
    const Vec3& e = cam.position;
    const float rows[16] = {cam.u.x / cam.half_width,
                            cam.u.y / cam.half_width,
                            cam.u.z / cam.half_width,
                            -dot(cam.u, e) / cam.half_width,
                            cam.v.x / cam.half_height,
                            cam.v.y / cam.half_height,
                            cam.v.z / cam.half_height,
                            -dot(cam.v, e) / cam.half_height,
                            -a * cam.w.x,
                            -a * cam.w.y,
                            -a * cam.w.z,
                            a * dot(cam.w, e) + b,
                            0,
                            0,
                            0,
                            1};
    gl.glUniformMatrix4fv(gl.glGetUniformLocation(program, "clip_from_world"), 1, GL_TRUE, rows);
    const Material& m = desc.materials[0];
    const Light& light = desc.lights[0];
    auto set3 = [&](const char* name, const Vec3& v) {
        gl.glUniform3f(gl.glGetUniformLocation(program, name), v.x, v.y, v.z);
    };
    set3("S", cam.w);
    set3("Ia", desc.ambient);
    set3("Ka", m.ka);
    set3("Kd", m.kd);
    set3("Ks", m.ks);
    set3("Lp", light.position);
    set3("Il", light.intensity);
    gl.glUniform1f(gl.glGetUniformLocation(program, "n"), m.n);
    gl.glUniform1f(gl.glGetUniformLocation(program, "K"), desc.attenuation_k);

    glViewport(0, 0, kWidth, kHeight);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    const Rgb bg = desc.image.background;
    glClearColor(bg.x, bg.y, bg.z, 1.0f);
    if (glGetError() != GL_NO_ERROR) throw std::runtime_error("GL error during set-up");

    const auto count = static_cast<GLsizei>(mesh.indices.size());
    auto frame = [&] {
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
        glFinish();
    };
    for (int i = 0; i < 3; ++i) frame();  // warm-up: shader compilation, buffer residency
    if (glGetError() != GL_NO_ERROR) throw std::runtime_error("GL error while rendering");
    std::printf("renderer %s\n", reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    std::printf("version %s (%s)\n", reinterpret_cast<const char*>(glGetString(GL_VERSION)),
                profile);
    std::printf("hash %016llx\n", static_cast<unsigned long long>(mesh_hash(mesh)));
    std::printf("threads %d\nready\n", process_threads());
    std::fflush(stdout);

    // Requests from the parent: "frames K" renders K frames and answers with their times;
    // "quit" ends.
    char line[256];
    while (std::fgets(line, sizeof line, stdin)) {
        int k = 0;
        if (std::sscanf(line, "frames %d", &k) != 1) break;
        const Batch b = run_batch(frame, k);
        std::printf("batch %.6f %.6f", b.cpu_ms, b.others);
        for (double ms : b.ms) std::printf(" %.6f", ms);
        std::printf("\n");
        std::fflush(stdout);
    }
    if (glGetError() != GL_NO_ERROR) throw std::runtime_error("GL error while rendering");

    // Read back (GL's rows go bottom to top; the file's top to bottom, as luz's image).
    std::vector<uint8_t> rgba(static_cast<size_t>(kWidth) * kHeight * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, kWidth, kHeight, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    std::ofstream out(image_path, std::ios::binary);
    for (int row = kHeight - 1; row >= 0; --row)
        out.write(reinterpret_cast<const char*>(&rgba[static_cast<size_t>(row) * kWidth * 4]),
                  kWidth * 4);
    if (!out) throw std::runtime_error("cannot write " + image_path);
    out.close();
    OSMesaDestroyContext(ctx);
    return 0;
}

inline std::string self_path() {
    char buf[4096];
    const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
    if (n <= 0) throw std::runtime_error("cannot read /proc/self/exe");
    return std::string(buf, static_cast<size_t>(n));
}

/// One llvmpipe child process (this program with --llvmpipe-child) at a fixed thread count.
class LlvmpipeChild {
  public:
    std::string renderer, version;
    uint64_t hash = 0;
    int threads_in_process = 0;  ///< after the first frames: main thread + llvmpipe's threads

    LlvmpipeChild(int level, int threads, bool float_target) {
        char path[] = "/tmp/luz_bench_llvmpipe_XXXXXX";
        const int fd = mkstemp(path);
        if (fd < 0) throw std::runtime_error("mkstemp failed");
        close(fd);
        image_path_ = path;
        // The child inherits the environment: set before its (only) GL context exists.
        setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);
        setenv("GALLIUM_DRIVER", "llvmpipe", 1);
        int to_child[2], from_child[2];
        if (pipe(to_child) != 0 || pipe(from_child) != 0) throw std::runtime_error("pipe failed");
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_adddup2(&actions, to_child[0], 0);
        posix_spawn_file_actions_adddup2(&actions, from_child[1], 1);
        for (int p : {to_child[0], to_child[1], from_child[0], from_child[1]})
            posix_spawn_file_actions_addclose(&actions, p);
        const std::string exe = self_path(), level_arg = std::to_string(level);
        std::vector<const char*> argv = {exe.c_str(), "--llvmpipe-child", level_arg.c_str(),
                                         image_path_.c_str()};
        if (float_target) argv.push_back("--float-target");
        argv.push_back(nullptr);
        const int err = posix_spawn(&pid_, exe.c_str(), &actions, nullptr,
                                    const_cast<char* const*>(argv.data()), environ);
        posix_spawn_file_actions_destroy(&actions);
        close(to_child[0]);
        close(from_child[1]);
        to_ = fdopen(to_child[1], "w");
        from_ = fdopen(from_child[0], "r");
        if (err != 0 || !to_ || !from_) throw std::runtime_error("cannot start llvmpipe child");
        for (std::string s; (s = read_line()) != "ready";) {
            if (s.rfind("renderer ", 0) == 0) renderer = s.substr(9);
            if (s.rfind("version ", 0) == 0) version = s.substr(8);
            if (s.rfind("hash ", 0) == 0) hash = std::stoull(s.substr(5), nullptr, 16);
            if (s.rfind("threads ", 0) == 0) threads_in_process = std::stoi(s.substr(8));
        }
    }
    LlvmpipeChild(const LlvmpipeChild&) = delete;
    LlvmpipeChild& operator=(const LlvmpipeChild&) = delete;
    ~LlvmpipeChild() {
        if (pid_ > 0) {  // not finished (an error elsewhere): stop it
            if (to_) std::fclose(to_);
            kill(pid_, SIGTERM);
            waitpid(pid_, nullptr, 0);
        }
        if (from_) std::fclose(from_);
        unlink(image_path_.c_str());
    }

    /// Renders k frames in the child.
    Batch frames(int k) {
        std::fprintf(to_, "frames %d\n", k);
        std::fflush(to_);
        std::istringstream in(read_line());
        std::string word;
        Batch b;
        in >> word >> b.cpu_ms >> b.others;
        for (double ms; in >> ms;) b.ms.push_back(ms);
        if (word != "batch" || static_cast<int>(b.ms.size()) != k)
            throw std::runtime_error("llvmpipe child: bad answer");
        return b;
    }

    /// Ends the child and returns the image of its last frame (RGBA8, rows top to bottom).
    std::vector<uint8_t> finish() {
        std::fclose(to_);
        to_ = nullptr;
        int status = 0;
        waitpid(pid_, &status, 0);
        pid_ = -1;
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
            throw std::runtime_error("llvmpipe child failed");
        std::vector<uint8_t> rgba(static_cast<size_t>(kWidth) * kHeight * 4);
        std::ifstream in(image_path_, std::ios::binary);
        in.read(reinterpret_cast<char*>(rgba.data()), static_cast<std::streamsize>(rgba.size()));
        if (!in) throw std::runtime_error("cannot read the llvmpipe image");
        return rgba;
    }

  private:
    pid_t pid_ = -1;
    FILE* to_ = nullptr;
    FILE* from_ = nullptr;
    std::string image_path_;

    std::string read_line() {
        std::string s;
        for (int c; (c = std::fgetc(from_)) != EOF && c != '\n';) s += static_cast<char>(c);
        if (s.empty() && std::feof(from_)) throw std::runtime_error("llvmpipe child ended early");
        return s;
    }
};

}  // namespace luz::zbuffer_bench
