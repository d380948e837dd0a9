// The viewer panel's sliders: each one's label and the scene key whose limits (slider_range())
// give its range. No GUI code, so that tests can check every range against the loader.
#pragma once

#include <string_view>

#include "luz/scene.h"
#include "luz/sliders.h"

namespace luz {

/// The sliders of panel.cpp, one entry each in kPanelSliders.
enum class PanelSlider {
    max_depth,
    min_weight,
    tessellation,
    samples,
    threshold,
    max_level,
    ambient,
    attenuation_k,
    light_intensity,
    light_radius,
    n,
    reflection,
    transparency,
    ior,
    view_height,
    fov_y,
};

/// A slider: its label and the key of the limits table it edits.
struct PanelSliderSpec {
    PanelSlider id;
    const char* label;
    std::string_view key;
};

/// Every slider of the panel, in PanelSlider order.
inline constexpr PanelSliderSpec kPanelSliders[] = {
    {PanelSlider::max_depth, "max depth", "render.max_depth"},
    {PanelSlider::min_weight, "min weight", "render.min_weight"},
    {PanelSlider::tessellation, "tessellation", "render.tessellation"},
    {PanelSlider::samples, "samples (s², s =)", "render.antialias.samples"},
    {PanelSlider::threshold, "threshold", "render.antialias.threshold"},
    {PanelSlider::max_level, "max level", "render.antialias.max_level"},
    {PanelSlider::ambient, "Ia (ambient)", "ambient"},
    {PanelSlider::attenuation_k, "K (attenuation)", "attenuation_k"},
    {PanelSlider::light_intensity, "Il", "lights.*.intensity"},
    {PanelSlider::light_radius, "radius", "lights.*.radius"},
    {PanelSlider::n, "n", "materials.*.n"},
    {PanelSlider::reflection, "reflection", "materials.*.reflection"},
    {PanelSlider::transparency, "transparency", "materials.*.transparency"},
    {PanelSlider::ior, "ior", "materials.*.ior"},
    {PanelSlider::view_height, "view height", "camera.view_height"},
    {PanelSlider::fov_y, "fov y", "camera.fov_y"},
};

/// The spec of slider `id`.
constexpr const PanelSliderSpec& panel_slider(PanelSlider id) {
    return kPanelSliders[static_cast<int>(id)];
}

/// The range slider `id` shows: the limits table's slider range for its key.
inline SliderRange panel_slider_range(PanelSlider id) { return slider_range(panel_slider(id).key); }

}  // namespace luz
