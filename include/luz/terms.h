// The per-term images of docs/SCENES.md#terms (AOVs) a render may fill: their kinds and names.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace luz {

/// The per-term images, in the order `--aov all` lists and writes them.
enum class AovKind : uint8_t {
    ambient,
    diffuse,
    specular,
    reflected,
    refracted,
    emitted,
    shadow,
    depth,
    normal,
    tests,
};
inline constexpr int kAovCount = 10;

/// The name --aov, Frame::aovs and file names use ("ambient" … "tests").
const char* aov_name(AovKind kind);

/// Whether the term is one value per pixel (depth, tests) rather than an RGB triple.
inline bool aov_is_scalar(AovKind kind) { return kind == AovKind::depth || kind == AovKind::tests; }

/// Every kind, in order.
std::vector<AovKind> all_aovs();

/// The kinds named by `text`: names separated by commas, or "all"; each once, in the order
/// given. Throws InputError "ORIGIN: unknown term "X"; valid: ambient, diffuse, …, all".
std::vector<AovKind> parse_aov_list(const std::string& text, const std::string& origin);

}  // namespace luz
