// Ray tree → ImGui text and lines.
#include "app/viewer/ray_tree_view.h"

#include <cmath>

#include "luz/luz.h"

namespace luz {

namespace {

void text_rgb(const char* label, const Rgb& c) {
    ImGui::Text("%s (%.4f, %.4f, %.4f)", label, c.x, c.y, c.z);
}

const char* kind_label(RayKind k) {
    return k == RayKind::primary ? "primary" : k == RayKind::reflection ? "reflected" : "refracted";
}

void draw_node(const RayTree& tree, const SceneDesc& desc, int index) {
    const RayTreeNode& n = tree.nodes[index];
    ImGui::PushID(index);
    std::string title =
        std::string(kind_label(n.kind)) + " ray (depth " + std::to_string(n.depth) + "): ";
    if (n.hit == RayHit::background) title += "background";
    if (n.hit == RayHit::light) title += "lights." + std::to_string(n.light);
    if (n.hit == RayHit::object) title += object_label(desc, n.object);
    if (ImGui::TreeNodeEx("node", ImGuiTreeNodeFlags_DefaultOpen, "%s", title.c_str())) {
        if (n.parent >= 0) {
            ImGui::Text("weight %.4f = coefficient %.3f x A %.4f", n.coefficient * n.A,
                        n.coefficient, n.A);
            text_rgb("returned", n.returned);
            text_rgb("contribution", n.contribution);
        }
        if (std::isinf(n.t)) {
            ImGui::Text("t = inf (miss)");
        } else {
            ImGui::Text("t = %.4f", n.t);
        }
        if (n.hit == RayHit::object) {
            ImGui::Text("material %s%s", material_label(desc, n.material).c_str(),
                        n.flipped ? "  (normal flipped)" : "");
            text_rgb("ambient Ia*Ka", n.ambient);
            for (size_t j = 0; j < n.lights.size(); ++j) {
                const LightTerm& l = n.lights[j];
                ImGui::Text("light %zu: vis %.3f  d %.3f  cos th %.4f  cos a %.4f", j, l.visibility,
                            l.distance, l.cos_theta, l.cos_alpha);
                text_rgb("   diffuse ", l.diffuse);
                text_rgb("   specular", l.specular);
            }
            text_rgb("local", n.local);
            if (n.total_internal_reflection) ImGui::Text("total internal reflection");
        }
        if (n.reflection_child >= 0) draw_node(tree, desc, n.reflection_child);
        if (n.refraction_child >= 0) draw_node(tree, desc, n.refraction_child);
        if (n.hit == RayHit::object) {
            ImGui::Text("= local%s%s", n.reflection_child >= 0 ? " + reflected" : "",
                        n.refraction_child >= 0 ? " + refracted" : "");
        }
        text_rgb("colour", n.colour);
        ImGui::TreePop();
    }
    ImGui::PopID();
}

}  // namespace

void draw_ray_tree_panel(const RayTree& tree, const SceneDesc& desc, int x, int y,
                         const Rgb& pixel) {
    ImGui::Text("pixel (%d, %d)", x, y);
    text_rgb("rendered", pixel);
    if (tree.raycast_for_zbuffer) {
        ImGui::TextWrapped(
            "zbuffer pipeline: the tree is the primary hit traced as raycast (depth 0), the same "
            "picture up to tessellation.");
    }
    if (!tree.nodes.empty()) draw_node(tree, desc, 0);
}

void draw_ray_tree_overlay(ImDrawList* draw, const RayTree& tree, const SceneDesc& desc,
                           ImVec2 origin, float scale, int x, int y) {
    // World point → screen; false when it lies behind the camera plane (perspective).
    auto project = [&](const Vec3& p, ImVec2& out) {
        float px, py;
        if (!project_point(desc, p, px, py)) return false;
        out = ImVec2(origin.x + px * scale, origin.y + py * scale);
        return true;
    };
    const ImU32 colours[] = {IM_COL32(255, 230, 0, 255), IM_COL32(0, 230, 255, 255),
                             IM_COL32(255, 80, 255, 255)};
    for (const RayTreeNode& n : tree.nodes) {
        const float length = std::isinf(n.t) ? 1000.0f : n.t;
        ImVec2 a, b;
        const bool has_a =
            n.kind == RayKind::primary
                ? (a = ImVec2(origin.x + (x + 0.5f) * scale, origin.y + (y + 0.5f) * scale), true)
                : project(n.origin, a);
        if (has_a && project(n.origin + n.direction * length, b)) {
            draw->AddLine(a, b, colours[static_cast<int>(n.kind)], 2.0f);
        }
        if (n.hit != RayHit::object) continue;
        ImVec2 p, l;
        if (!project(n.P, p)) continue;
        draw->AddCircleFilled(p, 3.0f, colours[static_cast<int>(n.kind)]);
        for (size_t j = 0; j < n.lights.size() && j < desc.lights.size(); ++j) {
            if (n.lights[j].cos_theta <= 0) continue;
            if (!project(desc.lights[j].position, l)) continue;
            const ImU32 c = n.lights[j].visibility > 0 ? IM_COL32(80, 255, 80, 160)
                                                       : IM_COL32(255, 60, 60, 160);
            draw->AddLine(p, l, c, 1.0f);
        }
    }
}

}  // namespace luz
