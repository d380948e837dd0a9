// The side panel (Dear ImGui widgets over SceneDesc fields).
#include "app/viewer/panel.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "app/viewer/panel_sliders.h"

namespace luz {

namespace {

/// An integer slider over the range the limits table gives (panel_sliders.h).
bool slider_int(PanelSlider id, int& value) {
    const SliderRange r = panel_slider_range(id);
    return ImGui::SliderInt(panel_slider(id).label, &value, static_cast<int>(r.lo),
                            static_cast<int>(r.hi));
}

/// A float slider over the range the limits table gives.
bool slider_float(PanelSlider id, float& value, const char* format = "%.3f",
                  ImGuiSliderFlags flags = 0) {
    const SliderRange r = panel_slider_range(id);
    return ImGui::SliderFloat(panel_slider(id).label, &value, static_cast<float>(r.lo),
                              static_cast<float>(r.hi), format, flags);
}

/// `value` kept at or above the slider's low end and, for a key bounded above, at or below its
/// high end (a typed-in value may leave the slider's range; the loader's limit still holds).
float clamp_to_limit(PanelSlider id, float value) {
    const SliderRange r = panel_slider_range(id);
    value = std::max(static_cast<float>(r.lo), value);
    return r.capped ? std::min(static_cast<float>(r.hi), value) : value;
}

/// A float dragged within the range the limits table gives.
bool drag_float(PanelSlider id, float& value, float speed) {
    const SliderRange r = panel_slider_range(id);
    const float lo = static_cast<float>(r.lo), hi = static_cast<float>(r.hi);
    if (!ImGui::DragFloat(panel_slider(id).label, &value, speed, lo, hi, "%.3f")) return false;
    value = clamp_to_limit(id, value);
    return true;
}

/// An RGB constant in [0, 1] (Ka, Kd, Ks).
bool edit_unit_rgb(const char* label, Rgb& c) {
    return ImGui::ColorEdit3(label, &c.x, ImGuiColorEditFlags_Float);
}

/// An RGB value ≥ 0 that may exceed 1 (Ia, Il).
bool edit_intensity(PanelSlider id, Rgb& c) {
    const SliderRange r = panel_slider_range(id);
    const float lo = static_cast<float>(r.lo), hi = static_cast<float>(r.hi);
    bool changed = ImGui::DragFloat3(panel_slider(id).label, &c.x, 0.01f, lo, hi, "%.3f");
    c = Rgb{clamp_to_limit(id, c.x), clamp_to_limit(id, c.y), clamp_to_limit(id, c.z)};
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
    changed |= slider_int(PanelSlider::max_depth, r.max_depth);
    changed |= slider_float(PanelSlider::min_weight, r.min_weight);
    changed |= ImGui::Checkbox("tree attenuation", &r.tree_attenuation);
    changed |= slider_int(PanelSlider::tessellation, d.geometry.tessellation);
    changed |= edit_enum("accel", d.geometry.accel, {"bvh", "none"});
    AntialiasDesc& aa = r.antialias;
    changed |= edit_enum("antialias", aa.mode, {"none", "grid", "adaptive"});
    if (aa.mode == AaMode::grid) {
        // The slider edits s; the table's range is that of s² (perfect squares).
        const SliderRange range = panel_slider_range(PanelSlider::samples);
        int s = 1;
        while (s * s < aa.samples) ++s;
        const int s_lo = static_cast<int>(std::lround(std::sqrt(range.lo)));
        const int s_hi = static_cast<int>(std::lround(std::sqrt(range.hi)));
        if (ImGui::SliderInt(panel_slider(PanelSlider::samples).label, &s, s_lo, s_hi)) {
            aa.samples = s * s;
            changed = true;
        }
        changed |= edit_enum("filter", aa.filter, {"box", "tent"});
        changed |= ImGui::Checkbox("jitter", &aa.jitter);
    } else if (aa.mode == AaMode::adaptive) {
        changed |= slider_float(PanelSlider::threshold, aa.threshold);
        changed |= slider_int(PanelSlider::max_level, aa.max_level);
    }
    return changed;
}

bool lighting_section(SceneDesc& d) {
    bool changed = false;
    changed |= edit_intensity(PanelSlider::ambient, d.ambient);
    changed |= drag_float(PanelSlider::attenuation_k, d.attenuation_k, 0.01f);
    // phong's distance law (docs/SCENES.md#models), in Attenuation's order
    changed |= edit_enum("attenuation", d.attenuation, {"none", "linear", "inverse_square"});
    for (size_t j = 0; j < d.lights.size(); ++j) {
        ImGui::PushID(static_cast<int>(j));
        if (ImGui::TreeNode("light", "lights.%zu", j)) {
            Light& l = d.lights[j];
            changed |= edit_intensity(PanelSlider::light_intensity, l.intensity);
            changed |= ImGui::DragFloat3("position", &l.position.x, 0.05f);
            changed |= drag_float(PanelSlider::light_radius, l.radius, 0.01f);
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
            if (slider_float(PanelSlider::n, m.n, "%.2f", ImGuiSliderFlags_Logarithmic)) {
                m.n = clamp_to_limit(PanelSlider::n, m.n);
                changed = true;
            }
            changed |= slider_float(PanelSlider::reflection, m.reflection);
            changed |= slider_float(PanelSlider::transparency, m.transparency);
            changed |= slider_float(PanelSlider::ior, m.ior);
            // w(i, λ) of the specular term (docs/SCENES.md#reflectance), in Reflectance's order
            changed |= edit_enum("reflectance", m.reflectance, {"constant", "schlick"});
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
        changed |= drag_float(PanelSlider::view_height, c.view_height, 0.05f);
    } else {
        changed |= slider_float(PanelSlider::fov_y, c.fov_y);
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
    // What the window shows: the image, or one of the terms that add up to it
    // (docs/SCENES.md#terms).
    {
        int i = state.show.term ? 1 + static_cast<int>(state.show.kind) : 0;
        std::string items = std::string("image") + '\0';
        for (AovKind k : all_aovs()) items += std::string(aov_name(k)) + '\0';
        items += '\0';
        if (ImGui::Combo("show (V)", &i, items.c_str())) {
            state.show = i == 0 ? Showing{} : Showing{true, static_cast<AovKind>(i - 1)};
            changed = true;
        }
    }
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
           "  V       show the next term (image, ambient, ... tests)\n"
           "  A       next antialiasing  T   tree attenuation on/off\n"
           "  [ ]     max depth -/+      C   clear the inspected pixel\n"
           "  S       save image         J   save scene (JSON)\n"
           "  Esc, Q  quit";
}

}  // namespace luz
