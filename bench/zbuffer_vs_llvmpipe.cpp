// Benchmark: luz's zbuffer frame time against Mesa's llvmpipe (OpenGL through OSMesa) on the
// same tessellated torus (~5k, ~100k, ~1M triangles), 1024×1024, orthographic,
// docs/SCENES.md#models phong with one light, per-pixel shading, 1 and 2 threads. Results go to
// docs/BENCHMARKS.md.
//
// llvmpipe reads LP_NUM_THREADS once, when its screen is created (the first context of the
// process), so each llvmpipe thread count runs in its own child process (this program
// re-executed with --llvmpipe-child) started with LP_NUM_THREADS and GALLIUM_DRIVER=llvmpipe
// set. The child builds the same mesh through the same luz code (checked by a hash), then
// renders batches of frames on request, so that luz and llvmpipe batches alternate in one
// timeline: a machine whose speed drifts (a shared virtual machine) slows all alike. At the end
// the child writes its image, and the parent checks that both renderers drew the same picture.
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

namespace {

using namespace luz;

constexpr int kWidth = 1024, kHeight = 1024;

/// A benchmark size: the torus tessellation level giving about that many triangles
/// (level·max(3, level/2)·2 triangles).
struct BenchSize {
    const char* name;
    int level;
};
constexpr BenchSize kSizes[] = {{"5k", 72}, {"100k", 316}, {"1M", 1000}};

/// What a run measures: many frames, their median wall time and the process CPU time.
struct Timing {
    double median_ms = 0;
    double cpu_ms = 0;  ///< process CPU time per frame, all threads (utilization = cpu/wall)
    double others = 0;  ///< cores kept busy by other processes meanwhile (should be ≈ 0)
    int frames = 0;
};

struct Options {
    int min_frames = 10;
    double min_seconds = 1.0;
    std::vector<BenchSize> sizes{std::begin(kSizes), std::end(kSizes)};
    bool luz = true, llvmpipe = true, breakdown = true;
    bool float_target = false;  ///< llvmpipe renders to RGBA32F instead of RGBA8
    double idle_wait = 120;     ///< longest wait for an idle machine, in seconds (0: never)
    std::string save_dir;       ///< write both images of every size there
    int profile_level = 0;      ///< > 0: only render luz frames at this level (for callgrind)
    int profile_threads = 1, profile_frames = 3;
};

// ---------------------------------------------------------------------------------------------
// The workload

/// A description and the runtime scene built from it (the scene no longer carries its
/// description: renders take the settings beside it).
struct TorusScene {
    SceneDesc desc;
    BuiltScene scene;
};

/// The benchmark scene: one torus seen at 45° from its axis, filling most of a 1024² image,
/// orthographic camera, one white point light, phong.
TorusScene torus_scene(int level) {
    SceneDesc d;
    d.name = "bench_torus";
    d.source = "zbuffer_vs_llvmpipe";
    d.image.width = kWidth;
    d.image.height = kHeight;
    d.image.background = Rgb{0.05f, 0.05f, 0.08f};
    d.camera.projection = Projection::orthographic;
    d.camera.position = {0, 0, 10};
    d.camera.look_at = {0, 0, 0};
    d.camera.up = {0, 1, 0};
    d.camera.view_height = 3.0f;
    d.render.pipeline = Pipeline::zbuffer;
    d.render.model = Model::phong;
    d.geometry.tessellation = level;
    d.ambient = Rgb{1.0f};
    d.attenuation_k = 1.0f;
    d.lights = {Light{{4, 5, 8}, Rgb{12.0f}, 0.0f}};
    Material m;
    m.name = "bench";
    m.ka = Rgb{0.1f};
    m.kd = Rgb{0.7f, 0.35f, 0.2f};
    m.ks = Rgb{0.5f};
    m.n = 30.0f;
    d.materials = {m};
    ObjectDesc torus;
    torus.type = ShapeType::torus;
    torus.path = "objects.0";
    torus.center = {0, 0, 0};
    torus.axis = {0, 1, 1};
    torus.major_radius = 1.0f;
    torus.minor_radius = 0.4f;
    d.objects = {torus};
    BuiltScene scene = build_scene(d);
    return {std::move(d), std::move(scene)};
}

/// FNV-1a over the mesh arrays: both processes must render the very same data.
uint64_t mesh_hash(const TriangleMesh& m) {
    uint64_t h = 1469598103934665603ull;
    auto add = [&](const void* data, size_t bytes) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
    };
    add(m.positions.data(), m.positions.size() * sizeof(Vec3));
    add(m.normals.data(), m.normals.size() * sizeof(Vec3));
    add(m.indices.data(), m.indices.size() * sizeof(uint32_t));
    return h;
}

using bench::cpu_seconds;
using bench::machine_busy_seconds;

/// The number of threads of this process (/proc/self/status), or −1.
int process_threads() {
    std::ifstream in("/proc/self/status");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("Threads:", 0) == 0) return std::stoi(line.substr(8));
    return -1;
}

/// Frames timed one by one, with the process CPU time and other processes' load meanwhile.
struct Batch {
    std::vector<double> ms;
    double cpu_ms = 0;  ///< process CPU time over the whole batch, all threads
    double others = 0;  ///< cores used by other processes meanwhile
};

/// Runs `frame` k times.
Batch run_batch(const std::function<void()>& frame, int k) {
    using clock = std::chrono::steady_clock;
    Batch b;
    const double cpu_start = cpu_seconds(), machine_start = machine_busy_seconds();
    const auto start = clock::now();
    for (int i = 0; i < k; ++i) {
        const auto t0 = clock::now();
        frame();
        b.ms.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
    }
    const double wall = std::chrono::duration<double>(clock::now() - start).count();
    const double own = cpu_seconds() - cpu_start;
    b.cpu_ms = 1000.0 * own;
    if (machine_start >= 0)
        b.others = std::max(0.0, (machine_busy_seconds() - machine_start - own) / wall);
    return b;
}

/// The frames of one configuration, gathered batch by batch.
struct Series {
    std::vector<double> ms;
    double cpu_ms = 0, seconds = 0, others = 0;

    void add(const Batch& b) {
        ms.insert(ms.end(), b.ms.begin(), b.ms.end());
        cpu_ms += b.cpu_ms;
        for (double x : b.ms) seconds += x / 1000.0;
        others = std::max(others, b.others);
    }
    double median() const {
        if (ms.empty()) return 0;
        std::vector<double> x = ms;
        std::sort(x.begin(), x.end());
        return x.size() % 2 ? x[x.size() / 2] : 0.5 * (x[x.size() / 2 - 1] + x[x.size() / 2]);
    }
    Timing timing() const {
        Timing t;
        t.frames = static_cast<int>(ms.size());
        t.median_ms = median();
        t.cpu_ms = t.frames ? cpu_ms / t.frames : 0;
        t.others = others;
        return t;
    }
};

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

GLuint compile(const Gl& gl, GLenum type, const char* source) {
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
int llvmpipe_child(int level, const std::string& image_path, const Options& opt) {
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

std::string self_path() {
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

// ---------------------------------------------------------------------------------------------
// luz

/// One luz frame of prepared geometry on `threads` threads, into `out`.
std::function<void()> luz_frame(const BuiltScene& scene, const Settings& settings,
                                const ZbufferGeometry& g, int threads, Image& out) {
    return [&scene, &settings, &g, threads, &out] {
        RenderControl control;
        control.threads = threads;
        RenderStats stats;
        render_zbuffer(scene, settings, g, control, out, stats);
    };
}

/// Waits until other processes leave the CPUs nearly idle (< 0.1 core over one second),
/// for at most `max_seconds`; false if they never did.
bool wait_for_idle(double max_seconds) {
    using clock = std::chrono::steady_clock;
    const auto start = clock::now();
    bool said = false;
    for (;;) {
        const double m0 = machine_busy_seconds(), c0 = cpu_seconds();
        const auto t0 = clock::now();
        usleep(1000000);
        const double wall = std::chrono::duration<double>(clock::now() - t0).count();
        const double busy = (machine_busy_seconds() - m0 - (cpu_seconds() - c0)) / wall;
        if (m0 < 0 || busy < 0.1) return true;
        if (std::chrono::duration<double>(clock::now() - start).count() >= max_seconds) {
            std::fprintf(stderr, "  machine still busy (%.2f cores): measuring anyway\n", busy);
            return false;
        }
        if (!said)
            std::fprintf(stderr, "  waiting for an idle machine (%.2f cores busy)...\n", busy);
        said = true;
    }
}

/// Measures configurations side by side: in rounds, one batch of frames of each per round
/// (in an order rotated every round, with a short pause between batches so that idle worker
/// threads go to sleep), until each has at least min_frames frames and min_seconds of frames
/// and there were at least 3 rounds. A first batch of 2 frames warms each up and is not
/// counted. A batch during which other processes took more than 0.15 core is dropped and
/// measured again once the machine is idle.
std::vector<Timing> side_by_side(const std::vector<std::function<Batch(int)>>& configs,
                                 const Options& opt) {
    const size_t n = configs.size();
    std::vector<Series> series(n);
    std::vector<double> estimate_ms(n);
    for (size_t c = 0; c < n; ++c) {
        const Batch warm = configs[c](2);
        estimate_ms[c] = *std::min_element(warm.ms.begin(), warm.ms.end());
    }
    const double batch_seconds = std::max(0.05, opt.min_seconds / 5);
    int dropped = 0;
    for (size_t round = 0;; ++round) {
        bool done = round >= 3;
        for (const Series& s : series)
            done = done && static_cast<int>(s.ms.size()) >= opt.min_frames &&
                   s.seconds >= opt.min_seconds;
        if (done) break;
        for (size_t i = 0; i < n; ++i) {
            const size_t c = (i + round) % n;
            const int k = std::clamp(
                static_cast<int>(std::lround(1000.0 * batch_seconds / estimate_ms[c])), 1, 200);
            usleep(20000);
            const Batch b = configs[c](k);
            if (opt.idle_wait > 0 && b.others > 0.15 && dropped < 50) {
                ++dropped;
                std::fprintf(stderr, "  other processes took %.2f cores: batch dropped\n",
                             b.others);
                wait_for_idle(opt.idle_wait);
                --i;  // the same configuration again
                continue;
            }
            series[c].add(b);
            estimate_ms[c] = series[c].median();
        }
    }
    std::vector<Timing> t;
    for (const Series& s : series) t.push_back(s.timing());
    return t;
}

/// Share of pixels whose 8-bit colours differ by at most `tolerance` in every channel, and
/// the largest difference.
struct Agreement {
    double within = 0;
    int max_diff = 0;
};

Agreement compare(const Image& luz_image, const std::vector<uint8_t>& rgba, int tolerance) {
    Agreement a;
    size_t ok = 0;
    for (size_t i = 0; i < luz_image.pixels.size(); ++i) {
        int worst = 0;
        for (int c = 0; c < 3; ++c) {
            const int v = encode_8bit(luz_image.pixels[i][c], Encoding::linear);
            worst = std::max(worst, std::abs(v - static_cast<int>(rgba[4 * i + c])));
        }
        a.max_diff = std::max(a.max_diff, worst);
        if (worst <= tolerance) ++ok;
    }
    a.within = 100.0 * static_cast<double>(ok) / static_cast<double>(luz_image.pixels.size());
    return a;
}

Image to_image(const std::vector<uint8_t>& rgba) {
    Image img(kWidth, kHeight);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        img.pixels[i] =
            Rgb{rgba[4 * i] / 255.0f, rgba[4 * i + 1] / 255.0f, rgba[4 * i + 2] / 255.0f};
    return img;
}

/// luz frame time split from outside, one thread, by rendering variants of the same mesh:
/// - behind: the camera turned away, every triangle behind it: the per-frame fixed cost
///   (fragment buffers, background fill of 1024² pixels), vertex projection, and the fetch and
///   clip codes of every triangle (all rejected by the camera plane);
/// - offscreen: the torus just outside the image (inside the guard band): + triangle set-up
///   (fixed-point vertices), every triangle then rejected by the binner;
/// - tiny: the view 64× wider, the whole mesh on a few pixels: + binning and the
///   per-triangle part of rasterization (edge functions, bounding box), almost no pixels;
/// - unlit: the benchmark frame with no light: pixels rasterized and shaded with Ia·Ka only;
/// - full: the benchmark frame.
struct Breakdown {
    Timing behind, offscreen, tiny, unlit, full;
};

Breakdown luz_breakdown(int level, const Options& opt) {
    const TorusScene torus = torus_scene(level);
    // The same scene and mesh for every variant; only the settings differ.
    const ZbufferGeometry g = prepare_zbuffer(torus.scene, torus.desc);
    const Settings full = torus.desc;
    Settings behind = full;
    behind.camera.look_at = {0, 0, 20};  // looking along +z from z = 10: torus behind
    Settings offscreen = full;
    offscreen.camera.position.x -= 2.5f * full.camera.view_height;
    offscreen.camera.look_at.x -= 2.5f * full.camera.view_height;
    Settings tiny = full;
    tiny.camera.view_height *= 64.0f;
    Settings unlit = full;
    unlit.lights.clear();
    Image out;
    std::vector<std::function<Batch(int)>> configs;
    for (const Settings* s :
         std::initializer_list<const Settings*>{&behind, &offscreen, &tiny, &unlit, &full})
        configs.push_back(
            [&, s](int k) { return run_batch(luz_frame(torus.scene, *s, g, 1, out), k); });
    const std::vector<Timing> t = side_by_side(configs, opt);
    return {t[0], t[1], t[2], t[3], t[4]};
}

/// One configuration's result on standard error, as it comes.
void report(const char* size, const char* renderer, int threads, const Timing& t) {
    std::fprintf(stderr,
                 "[%s] %s %dt: %.2f ms median of %d frames, cpu %.2f ms/frame, other processes "
                 "%.2f cores%s\n",
                 size, renderer, threads, t.median_ms, t.frames, t.cpu_ms, t.others,
                 t.others > 0.2 ? "  (machine busy: figures unreliable)" : "");
}

void print_usage() {
    std::printf(
        "usage: zbuffer_vs_llvmpipe [--sizes 5k,100k,1M] [--frames N] [--seconds S]\n"
        "                           [--luz-only | --llvmpipe-only] [--no-breakdown]\n"
        "                           [--idle-wait S] [--float-target] [--save DIR]\n"
        "       zbuffer_vs_llvmpipe --profile LEVEL [--threads T] [--frames N]\n"
        "  Times luz's zbuffer and Mesa's llvmpipe (OSMesa) on the same torus at 1024x1024,\n"
        "  1 and 2 threads, in alternating batches (median of >= N frames and >= S seconds of\n"
        "  frames per configuration; defaults 10, 1). Batches during which other processes\n"
        "  used the CPUs are measured again after waiting up to --idle-wait seconds (default\n"
        "  120; 0: never) for an idle machine.\n"
        "  --float-target: llvmpipe renders to RGBA32F instead of RGBA8.\n"
        "  --save DIR: write luz_SIZE.png and llvmpipe_SIZE.png there.\n"
        "  --profile renders N luz frames only (for perf or valgrind --tool=callgrind).\n");
}

int run(int argc, char** argv) {
    Options opt;
    std::string child_image;
    int child_level = 0;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--llvmpipe-child") {
            child_level = std::stoi(next());
            child_image = next();
        } else if (a == "--frames") {
            opt.min_frames = opt.profile_frames = std::max(1, std::stoi(next()));
        } else if (a == "--seconds") {
            opt.min_seconds = std::stod(next());
        } else if (a == "--sizes") {
            opt.sizes.clear();
            std::string list = next() + ",";
            for (size_t p = 0, q; (q = list.find(',', p)) != std::string::npos; p = q + 1) {
                const std::string name = list.substr(p, q - p);
                bool found = false;
                for (const BenchSize& s : kSizes)
                    if (name == s.name) opt.sizes.push_back(s), found = true;
                if (!found) throw std::runtime_error("unknown size " + name + " (5k, 100k, 1M)");
            }
        } else if (a == "--luz-only") {
            opt.llvmpipe = false;
        } else if (a == "--llvmpipe-only") {
            opt.luz = false;
        } else if (a == "--idle-wait") {
            opt.idle_wait = std::stod(next());
        } else if (a == "--no-breakdown") {
            opt.breakdown = false;
        } else if (a == "--float-target") {
            opt.float_target = true;
        } else if (a == "--save") {
            opt.save_dir = next();
        } else if (a == "--profile") {
            opt.profile_level = std::stoi(next());
        } else if (a == "--threads") {
            opt.profile_threads = std::stoi(next());
        } else if (a == "--help" || a == "-h") {
            print_usage();
            return 0;
        } else {
            print_usage();
            return 2;
        }
    }
    if (child_level > 0) return llvmpipe_child(child_level, child_image, opt);

    if (opt.profile_level > 0) {  // a few luz frames and nothing else
        const TorusScene torus = torus_scene(opt.profile_level);
        const ZbufferGeometry g = prepare_zbuffer(torus.scene, torus.desc);
        RenderControl control;
        control.threads = opt.profile_threads;
        Image out;
        for (int f = 0; f < opt.profile_frames; ++f) {
            RenderStats stats;
            render_zbuffer(torus.scene, torus.desc, g, control, out, stats);
        }
        std::printf("profiled %d frames of %zu triangles\n", opt.profile_frames,
                    g.mesh.triangle_count());
        return 0;
    }

    std::printf("zbuffer vs llvmpipe: torus, %dx%d, orthographic, phong, 1 light, culling off\n",
                kWidth, kHeight);
    std::printf(
        "median of >= %d frames and >= %.1f s of frames per configuration, configurations\n"
        "measured in alternating batches\n\n",
        opt.min_frames, opt.min_seconds);

    struct Row {
        BenchSize size;
        size_t triangles = 0;
        Timing luz[2], gl[2];
        Agreement agreement;
        Breakdown breakdown;
    };
    std::vector<Row> rows;
    std::string renderer;
    for (const BenchSize& size : opt.sizes) {
        Row row;
        row.size = size;
        const TorusScene torus = torus_scene(size.level);
        const ZbufferGeometry g = prepare_zbuffer(torus.scene, torus.desc);
        row.triangles = g.mesh.triangle_count();
        const uint64_t hash = mesh_hash(g.mesh);
        std::fprintf(stderr, "[%s] level %d: %zu triangles, %zu vertices, mesh hash %016llx\n",
                     size.name, size.level, row.triangles, g.mesh.positions.size(),
                     static_cast<unsigned long long>(hash));
        if (opt.idle_wait > 0) wait_for_idle(opt.idle_wait);

        // The configurations, measured side by side: llvmpipe 1t, 2t (children), luz 1t, 2t.
        std::vector<std::unique_ptr<LlvmpipeChild>> children;
        std::vector<std::function<Batch(int)>> configs;
        Image image;
        if (opt.llvmpipe) {
            for (int t = 1; t <= 2; ++t) {
                children.push_back(
                    std::make_unique<LlvmpipeChild>(size.level, t, opt.float_target));
                LlvmpipeChild& child = *children.back();
                if (child.hash != hash) throw std::runtime_error("llvmpipe child saw another mesh");
                renderer = child.renderer + ", OpenGL " + child.version;
                std::fprintf(stderr, "[%s] llvmpipe child, LP_NUM_THREADS=%d: %d threads in all\n",
                             size.name, t, child.threads_in_process);
                configs.push_back([&child](int k) { return child.frames(k); });
            }
        }
        if (opt.luz) {
            for (int t = 1; t <= 2; ++t)
                configs.push_back([&, t](int k) {
                    return run_batch(luz_frame(torus.scene, torus.desc, g, t, image), k);
                });
        }
        const std::vector<Timing> timings = side_by_side(configs, opt);
        size_t next = 0;
        if (opt.llvmpipe) {
            for (int t = 0; t < 2; ++t) {
                row.gl[t] = timings[next++];
                report(size.name, "llvmpipe", t + 1, row.gl[t]);
            }
        }
        if (opt.luz) {
            for (int t = 0; t < 2; ++t) {
                row.luz[t] = timings[next++];
                report(size.name, "luz", t + 1, row.luz[t]);
            }
        }
        std::vector<uint8_t> gl_image;
        if (opt.llvmpipe) {
            gl_image = children[1]->finish();  // 2 threads
            children[0]->finish();
        }
        if (opt.luz && opt.llvmpipe) row.agreement = compare(image, gl_image, 3);
        if (!opt.save_dir.empty()) {
            if (opt.luz) write_image(opt.save_dir + "/luz_" + size.name + ".png", image);
            if (opt.llvmpipe)
                write_image(opt.save_dir + "/llvmpipe_" + size.name + ".png", to_image(gl_image));
        }
        if (opt.luz && opt.breakdown) row.breakdown = luz_breakdown(size.level, opt);
        rows.push_back(row);
    }

    if (!renderer.empty()) std::printf("llvmpipe: %s\n\n", renderer.c_str());
    std::printf("%-5s %9s %10s %10s %15s %15s %9s\n", "size", "triangles", "luz_1t_ms", "luz_2t_ms",
                "llvmpipe_1t_ms", "llvmpipe_2t_ms", "ratio_2t");
    for (const Row& r : rows) {
        const double ratio = r.luz[1].median_ms > 0 ? r.gl[1].median_ms / r.luz[1].median_ms : 0;
        std::printf("%-5s %9zu %10.2f %10.2f %15.2f %15.2f %9.2f\n", r.size.name, r.triangles,
                    r.luz[0].median_ms, r.luz[1].median_ms, r.gl[0].median_ms, r.gl[1].median_ms,
                    ratio);
    }
    std::printf("(ratio_2t = llvmpipe_2t_ms / luz_2t_ms: > 1 means luz is faster)\n\n");

    auto fps = [](const Timing& t) { return t.median_ms > 0 ? 1000.0 / t.median_ms : 0.0; };
    std::printf("%-5s %10s %10s %15s %15s\n", "size", "luz_1t_fps", "luz_2t_fps", "llvmpipe_1t_fps",
                "llvmpipe_2t_fps");
    for (const Row& r : rows)
        std::printf("%-5s %10.1f %10.1f %15.1f %15.1f\n", r.size.name, fps(r.luz[0]), fps(r.luz[1]),
                    fps(r.gl[0]), fps(r.gl[1]));

    // CPU time per frame over all threads: cpu/wall is how many cores a renderer kept busy;
    // `others` is what other processes used meanwhile (> 0.2 cores: the wall times suffer).
    std::printf("\n%-5s %10s %10s %15s %15s %13s\n", "size", "luz_1t_cpu", "luz_2t_cpu",
                "llvmpipe_1t_cpu", "llvmpipe_2t_cpu", "others_cores");
    for (const Row& r : rows) {
        double others = 0;
        for (const Timing& t : {r.luz[0], r.luz[1], r.gl[0], r.gl[1]})
            others = std::max(others, t.others);
        std::printf("%-5s %10.2f %10.2f %15.2f %15.2f %13.2f\n", r.size.name, r.luz[0].cpu_ms,
                    r.luz[1].cpu_ms, r.gl[0].cpu_ms, r.gl[1].cpu_ms, others);
    }
    std::printf(
        "(CPU ms per frame, all threads of the renderer; others_cores: the most that other\n"
        " processes used during any of the four runs)\n");
    if (opt.luz && opt.llvmpipe) {
        std::printf("\nimage agreement (luz vs llvmpipe 2t, 8-bit): pixels within 3/255\n");
        for (const Row& r : rows)
            std::printf("%-5s %6.2f %%  (max difference %d/255)\n", r.size.name, r.agreement.within,
                        r.agreement.max_diff);
    }
    if (opt.luz && opt.breakdown) {
        std::printf("\nluz frame time by variant of the same mesh, 1 thread, median ms:\n");
        std::printf("%-5s %8s %10s %8s %8s %8s\n", "size", "behind", "offscreen", "tiny", "unlit",
                    "full");
        for (const Row& r : rows) {
            const Breakdown& b = r.breakdown;
            std::printf("%-5s %8.2f %10.2f %8.2f %8.2f %8.2f\n", r.size.name, b.behind.median_ms,
                        b.offscreen.median_ms, b.tiny.median_ms, b.unlit.median_ms,
                        b.full.median_ms);
        }
        std::printf("\nso, ms per frame (differences of medians; noisy when small):\n");
        std::printf("%-5s %14s %10s %16s %12s %11s\n", "size", "fixed+project", "tri_setup",
                    "bin+tri_raster", "pixels", "light_loop");
        for (const Row& r : rows) {
            const Breakdown& b = r.breakdown;
            const double behind = b.behind.median_ms, offscreen = b.offscreen.median_ms,
                         tiny = b.tiny.median_ms, unlit = b.unlit.median_ms,
                         full = b.full.median_ms;
            std::printf("%-5s %14.2f %10.2f %16.2f %12.2f %11.2f\n", r.size.name, behind,
                        offscreen - behind, tiny - offscreen, full - tiny, full - unlit);
        }
        std::printf(
            "(fixed+project = behind: buffers, background fill, vertex projection, clip codes;\n"
            " tri_setup = offscreen - behind; bin+tri_raster = tiny - offscreen;\n"
            " pixels = full - tiny: per-pixel rasterization and shading;\n"
            " light_loop = full - unlit: the lit part of shade())\n");
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "zbuffer_vs_llvmpipe: %s\n", e.what());
        return 1;
    }
}
