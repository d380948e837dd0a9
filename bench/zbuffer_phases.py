#!/usr/bin/env python3
# Splits a perf profile of `zbuffer_vs_llvmpipe --profile LEVEL` (perf record --call-graph dwarf,
# binary built with -g) into the zbuffer's phases: each sample goes to the innermost stack frame
# that lies in one of the given sources, classified by the function that line belongs to.
# Usage: zbuffer_phases.py PERF_DATA SRC/render/zbuffer.cpp,SRC/render/rasterizer.cpp,... [TOP_LEAVES]
import collections
import re
import subprocess
import sys

data, sources = sys.argv[1], sys.argv[2].split(',')
top_leaves = int(sys.argv[3]) if len(sys.argv) > 3 else 12

# Per source file (by base name): line ranges of its functions and of the frame's numbered
# steps (1, 2 in the rasterizer's constructor, 3 in render_zbuffer).
marks = {}  # base name -> [(first line, name)]
for source in sources:
    file_marks = marks.setdefault(source.rsplit('/', 1)[-1], [])
    for n, line in enumerate(open(source, encoding='utf-8'), 1):
        m = re.match(r'^(?:\[\[[\w:]+\]\]\s*)?[A-Za-z][\w:<>,\s\*&]*?\b(\w+)\((.*)$', line)
        if m and not line.startswith(('namespace', 'using', 'constexpr', 'struct', 'return')):
            file_marks.append((n, m.group(1)))
        m = re.match(r'^\s*// (\d)\. ', line)
        if m:
            file_marks.append((n, 'render_zbuffer_step' + m.group(1)))
    file_marks.sort()


def function_at(file, line):
    name = 'top'
    for first, f in marks[file]:
        if first > line:
            break
        name = f
    return name


PHASES = {
    'project': 'vertex projection',
    'render_zbuffer_step1': 'vertex projection',
    'plane_distance': 'triangle set-up: fetch, clip codes',
    'bin_chunk': 'triangle set-up: fetch, clip codes',
    'lerp': 'triangle set-up: clipping',
    'clip_polygon': 'triangle set-up: clipping',
    'near_depth': 'triangle set-up: fetch, clip codes',
    'setup': 'triangle set-up: setup() (fixed point via lround)',
    'bin': 'binning: tile lists (push_back, growth, page faults)',
    'render_zbuffer_step2': 'binning: tile lists (push_back, growth, page faults)',
    'rasterize_triangle': 'rasterization: edge set-up, pixel loop, depth test',
    'rasterize': 'rasterization: per-tile fragment clear, walk of the bins',
    'render_zbuffer_step3': 'rasterization: per-tile fragment clear, walk of the bins',
}

out = subprocess.run(['perf', 'script', '-i', data, '-F', 'ip,sym,srcline'],
                     capture_output=True, text=True, check=True).stdout
samples, cur, sym = [], [], None
for line in out.splitlines():
    if not line.strip():
        if cur:
            samples.append(cur)
        cur = []
        continue
    m = re.match(r'^\s+[0-9a-f]+\s+(.*)$', line)
    if m and line.startswith('\t'):
        sym = m.group(1)
        continue
    if sym is not None:
        cur.append((sym, line.strip()))
        sym = None
if cur:
    samples.append(cur)


NOT_A_FRAME = re.compile(r'prepare_zbuffer|tessellate|torus_scene|build_scene|make_shape|'
                        r'mesh_hash|_dl_|_exit|exit_handlers')


def phase(stack):
    # Stacks may be cut short (the tile loop keeps a 64 KiB fragment buffer on the stack, more
    # than perf copies), so a sample counts unless it is in set-up or process start and end.
    names = ' | '.join(s for s, _ in stack)
    srcs = ' | '.join(src for _, src in stack)
    in_bench = 'zbuffer_vs_llvmpipe.cpp' in srcs or 'zbuffer_bench_' in srcs  # or its parts
    if NOT_A_FRAME.search(names) or in_bench and 'render_zbuffer' not in names:
        return None  # prepare_zbuffer, start-up: not part of a frame
    for s, src in stack:
        m = re.match(r'(?:.*/)?([\w.]+):(\d+)', src)
        if not m or m.group(1) not in marks:
            continue
        f = function_at(m.group(1), int(m.group(2)))
        if f in ('shade_tile', 'shade_fragment'):
            if re.search(r'luz::shade<|powf', names):
                return 'shading: shade() (phong model, powf)'
            return 'shading: fetch, interpolate P and N, normalize, store pixel'
        return PHASES.get(f, 'frame overhead: ' + ('per-frame buffers' if f == 'top' else f))
    return 'thread pool (TBB)'


counts = collections.Counter()
leaves = collections.Counter()
for st in samples:
    p = phase(st)
    if p is None:
        continue
    counts[p] += 1
    leaves[re.sub(r'\+0x[0-9a-f]+$', '', st[0][0])[:90]] += 1
total = sum(counts.values())
print(f'{total} samples in frames ({len(samples)} in all)')
for k, v in counts.most_common():
    print(f'{100.0 * v / total:6.1f} %  {k}')
print('top functions (self, inlined code counted in its own function):')
for k, v in leaves.most_common(top_leaves):
    print(f'{100.0 * v / total:6.1f} %  {k}')
