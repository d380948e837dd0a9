// The `luz render` options: their declaration for CLI11 and their translation into Overrides.
#include "app/cli_options.h"

#include <CLI/CLI.hpp>

#include "luz/options.h"

namespace luz {

void add_render_options(CLI::App& cmd, RenderArgs& o) {
    cmd.add_option("SCENE", o.scene,
                   "scene file (JSON, or NFF: .nff), or demo:NAME (see `luz scenes`)")
        ->required();
    cmd.add_option("-o,--output", o.output,
                   "output image; the extension picks the format: .png .ppm .pfm .exr "
                   "(default: the scene's name + .png)")
        ->type_name("OUT");
    cmd.add_option("--pipeline", o.pipeline, "rendering pipeline (render.pipeline)")
        ->type_name("zbuffer|raycast|raytrace");
    cmd.add_option("--model", o.model, "illumination model (render.model)")
        ->type_name("lambert|phong");
    cmd.add_option("--width", o.width, "image width in pixels (image.width)")->type_name("INT");
    cmd.add_option("--height", o.height, "image height in pixels (image.height)")->type_name("INT");
    cmd.add_option("--max-depth", o.max_depth, "ray tree depth, raytrace (render.max_depth)")
        ->type_name("INT");
    cmd.add_option("--aa", o.aa, "antialiasing (render.antialias.mode)")
        ->type_name("none|grid|adaptive");
    cmd.add_option("--samples", o.samples,
                   "samples per pixel for grid antialiasing, a perfect square "
                   "(render.antialias.samples)")
        ->type_name("INT");
    cmd.add_option("--threshold", o.threshold,
                   "colour difference that splits a pixel, adaptive antialiasing "
                   "(render.antialias.threshold)")
        ->type_name("NUMBER");
    cmd.add_option("--threads", o.threads, "worker threads (default, or 0: all cores)")
        ->check(CLI::Range(0, 4096));
    cmd.add_option("--stats", o.stats_file, "write render statistics as JSON to FILE")
        ->type_name("FILE");
    cmd.add_option("--aa-mask", o.aa_mask_file,
                   "write an image of the pixels adaptive antialiasing refined, coloured by "
                   "depth (1 blue ... 6 red; others dim grey); extension as for -o")
        ->type_name("FILE");
    cmd.add_option("--aov", o.aovs,
                   "also write per-term images (ambient diffuse specular reflected refracted "
                   "emitted shadow depth normal tests, comma-separated, or all): X.NAME.EXT "
                   "beside -o X.EXT, or layers of X.exr")
        ->type_name("NAME[,NAME...]");
    cmd.add_option("--checkpoint", o.checkpoint,
                   "keep the finished tiles in FILE (every 10 s and when interrupted); run "
                   "again with the same scene, options and FILE to continue; removed once the "
                   "output is written")
        ->type_name("FILE");
    cmd.add_option("--region", o.region,
                   "render only the pixels X0 <= x < X1, Y0 <= y < Y1: an image X1-X0 by "
                   "Y1-Y0 whose pixels are those of the same rectangle of the whole render")
        ->type_name("X0,Y0,X1,Y1");
    cmd.add_option("--frames", o.frames,
                   "scene with an animation: render frames A to B-1 (or all) to X.0000.EXT, "
                   "X.0001.EXT ... beside -o X.EXT")
        ->type_name("A:B|all");
    cmd.add_flag("-q,--quiet", o.quiet, "print nothing on success, no progress bar");
    cmd.add_option("--set", o.sets,
                   "override any scene key by dotted path, e.g. materials.red.n=4 or "
                   "lights.0.intensity=[1,0.9,0.8]; repeatable")
        ->type_name("PATH=JSON")
        ->allow_extra_args(false);
    cmd.add_option("--max-memory", o.max_memory,
                   "refuse images that need more memory than this (e.g. 2G; default: half "
                   "of physical memory)")
        ->type_name("BYTES")
        ->transform(CLI::AsSizeValue(false))
        // transforms run last added first: this sees the text before AsSizeValue wraps "-1"
        ->transform(CLI::Validator(
            [](std::string& text) {
                const std::size_t first = text.find_first_not_of(" \t");
                if (first == std::string::npos || text[first] != '-') return std::string();
                return "must not be negative, got " + text;
            },
            "", ""));
    cmd.footer(
        "SCENE is a scene file (JSON, or NFF: .nff) or demo:NAME (see `luz scenes`). Options that "
        "name a scene key override it and are checked like it.\n"
        "Exit status: 0 success; 2 bad input (one line naming the file and the place); 1 any "
        "other failure; 130/143 interrupted by SIGINT/SIGTERM (nothing written).\n"
        "Environment: LUZ_CHECKPOINT_SECONDS, the --checkpoint interval (default 10); "
        "LUZ_MPI_TIMEOUT under mpirun.\n"
        "Every option, output and message: docs/CLI.md; every scene key: docs/SCENES.md.");
}

std::vector<Override> overrides_of(const RenderArgs& o) {
    std::vector<Override> out;
    for (const std::string& s : o.sets) out.push_back(parse_set(s));
    const std::vector<Override> options = option_overrides(
        {o.pipeline, o.model, o.width, o.height, o.max_depth, o.aa, o.samples, o.threshold});
    out.insert(out.end(), options.begin(), options.end());
    return out;
}

}  // namespace luz
