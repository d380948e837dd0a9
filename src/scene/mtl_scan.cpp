// MTL reading and mapping (see mtl_scan.h).
#include "scene/mtl_scan.h"

#include <charconv>
#include <cstdio>

#include "scene/message_text.h"
#include "scene/obj_text.h"

namespace luz {
namespace {

using namespace obj_text;

/// Clamps a constant to [0, 1] (docs/SCENES.md#scene-files), with a warning when it had to.
float unit(float x, const char* key, const std::string& file, size_t line,
           std::vector<std::string>& warnings) {
    if (x >= 0 && x <= 1) return x;
    const float c = x < 0 ? 0.0f : 1.0f;
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s %g is outside [0, 1]; %g is used", key, double(x),
                  double(c));
    warnings.push_back(at(file, line) + buf);
    return c;
}

}  // namespace

std::vector<Material> scan_mtl(std::string_view text, const std::string& file,
                               const std::string& prefix, std::vector<std::string>& warnings) {
    std::vector<Material> out;
    Material m;
    std::string name;
    int illum = -1;
    bool has_d = false;
    const auto flush = [&] {
        // illum 3–7: ray-traced reflection, weighted by Ks in the MTL model
        m.reflection = (illum >= 3 && illum <= 7) ? (m.ks.x + m.ks.y + m.ks.z) / 3.0f : 0.0f;
        m.name = prefix + name;
        out.push_back(m);
    };
    Lines lines(text);
    std::string_view line;
    float v[3];
    while (lines.next(line)) {
        const size_t n = lines.number();
        Tokens tokens(line);
        std::string_view key;
        if (!tokens.next(key) || key[0] == '#') continue;
        if (key == "newmtl") {
            if (!name.empty()) flush();
            m = Material{};
            illum = -1;
            has_d = false;
            // as LoadMtl: the rest of the line, trailing blanks removed
            std::string_view rest = tokens.rest();
            while (!rest.empty() && is_blank(rest.back())) rest.remove_suffix(1);
            // tinyobjloader skips an unnamed `newmtl` and cuts a name at a NUL: refuse both,
            // so that both readers list the same materials (found by fuzzing)
            if (rest.empty()) fail_at(file, n, "newmtl: expected a material name");
            for (const char c : rest) {
                if (static_cast<unsigned char>(c) < 0x20 && c != '\t') {
                    fail_at(file, n, "newmtl: control character in the material name");
                }
            }
            name = std::string(rest);
        } else if (key == "Ka" || key == "Kd" || key == "Ks") {
            const std::string k(key);
            // "Kd r g b", or "Kd r" meaning r r r
            const int count = read_numbers(tokens, v, 1, 3, file, n, k);
            if (count == 2) fail_at(file, n, k + ": expected 1 or 3 numbers, got 2");
            if (count == 1) v[1] = v[2] = v[0];
            Rgb& target = key == "Ka" ? m.ka : (key == "Kd" ? m.kd : m.ks);
            target = Rgb{unit(v[0], k.c_str(), file, n, warnings),
                         unit(v[1], k.c_str(), file, n, warnings),
                         unit(v[2], k.c_str(), file, n, warnings)};
        } else if (key == "Ns") {
            read_numbers(tokens, v, 1, 1, file, n, "Ns");
            m.n = v[0] > 0 ? v[0] : 1.0f;  // docs/SCENES.md: n > 0
        } else if (key == "Ni") {
            read_numbers(tokens, v, 1, 1, file, n, "Ni");
            m.ior = v[0] >= 1 ? v[0] : 1.0f;  // docs/SCENES.md: ior ≥ 1
        } else if (key == "d") {
            std::string_view first = tokens.rest();
            if (first.substr(0, 5) == "-halo") {
                std::string_view skip;
                tokens.next(skip);
            }
            read_numbers(tokens, v, 1, 1, file, n, "d");
            m.transparency = 1.0f - unit(v[0], "d", file, n, warnings);
            has_d = true;
        } else if (key == "Tr") {
            read_numbers(tokens, v, 1, 1, file, n, "Tr");
            if (!has_d) m.transparency = unit(v[0], "Tr", file, n, warnings);  // d wins
        } else if (key == "illum") {
            std::string_view token;
            tokens.next(token);
            const auto [ptr, ec] =
                std::from_chars(token.data(), token.data() + token.size(), illum);
            std::string_view extra;
            if (token.empty() || ec != std::errc() || ptr != token.data() + token.size() ||
                tokens.next(extra)) {
                fail_at(file, n, "illum: expected an integer, got " + quote(line));
            }
        }
    }
    flush();
    return out;
}

}  // namespace luz
