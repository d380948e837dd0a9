#!/usr/bin/env python3
# Where a luz render's instructions go (callgrind, one thread), grouped: BVH traversal, primitive
# tests by shape kind, shading, shadow rays, recursion, sampling/output, scene load + BVH build.
# usage: spd_profile.py LUZ SIZE SCENE.nff… [--keep DIR]   (prints one markdown table per scene)
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

# (group, pattern on the demangled function name), first match wins; inlined code counts where
# it was inlined (e.g. the sphere and triangle lanes of a BVH leaf in the traversal that runs it).
GROUPS = [
    ("shadow rays: BVH traversal", r"any_leaves<.*transmittance"),
    ("shadow rays: primitive tests", r"cross_block|cross_shape|count_by_repeated_hits|count_crossings"),
    ("shadow rays: segments, lights", r"transmittance|Crossings|shadow|light_visib|SegmentLanes"),
    ("BVH traversal (nearest hit)", r"nearest_leaves|nearest_packet|nearest_hit|nearest_hits|WideBvh"),
    ("primitive tests: cylinder", r"cylinder::|<luz::shapes::cylinder"),
    ("primitive tests: cone", r"cone::|<luz::shapes::cone"),
    ("primitive tests: sphere", r"sphere::|ray_sphere|SphereLanes|sphere_lanes"),
    ("primitive tests: triangle", r"triangle|Watertight|watertight"),
    ("primitive tests: leaf lanes (axis pre-test), dispatch", r"offer_block|offer_shape|shapes::|intersect"),
    ("scene load + BVH build", r"loader::|nlohmann|json|read_nff|obj_text|Builder::|Collapser|"
     r"build_bvh|Bvh::build|build_scene|make_shape|::place|SceneDesc|ObjectDesc|check_shape|"
     r"estimate_memory|MaterialTable|from_chars|strto|scanf|Mesh::face_normal|luz::bounds|"
     r"luz::build|Animation|Scene::State|CLI::|_dl_|dl-|do_lookup|check_match"),
    ("shading", r"shade|surface_at|phong|Phong|lambert|powf|pow|Mesh::shading_normal|material"),
    ("ray spawning, recursion", r"trace_trees|bounce|reflect|refract|recursion|spawn|Whitted"),
    ("sampling, image, output", r"sample|Sampler|adaptive|Png|png|libz|adler32|crc32|deflate|tile|"
     r"Tile|image|Image|write|pixel"),
    ("memory, strings (libc)", r"malloc|free|memcpy|memmove|memset|memcmp|memchr|strlen|strcmp|"
     r"operator new|operator delete|basic_string|_Hash|Hashtable|_Map_base|to_string|unlink_chunk|"
     r"alloc_perturb|string_view"),
]


def profile(luz, scene, size, out):
    subprocess.run(["valgrind", "--tool=callgrind", "--callgrind-out-file=" + out, luz, "render",
                    scene, "--width", str(size), "--height", str(size), "--threads", "1", "-q",
                    "-o", out + ".png"], check=True, capture_output=True)
    text = subprocess.run(["callgrind_annotate", "--inclusive=no", "--threshold=100", out],
                          check=True, capture_output=True, text=True).stdout
    total, funcs = 0, []
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+) \(\s*[\d.]+%\)\s+(.*)", line)
        if not m:
            continue
        ir = int(m.group(1).replace(",", ""))
        if "PROGRAM TOTALS" in m.group(2):
            total = ir
        else:
            funcs.append((ir, m.group(2)))
    return total, funcs


def group(funcs):
    sums = {g: 0 for g, _ in GROUPS}
    sums["other"] = 0
    pats = [(g, re.compile(p)) for g, p in GROUPS]
    for ir, name in funcs:
        sums[next((g for g, p in pats if p.search(name)), "other")] += ir
    return sums


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("luz")
    ap.add_argument("size", type=int)
    ap.add_argument("scenes", nargs="+")
    ap.add_argument("--keep", help="folder to keep the callgrind files in")
    a = ap.parse_args()
    work = a.keep or tempfile.mkdtemp(prefix="luz_spdprof.")
    os.makedirs(work, exist_ok=True)
    try:
        report(a, work)
    finally:
        if not a.keep:  # the callgrind files, unless asked to keep them
            shutil.rmtree(work, ignore_errors=True)


def report(a, work):
    for scene in a.scenes:
        name = os.path.splitext(os.path.basename(scene))[0]
        total, funcs = profile(a.luz, scene, a.size, os.path.join(work, f"{name}.{a.size}.cg"))
        fixed, _ = profile(a.luz, scene, 1, os.path.join(work, f"{name}.1.cg"))
        sums = group(funcs)
        print(f"\n**{name}** ({a.size}², whole process {total / 1e6:.0f} M instructions; the same "
              f"at 1×1, i.e. start-up, load, BVH build: {fixed / 1e6:.0f} M)\n")
        print("| group | M instructions | share |\n|---|---|---|")
        for g, ir in sorted(sums.items(), key=lambda kv: -kv[1]):
            if ir:
                print(f"| {g} | {ir / 1e6:.1f} | {100.0 * ir / total:.1f} % |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
