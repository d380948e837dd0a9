// The material presets (docs/SCENES.md#scene-files), tuned for `phong` with Il/(d+K) ≈ 1: the
// lecture's eight, diffuse surfaces (cortiça, gesso, …) versus specular ones (polished metal, still
// water, …), then three metals whose w(i, λ) is Schlick's curve (docs/SCENES.md#reflectance) from a
// measured Ks.
//
// The metals' Ks is their reflectance at normal incidence F(0°), linear RGB, from Table 1 of
// Naty Hoffman, "Background: Physically-Based Shading", SIGGRAPH 2010 course "Physically-Based
// Shading Models in Film and Game Production" (the table is from Real-Time Rendering, 3rd
// edition, Akenine-Möller, Haines and Hoffman, 2008): gold (1.00, 0.71, 0.29), silver
// (0.95, 0.93, 0.88), copper (0.95, 0.64, 0.54).
#include "scene/presets.h"

#include <array>

namespace luz {
namespace {

// The polished metals' shared constants (make_metal).
constexpr float kMetalKdScale = 0.5f;     // Kd = 0.5·F0
constexpr float kMetalN = 150.0f;         // a tight highlight
constexpr float kMetalReflection = 0.5f;  // a mirror, less than metal_polido's 0.7 (untinted)

/// A preset material: Ka is a dim version of Kd (ka_scale·Kd), the rest as given.
Material make(std::string_view name, Rgb kd, float ka_scale, float ks, float n,
              float reflection = 0.0f, float transparency = 0.0f, float ior = 1.0f) {
    Material m;
    m.name = std::string(name);
    m.kd = kd;
    m.ka = kd * ka_scale;
    m.ks = Rgb(ks);
    m.n = n;
    m.reflection = reflection;
    m.transparency = transparency;
    m.ior = ior;
    return m;
}

/// A polished metal (docs/SCENES.md#reflectance): Ks = F0, its measured reflectance at normal
/// incidence, with `reflectance: schlick`; Kd a dim F0 (metals have no diffuse body colour, but the
/// classic model has no coloured environment either: a little Kd gives the metal its tint away from
/// the highlight), Ka = 0.2·Kd, a tight highlight and a mirror.
Material make_metal(std::string_view name, Rgb F0) {
    Material m = make(name, F0 * kMetalKdScale, 0.2f, 0.0f, kMetalN, kMetalReflection);
    m.ks = F0;
    m.reflectance = Reflectance::schlick;
    return m;
}

const std::array<Preset, 11>& table() {
    static const std::array<Preset, 11> presets_ = {{
        {"gesso", "plaster", "matte near-white plaster: all diffuse, no highlight",
         make("gesso", {0.80f, 0.79f, 0.76f}, 0.15f, 0.0f, 2.0f)},
        {"madeira", "wood", "warm brown wood: diffuse with a faint broad sheen",
         make("madeira", {0.55f, 0.34f, 0.17f}, 0.15f, 0.15f, 10.0f)},
        {"concreto", "concrete", "mid-grey concrete: rough, almost no highlight",
         make("concreto", {0.50f, 0.50f, 0.48f}, 0.15f, 0.05f, 4.0f)},
        {"cortica", "cork", "tan cork: soft, diffuse, no visible highlight",
         make("cortica", {0.62f, 0.46f, 0.30f}, 0.15f, 0.02f, 3.0f)},
        {"plastico", "plastic", "saturated red plastic: coloured diffuse, sharp white highlight",
         make("plastico", {0.75f, 0.08f, 0.06f}, 0.15f, 0.6f, 40.0f)},
        {"metal_polido", "polished_metal", "polished metal: dark diffuse, tight highlight, mirror",
         make("metal_polido", {0.15f, 0.15f, 0.16f}, 0.2f, 0.9f, 200.0f, 0.7f)},
        {"agua", "still_water",
         "still water: faint blue tint, very sharp highlight, transparent (ior 1.33)",
         make("agua", {0.03f, 0.08f, 0.12f}, 0.2f, 0.8f, 300.0f, 0.2f, 0.8f, 1.33f)},
        {"vidro", "glass", "clear glass: almost no diffuse, sharp highlight, refracts (ior 1.5)",
         make("vidro", {0.02f, 0.02f, 0.02f}, 0.2f, 0.9f, 500.0f, 0.1f, 0.9f, 1.5f)},
        {"ouro", "gold", "polished gold: Schlick's curve from Ks = F0 (1, 0.71, 0.29), mirror",
         make_metal("ouro", {1.00f, 0.71f, 0.29f})},
        {"prata", "silver",
         "polished silver: Schlick's curve from Ks = F0 (0.95, 0.93, 0.88), mirror",
         make_metal("prata", {0.95f, 0.93f, 0.88f})},
        {"cobre", "copper",
         "polished copper: Schlick's curve from Ks = F0 (0.95, 0.64, 0.54), mirror",
         make_metal("cobre", {0.95f, 0.64f, 0.54f})},
    }};
    return presets_;
}

}  // namespace

std::span<const Preset> presets() { return table(); }

const Preset* find_preset(std::string_view name) {
    for (const Preset& p : table()) {
        if (p.name == name || p.alias == name) return &p;
    }
    return nullptr;
}

}  // namespace luz
