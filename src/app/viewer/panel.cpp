// The side panel (Dear ImGui widgets over SceneDesc fields).
#include "app/viewer/panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <string>

namespace luz {

namespace {

/// An RGB constant in [0, 1] (Ka, Kd, Ks).
bool edit_unit_rgb(const char* label, Rgb& c) {
    return ImGui::ColorEdit3(label, &c.x, ImGuiColorEditFlags_Float);
}

/// An RGB value ≥ 0 that may exceed 1 (Ia, Il).
bool edit_intensity(const char* label, Rgb& c) {
    bool changed = ImGui::DragFloat3(label, &c.x, 0.01f, 0.0f, 1000.0f, "%.3f");
    c = Rgb{std::max(0.0f, c.x), std::max(0.0f, c.y), std::max(0.0f, c.z)};
    return changed;
}

template <class E>
bool edit_enum(const char* label, E& value, std::initializer_list<const char*> names) {
    int i = static_cast<int>(value);
    std::string items;
    for (const char* n : names) items += std::string(n) + '\0';
    items += '\0';
    if (!ImGui::Combo(label, &i, items.c_str())) return false;
    value = static_cast<E>(i);
    return true;
}

bool render_section(SceneDesc& d) {
    bool changed = false;
    RenderDesc& r = d.render;
    changed |= edit_enum("pipeline", r.pipeline, {"zbuffer", "raycast", "raytrace"});
    changed |= edit_enum("model", r.model, {"lambert", "phong"});
    changed |= ImGui::SliderInt("max depth", &r.max_depth, 0, 16);
    changed |= ImGui::Checkbox("tree attenuation", &r.tree_attenuation);
    changed |= ImGui::SliderInt("tessellation", &d.geometry.tessellation, 3, 512);
    changed |= edit_enum("accel", d.geometry.accel, {"bvh", "none"});
    AntialiasDesc& aa = r.antialias;
    changed |= edit_enum("antialias", aa.mode, {"none", "grid", "adaptive"});
    if (aa.mode == AaMode::grid) {
        int s = 1;
        while (s * s < aa.samples) ++s;
        if (ImGui::SliderInt("samples (s², s =)", &s, 1, 16)) {
            aa.samples = s * s;
            changed = true;
        }
        changed |= edit_enum("filter", aa.filter, {"box", "tent"});
        changed |= ImGui::Checkbox("jitter", &aa.jitter);
    } else if (aa.mode == AaMode::adaptive) {
        changed |= ImGui::SliderFloat("threshold", &aa.threshold, 0.0f, 1.0f, "%.3f");
        changed |= ImGui::SliderInt("max level", &aa.max_level, 0, 6);
    }
    return changed;
}

bool lighting_section(SceneDesc& d) {
    bool changed = false;
    changed |= edit_intensity("Ia (ambient)", d.ambient);
    if (ImGui::DragFloat("K (attenuation)", &d.attenuation_k, 0.01f, 1e-3f, 1000.0f, "%.3f")) {
        d.attenuation_k = std::max(1e-3f, d.attenuation_k);
        changed = true;
    }
    for (size_t j = 0; j < d.lights.size(); ++j) {
        ImGui::PushID(static_cast<int>(j));
        if (ImGui::TreeNode("light", "lights.%zu", j)) {
            Light& l = d.lights[j];
            changed |= edit_intensity("Il", l.intensity);
            changed |= ImGui::DragFloat3("position", &l.position.x, 0.05f);
            if (ImGui::DragFloat("radius", &l.radius, 0.01f, 0.0f, 100.0f)) {
                l.radius = std::max(0.0f, l.radius);
                changed = true;
            }
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
    return changed;
}

bool materials_section(SceneDesc& d) {
    bool changed = false;
    for (size_t i = 0; i < d.materials.size(); ++i) {
        Material& m = d.materials[i];
        ImGui::PushID(static_cast<int>(i));
        if (ImGui::TreeNode("material", "%s", m.name.empty() ? "(inline)" : m.name.c_str())) {
            changed |= edit_unit_rgb("Ka", m.ka);
            changed |= edit_unit_rgb("Kd", m.kd);
            changed |= edit_unit_rgb("Ks", m.ks);
            if (ImGui::SliderFloat("n", &m.n, 0.1f, 2000.0f, "%.2f",
                                   ImGuiSliderFlags_Logarithmic)) {
                m.n = std::max(1e-3f, m.n);
                changed = true;
            }
            changed |= ImGui::SliderFloat("reflection", &m.reflection, 0.0f, 1.0f);
            changed |= ImGui::SliderFloat("transparency", &m.transparency, 0.0f, 1.0f);
            changed |= ImGui::SliderFloat("ior", &m.ior, 1.0f, 3.0f);
            if (m.checker) {
                changed |= edit_unit_rgb("checker Ka", m.checker->ka);
                changed |= edit_unit_rgb("checker Kd", m.checker->kd);
            }
            ImGui::TreePop();
        }
        ImGui::PopID();
    }
    return changed;
}

bool camera_section(SceneDesc& d, PanelState& state) {
    bool changed = false;
    CameraDesc& c = d.camera;
    changed |= edit_enum("projection", c.projection, {"orthographic", "perspective"});
    changed |= ImGui::DragFloat3("position", &c.position.x, 0.05f);
    changed |= ImGui::DragFloat3("look at", &c.look_at.x, 0.05f);
    if (c.projection == Projection::orthographic) {
        changed |= ImGui::DragFloat("view height", &c.view_height, 0.05f, 1e-3f, 1e4f);
    } else {
        changed |= ImGui::SliderFloat("fov y", &c.fov_y, 1.0f, 170.0f);
    }
    if (ImGui::Button("reset camera (R)")) state.reset_camera = true;
    return changed;
}

}  // namespace

bool draw_scene_panel(SceneDesc& d, PanelState& state) {
    const RenderFrame& f = state.last;
    ImGui::Text("pass %d/%d  1/%d%s  %.1f ms", f.pass + 1, f.passes, f.divisor,
                f.antialiased ? " + AA" : "", f.seconds * 1e3);
    ImGui::Text("%.2f M %s/s   preview %.1f fps", f.seconds > 0 ? f.rays / f.seconds * 1e-6 : 0.0,
                d.render.pipeline == Pipeline::zbuffer ? "samples" : "rays", state.fps);
    bool changed = false;
    if (ImGui::CollapsingHeader("Render", ImGuiTreeNodeFlags_DefaultOpen))
        changed |= render_section(d);
    if (ImGui::CollapsingHeader("Lighting", ImGuiTreeNodeFlags_DefaultOpen))
        changed |= lighting_section(d);
    if (ImGui::CollapsingHeader("Materials", ImGuiTreeNodeFlags_DefaultOpen))
        changed |= materials_section(d);
    if (ImGui::CollapsingHeader("Camera")) changed |= camera_section(d, state);
    if (ImGui::CollapsingHeader("Save", ImGuiTreeNodeFlags_DefaultOpen)) {
        ImGui::InputText("image", &state.image_path);
        if (ImGui::Button("save image (S)")) state.save_image = true;
        ImGui::InputText("scene", &state.scene_path);
        if (ImGui::Button("save scene (J)")) state.save_scene = true;
    }
    if (!state.status.empty()) ImGui::TextWrapped("%s", state.status.c_str());
    return changed;
}

const char* viewer_help_text() {
    return "Mouse over the image:\n"
           "  left drag     orbit the camera about look_at\n"
           "  right drag    pan (also middle drag, or shift + left drag)\n"
           "  wheel         zoom\n"
           "  left click    inspect the pixel's ray tree\n"
           "Keys:\n"
           "  H, F1   this help          R   reset the camera\n"
           "  P       next pipeline      M   lambert / phong\n"
           "  A       next antialiasing  T   tree attenuation on/off\n"
           "  [ ]     max depth -/+      C   clear the inspected pixel\n"
           "  S       save image         J   save scene (JSON)\n"
           "  Esc, Q  quit";
}

}  // namespace luz
