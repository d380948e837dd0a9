// The viewer's side panel: every constant of docs/SCENES.md#models and the render settings, edited
// live.
#pragma once

#include <string>

#include "app/viewer/render_worker.h"
#include "luz/luz.h"

namespace luz {

/// What the panel shows besides the scene, and what the user asked of it this frame.
struct PanelState {
    // shown
    RenderFrame last;    ///< the last pass shown (its image is not used)
    double fps = 0;      ///< 1 / the first (coarsest) pass's time: the preview's rate
    std::string status;  ///< last message (saved files, errors)
    // edited
    std::string image_path;  ///< where "Save image" writes (.png, .exr, …)
    std::string scene_path;  ///< where "Save scene" writes (.json)
    Showing show;            ///< the image, or one of its terms (docs/SCENES.md#terms)
    // requests (set for one frame)
    bool save_image = false, save_scene = false, reset_camera = false;
};

/// Draws the panel's scene sections into the current ImGui window; true when `desc` changed.
bool draw_scene_panel(SceneDesc& desc, PanelState& state);

/// The keys, mouse actions and what they do, for the help overlay and docs/VIEWER.md.
const char* viewer_help_text();

}  // namespace luz
