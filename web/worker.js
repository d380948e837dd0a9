// luz's render worker (docs/WEB.md): runs after Emscripten's luz_core.js (createLuz) in one Blob;
// loads scenes with the page's edits (--set paths), renders progressive passes band by band
// and yields between bands, so that a newer edit cancels the pass under way.
'use strict';
let core = null;
let generation = 0; // the newest job; a running job whose number is older stops
let job = null; // {source, sets, term}
const pending = [];

// A yield to the event loop without setTimeout's clamping: the page's messages get in.
const channel = new MessageChannel();
let resume = null;
channel.port1.onmessage = () => resume && resume();
const breathe = () => new Promise((r) => { resume = r; channel.port2.postMessage(0); });

function text() { return core.UTF8ToString(core._luz_text()); }

// The passes of an image, as the native viewer's plan_passes(): 1/8, 1/2, full, antialiased.
function plan(scene) {
  const w = scene.image.width, h = scene.image.height, smaller = Math.min(w, h);
  const passes = [];
  if (smaller >= 64) passes.push({ divisor: 8, aa: 0 });
  if (smaller >= 16) passes.push({ divisor: 2, aa: 0 });
  passes.push({ divisor: 1, aa: 0 });
  const aa = scene.render && scene.render.antialias;
  if (aa && aa.mode && aa.mode !== 'none') passes.push({ divisor: 1, aa: 1 });
  return passes;
}

function renderBand(pass, y0, y1, term) {
  const ptr = core._luz_render(pass.divisor, pass.aa, y0, y1, term);
  if (!ptr) return null;
  const w = core._luz_pass_width(), h = core._luz_pass_height();
  const rows = Math.min(y1, h) - y0;
  return { w, h, rgba: core.HEAPU8.slice(ptr, ptr + w * rows * 4) };
}

async function run(gen) {
  const t = job;
  const sets = t.sets.join('\n');
  if (!core.ccall('luz_load', 'number', ['string', 'string'], [t.source, sets])) {
    postMessage({ type: 'error', gen, message: text() });
    return;
  }
  const scene = JSON.parse(core.UTF8ToString(core._luz_scene_json()));
  postMessage({ type: 'scene', gen, scene });
  const passes = plan(scene);
  for (let p = 0; p < passes.length; ++p) {
    const pass = passes[p];
    const h = Math.max(1, Math.floor(scene.image.height / pass.divisor));
    const bandRows = Math.max(16, Math.ceil(h / 4));
    const start = performance.now();
    let rays = 0;
    for (let y0 = 0; y0 < h; y0 += bandRows) {
      await breathe();
      if (gen !== generation) return; // a newer edit: this pass is cancelled
      const band = renderBand(pass, y0, y0 + bandRows, t.term);
      if (!band) { postMessage({ type: 'error', gen, message: text() }); return; }
      rays += core._luz_band_rays();
      postMessage({ type: 'band', gen, pass: p, passes: passes.length, divisor: pass.divisor,
        width: band.w, height: band.h, y0, rgba: band.rgba.buffer }, [band.rgba.buffer]);
    }
    const ms = performance.now() - start;
    postMessage({ type: 'pass', gen, pass: p, passes: passes.length, ms, rays });
  }
  postMessage({ type: 'done', gen });
}

// Full passes of the loaded scene, back to back, in one band each: frames per second.
function bench(frames) {
  const pass = { divisor: 1, aa: 0 };
  const start = performance.now();
  for (let i = 0; i < frames; ++i) renderBand(pass, 0, 1 << 30, -1);
  return (performance.now() - start) / frames;
}

function handle(m) {
  if (m.type === 'files') {
    // A scene chosen from disk, with its meshes: written into /scene, read from there.
    const FS = core.FS;
    try { FS.mkdir('/scene'); } catch (e) { /* already there */ }
    for (const name of FS.readdir('/scene')) if (name !== '.' && name !== '..') FS.unlink('/scene/' + name);
    for (const f of m.files) FS.writeFile('/scene/' + f.name, new Uint8Array(f.bytes));
    FS.chdir('/scene');
  } else if (m.type === 'render') {
    job = { source: m.source, sets: m.sets, term: m.term };
    const gen = ++generation;
    run(gen);
  } else if (m.type === 'tree') {
    postMessage({ type: 'tree', x: m.x, y: m.y, json: core.UTF8ToString(core._luz_ray_tree(m.x, m.y)) });
  } else if (m.type === 'bench') {
    postMessage({ type: 'bench', ms: bench(m.frames) });
  }
}

onmessage = (e) => { if (core) handle(e.data); else pending.push(e.data); };
createLuz().then((m) => {
  core = m;
  postMessage({ type: 'ready', demos: JSON.parse(core.UTF8ToString(core._luz_demos())),
    limits: JSON.parse(core.UTF8ToString(core._luz_limits())) });
  for (const msg of pending.splice(0)) handle(msg);
});
