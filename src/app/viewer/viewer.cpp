// The viewer's window and main loop: SDL2 events, camera controls, the render worker's frames
// shown as a texture, the panel, the ray-tree inspector, saving, and the headless screenshot.
#include "app/viewer/viewer.h"

#include <SDL.h>
#include <SDL_opengl.h>
#include <imgui.h>
#include <imgui_impl_opengl2.h>
#include <imgui_impl_sdl.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>

#include "app/viewer/camera_controls.h"
#include "app/viewer/gl_texture.h"
#include "app/viewer/panel.h"
#include "app/viewer/panel_sliders.h"
#include "app/viewer/ray_tree_view.h"
#include "app/viewer/render_worker.h"
#include "app/viewer/screenshot.h"
#include "luz/inspect.h"
#include "luz/luz.h"
#include "luz/scene_text.h"

namespace luz {

namespace {

constexpr int kPanelWidth = 440;
constexpr double kScreenshotTimeout = 120;  // seconds

using Clock = std::chrono::steady_clock;

/// "X,Y" → pixel; throws InputError when malformed or outside the image.
void parse_click(const std::string& s, const SceneDesc& d, int& x, int& y) {
    char extra;
    if (std::sscanf(s.c_str(), "%d,%d%c", &x, &y, &extra) != 2) {
        throw InputError("--click " + s + ": expected X,Y (pixel column and row)");
    }
    if (x < 0 || y < 0 || x >= d.image.width || y >= d.image.height) {
        throw InputError("--click " + s + ": outside the " + std::to_string(d.image.width) + "x" +
                         std::to_string(d.image.height) + " image");
    }
}

/// The path with its extension replaced.
std::string with_extension(const std::string& path, const char* ext) {
    return std::filesystem::path(path).replace_extension(ext).string();
}

class Viewer {
  public:
    Viewer(const ViewOptions& o, SceneDesc desc)
        : options_(o),
          edit_(std::move(desc)),
          camera0_(desc_.camera),
          worker_(render_threads(o.threads)) {
        panel_.image_path = desc_.name + ".png";
        panel_.scene_path = desc_.name + "_edited.json";
        if (!o.click.empty()) {
            parse_click(o.click, desc_, sel_x_, sel_y_);
            selected_ = true;
        }
        if (!o.show.empty()) {
            const std::vector<AovKind> kinds = parse_aov_list(o.show, "--aov " + o.show);
            if (kinds.size() != 1) throw InputError("--aov " + o.show + ": name one term to show");
            panel_.show = {true, kinds.front()};
        }
    }

    int run();

  private:
    bool open_window();
    void close_window();
    /// Marks the scene edited: it goes to the worker once per frame (apply_edits).
    void submit() { dirty_ = true; }
    void apply_edits();  // the edited scene to the worker (and the inspected tree)
    void handle_event(const SDL_Event& e);
    void handle_key(SDL_Keycode key);
    void draw_frame();
    void save_image();
    void save_scene();
    bool image_rect(float& x0, float& y0, float& scale) const;

    ViewOptions options_;
    EditableScene edit_;  ///< the edited description and the Scene built from it
    SceneDesc& desc_ = edit_.desc();
    CameraDesc camera0_;
    RenderWorker worker_;
    SDL_Window* window_ = nullptr;
    SDL_GLContext gl_ = nullptr;
    int win_w_ = 0, win_h_ = 0;
    GlTexture texture_;
    PanelState panel_;
    uint64_t generation_ = 0;
    bool have_full_ = false, final_shown_ = false;
    Image full_;  ///< the newest full-resolution pass without antialiasing (pixel values)
    bool show_help_ = false;
    bool quit_ = false;
    // inspector
    bool selected_ = false;
    int sel_x_ = 0, sel_y_ = 0;
    RayTree tree_;
    // mouse drag on the image
    int drag_button_ = 0;
    int press_x_ = 0, press_y_ = 0, last_x_ = 0, last_y_ = 0;
    bool moved_ = false;
    bool dirty_ = false;
};

bool Viewer::open_window() {
    // Without a display SDL may fall back to an off-screen driver nobody sees: refuse instead.
    const char* display = std::getenv("DISPLAY");
    const char* wayland = std::getenv("WAYLAND_DISPLAY");
    if ((!display || !*display) && (!wayland || !*wayland) && !std::getenv("SDL_VIDEODRIVER")) {
        std::fprintf(stderr,
                     "luz view: cannot open a window: no display (DISPLAY is not set; for "
                     "headless use run it under xvfb-run)\n");
        return false;
    }
    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        std::fprintf(stderr, "luz view: cannot open a window: %s\n", SDL_GetError());
        return false;
    }
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 2);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 1);
    SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
    SDL_GL_SetAttribute(SDL_GL_RED_SIZE, 8);
    SDL_GL_SetAttribute(SDL_GL_GREEN_SIZE, 8);
    SDL_GL_SetAttribute(SDL_GL_BLUE_SIZE, 8);
    // The image at 1:1 beside the panel; smaller when the display is (then the image scales).
    win_w_ = desc_.image.width + kPanelWidth;
    win_h_ = std::max(desc_.image.height, 720);
    SDL_Rect bounds;
    if (options_.screenshot.empty() && SDL_GetDisplayUsableBounds(0, &bounds) == 0) {
        win_w_ = std::min(win_w_, bounds.w);
        win_h_ = std::min(win_h_, bounds.h);
    }
    window_ = SDL_CreateWindow(("luz view — " + desc_.source).c_str(), SDL_WINDOWPOS_CENTERED,
                               SDL_WINDOWPOS_CENTERED, win_w_, win_h_,
                               SDL_WINDOW_OPENGL | SDL_WINDOW_RESIZABLE | SDL_WINDOW_SHOWN);
    if (!window_) {
        std::fprintf(stderr, "luz view: cannot open a window: %s\n", SDL_GetError());
        SDL_Quit();
        return false;
    }
    gl_ = SDL_GL_CreateContext(window_);
    if (!gl_) {
        std::fprintf(stderr, "luz view: no OpenGL context: %s\n", SDL_GetError());
        SDL_DestroyWindow(window_);
        SDL_Quit();
        return false;
    }
    SDL_GL_MakeCurrent(window_, gl_);
    SDL_GL_SetSwapInterval(options_.screenshot.empty() ? 1 : 0);
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working folder
    ImGui::StyleColorsDark();
    ImGui_ImplSDL2_InitForOpenGL(window_, gl_);
    ImGui_ImplOpenGL2_Init();
    return true;
}

void Viewer::close_window() {
    ImGui_ImplOpenGL2_Shutdown();
    ImGui_ImplSDL2_Shutdown();
    ImGui::DestroyContext();
    SDL_GL_DeleteContext(gl_);
    SDL_DestroyWindow(window_);
    SDL_Quit();
}

void Viewer::apply_edits() {
    dirty_ = false;
    // Rebuilt only when the edit needs it (objects, tessellation, accel): light, material,
    // camera and render-setting edits reuse the scene, its geometry and its BVH.
    const Scene& scene = edit_.scene();
    generation_ = worker_.submit(scene, desc_, panel_.show);
    final_shown_ = false;
    have_full_ = false;
    if (selected_) tree_ = ray_tree(scene, desc_, sel_x_ + 0.5f, sel_y_ + 0.5f);
}

bool Viewer::image_rect(float& x0, float& y0, float& scale) const {
    const float avail_w = static_cast<float>(win_w_ - kPanelWidth);
    const float avail_h = static_cast<float>(win_h_);
    scale = std::min({1.0f, avail_w / desc_.image.width, avail_h / desc_.image.height});
    if (scale <= 0) return false;
    x0 = 0;
    y0 = 0;
    return true;
}

void Viewer::handle_key(SDL_Keycode key) {
    bool changed = true;
    RenderDesc& r = desc_.render;
    switch (key) {
        case SDLK_ESCAPE:
        case SDLK_q:
            quit_ = true;
            return;
        case SDLK_h:
        case SDLK_F1:
            show_help_ = !show_help_;
            return;
        case SDLK_r:
            desc_.camera = camera0_;
            break;
        case SDLK_p:
            r.pipeline = static_cast<Pipeline>((static_cast<int>(r.pipeline) + 1) % 3);
            break;
        case SDLK_m:
            r.model = r.model == Model::phong ? Model::lambert : Model::phong;
            break;
        case SDLK_a:
            r.antialias.mode = static_cast<AaMode>((static_cast<int>(r.antialias.mode) + 1) % 3);
            break;
        case SDLK_t:
            r.tree_attenuation = !r.tree_attenuation;
            break;
        case SDLK_v: {  // image → ambient → … → tests → image
            Showing& s = panel_.show;
            if (!s.term) {
                s = {true, AovKind::ambient};
            } else if (static_cast<int>(s.kind) + 1 < kAovCount) {
                s.kind = static_cast<AovKind>(static_cast<int>(s.kind) + 1);
            } else {
                s = {};
            }
            break;
        }
        case SDLK_LEFTBRACKET:
            r.max_depth = std::max(static_cast<int>(panel_slider_range(PanelSlider::max_depth).lo),
                                   r.max_depth - 1);
            break;
        case SDLK_RIGHTBRACKET:
            r.max_depth = std::min(static_cast<int>(panel_slider_range(PanelSlider::max_depth).hi),
                                   r.max_depth + 1);
            break;
        case SDLK_c:
            selected_ = false;
            return;
        case SDLK_s:
            save_image();
            return;
        case SDLK_j:
            save_scene();
            return;
        default:
            changed = false;
    }
    if (changed) submit();
}

void Viewer::handle_event(const SDL_Event& e) {
    ImGui_ImplSDL2_ProcessEvent(&e);
    const ImGuiIO& io = ImGui::GetIO();
    float x0, y0, scale;
    if (!image_rect(x0, y0, scale)) scale = 1, x0 = y0 = 0;
    switch (e.type) {
        case SDL_QUIT:
            quit_ = true;
            break;
        case SDL_WINDOWEVENT:
            if (e.window.event == SDL_WINDOWEVENT_SIZE_CHANGED) {
                win_w_ = e.window.data1;
                win_h_ = e.window.data2;
            }
            break;
        case SDL_KEYDOWN:
            if (!io.WantCaptureKeyboard) handle_key(e.key.keysym.sym);
            break;
        case SDL_MOUSEBUTTONDOWN: {
            const float ix = (e.button.x - x0) / scale, iy = (e.button.y - y0) / scale;
            if (io.WantCaptureMouse || ix < 0 || iy < 0 || ix >= desc_.image.width ||
                iy >= desc_.image.height)
                break;
            drag_button_ = e.button.button;
            if (drag_button_ == SDL_BUTTON_LEFT && (SDL_GetModState() & KMOD_SHIFT))
                drag_button_ = SDL_BUTTON_RIGHT;
            press_x_ = last_x_ = e.button.x;
            press_y_ = last_y_ = e.button.y;
            moved_ = false;
            break;
        }
        case SDL_MOUSEMOTION: {
            if (!drag_button_) break;
            const int dx = e.motion.x - last_x_, dy = e.motion.y - last_y_;
            last_x_ = e.motion.x;
            last_y_ = e.motion.y;
            if (std::abs(e.motion.x - press_x_) + std::abs(e.motion.y - press_y_) > 3)
                moved_ = true;
            if (!moved_) break;
            const float h = desc_.image.height * scale;
            if (drag_button_ == SDL_BUTTON_LEFT) {
                orbit_camera(desc_.camera, -0.4f * dx, 0.4f * dy);
            } else {
                pan_camera(desc_.camera, -dx / h, dy / h);
            }
            submit();
            break;
        }
        case SDL_MOUSEBUTTONUP:
            if (drag_button_ == SDL_BUTTON_LEFT && !moved_) {
                sel_x_ =
                    std::clamp(static_cast<int>((press_x_ - x0) / scale), 0, desc_.image.width - 1);
                sel_y_ = std::clamp(static_cast<int>((press_y_ - y0) / scale), 0,
                                    desc_.image.height - 1);
                selected_ = true;
                tree_ = ray_tree(edit_.scene(), desc_, sel_x_ + 0.5f, sel_y_ + 0.5f);
            }
            drag_button_ = 0;
            break;
        case SDL_MOUSEWHEEL:
            if (io.WantCaptureMouse || e.wheel.y == 0) break;
            zoom_camera(desc_.camera, std::pow(0.9f, static_cast<float>(e.wheel.y)));
            submit();
            break;
        default:
            break;
    }
}

void Viewer::save_image() {
    try {
        RenderOptions options;
        options.threads = options_.threads;
        write_frame(render(edit_.scene(), desc_, options), panel_.image_path, desc_.image.encoding);
        panel_.status = "wrote " + panel_.image_path;
    } catch (const std::exception& e) {
        panel_.status = std::string("cannot save the image: ") + e.what();
    }
}

void Viewer::save_scene() {
    try {
        write_scene(panel_.scene_path, desc_);
        panel_.status = "wrote " + panel_.scene_path;
    } catch (const std::exception& e) {
        panel_.status = std::string("cannot save the scene: ") + e.what();
    }
}

void Viewer::draw_frame() {
    ImGui_ImplOpenGL2_NewFrame();
    ImGui_ImplSDL2_NewFrame();
    ImGui::NewFrame();

    float x0, y0, scale;
    if (image_rect(x0, y0, scale) && texture_.id()) {
        ImDrawList* bg = ImGui::GetBackgroundDrawList();
        const ImVec2 a(x0, y0);
        const ImVec2 b(x0 + desc_.image.width * scale, y0 + desc_.image.height * scale);
        bg->AddImage(texture_.id(), a, b);
        if (selected_) {
            draw_ray_tree_overlay(bg, tree_, desc_, a, scale, sel_x_, sel_y_);
            bg->AddRect(ImVec2(x0 + sel_x_ * scale - 2, y0 + sel_y_ * scale - 2),
                        ImVec2(x0 + (sel_x_ + 1) * scale + 2, y0 + (sel_y_ + 1) * scale + 2),
                        IM_COL32(255, 255, 255, 255));
        }
    }

    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(win_w_ - kPanelWidth), 0));
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(kPanelWidth), static_cast<float>(win_h_)));
    ImGui::Begin("luz", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::Text("%s  (H: help)", desc_.source.c_str());
    if (draw_scene_panel(desc_, panel_)) submit();
    if (panel_.reset_camera) {
        desc_.camera = camera0_;
        submit();
    }
    if (panel_.save_image) save_image();
    if (panel_.save_scene) save_scene();
    panel_.save_image = panel_.save_scene = panel_.reset_camera = false;
    if (selected_ && ImGui::CollapsingHeader("Ray tree", ImGuiTreeNodeFlags_DefaultOpen)) {
        const Rgb pixel = have_full_ ? full_.at(sel_x_, sel_y_) : Rgb{0.0f};
        draw_ray_tree_panel(tree_, desc_, sel_x_, sel_y_, pixel);
    }
    ImGui::End();

    if (show_help_) {
        ImGui::SetNextWindowPos(ImVec2(20, 20));
        ImGui::Begin("help", &show_help_, ImGuiWindowFlags_AlwaysAutoResize);
        ImGui::TextUnformatted(viewer_help_text());
        ImGui::End();
    }

    ImGui::Render();
    glViewport(0, 0, win_w_, win_h_);
    glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
}

int Viewer::run() {
    if (!open_window()) return 1;
    apply_edits();
    const bool headless = !options_.screenshot.empty();
    const auto start = Clock::now();
    int frames_after_final = 0;
    int status = 0;
    while (!quit_) {
        SDL_Event e;
        while (SDL_PollEvent(&e)) handle_event(e);
        RenderFrame frame;
        if (worker_.take_frame(frame) && frame.generation == generation_) {
            texture_.upload(frame.image, desc_.image.encoding);
            if (frame.divisor == 1 && !frame.antialiased) {
                full_ = frame.image;
                have_full_ = true;
            }
            if (frame.first_seconds > 0) panel_.fps = 1 / frame.first_seconds;
            final_shown_ = frame.pass + 1 == frame.passes;
            frame.image = Image();
            panel_.last = std::move(frame);
        }
        draw_frame();
        if (dirty_) apply_edits();
        if (headless) {
            frames_after_final = final_shown_ ? frames_after_final + 1 : 0;
            // A few frames after the last pass so that ImGui has laid the panel out.
            if (frames_after_final >= 3) {
                if (selected_) {
                    const std::string json = with_extension(options_.screenshot, ".json");
                    write_files_together({{json, ray_tree_json(tree_, desc_, sel_x_, sel_y_,
                                                               full_.at(sel_x_, sel_y_))}});
                }
                write_screenshot(options_.screenshot, win_w_, win_h_);
                quit_ = true;
            } else if (std::chrono::duration<double>(Clock::now() - start).count() >
                       kScreenshotTimeout) {
                std::fprintf(stderr, "luz view: the render did not finish in %.0f s\n",
                             kScreenshotTimeout);
                status = 1;
                quit_ = true;
            }
        }
        SDL_GL_SwapWindow(window_);
        // Idle: wait for input; rendering: leave the cores to the render threads a little.
        if (!headless && worker_.done() && final_shown_) {
            SDL_WaitEventTimeout(nullptr, 30);
        } else if (!final_shown_) {
            SDL_WaitEventTimeout(nullptr, headless ? 5 : 2);
        }
    }
    close_window();
    return status;
}

}  // namespace

int run_viewer(const ViewOptions& o) {
    if (o.benchmark) return run_view_benchmark(o);
    std::vector<Override> overrides;
    for (const std::string& s : o.sets) overrides.push_back(parse_set(s));
    if (o.width > 0) overrides.push_back({"image.width", std::to_string(o.width), "--width"});
    if (o.height > 0) overrides.push_back({"image.height", std::to_string(o.height), "--height"});
    SceneDesc desc = load_scene(o.scene, overrides);
    for (const std::string& w : desc.warnings)
        std::fprintf(stderr, "luz: warning: %s\n", w.c_str());
    Viewer viewer(o, std::move(desc));
    return viewer.run();
}

}  // namespace luz
