// luz.html's page script (docs/WEB.md): the panel, the canvas at 1:1 and the mouse; every edit is a
// scene path and a JSON value, as `luz render --set PATH=JSON` takes it, sent to the worker.
'use strict';
const $ = (id) => document.getElementById(id);
const worker = new Worker(URL.createObjectURL(
  new Blob([$('luz-worker').textContent], { type: 'text/javascript' })));
const TERMS = ['ambient', 'diffuse', 'specular', 'reflected', 'refracted', 'emitted', 'shadow',
  'depth', 'normal', 'tests'];
const ENUMS = {
  'render.pipeline': ['zbuffer', 'raycast', 'raytrace'],
  'render.model': ['lambert', 'phong'],
  'render.antialias.mode': ['none', 'grid', 'adaptive'],
  'render.tree_attenuation': [false, true],
  'attenuation': ['linear', 'none', 'inverse_square'],
  'materials.*.reflectance': ['constant', 'fresnel'],
};
const state = {
  source: 'demo:whitted', sets: new Map(), term: -1, gen: 0, scene: null, limits: {},
  good: null, // the last scene that loaded: { source, sets }
  error: '', done: false, panelFor: null, waiters: [], treeWaiter: null, benchWaiter: null,
};
let pass = null; // the canvas of the pass being drawn (its own resolution)

function status(text) { $('status').textContent = text; }
function showError(message) {
  state.error = message;
  $('error').textContent = message;
  $('error').hidden = !message;
}

function render() {
  state.done = false;
  const overlay = $('rays');
  overlay.getContext('2d').clearRect(0, 0, overlay.width, overlay.height);
  state.gen += 1;
  worker.postMessage({ type: 'render', source: state.source, term: state.term,
    sets: [...state.sets].map(([k, v]) => `${k}=${v}`) });
}
function set(path, json) { state.sets.set(path, json); render(); }
function settle() {
  state.done = true;
  for (const w of state.waiters.splice(0)) w();
}

// --- the panel: a control for each key of the scene the viewer has, ranges from limits.cpp
function limitOf(path) {
  const generic = path.replace(/^lights\.\d+\./, 'lights.*.').replace(/^materials\.[^.]+\./, 'materials.*.');
  return state.limits[path] || state.limits[generic];
}
function enumOf(path) {
  return ENUMS[path] || ENUMS[path.replace(/^materials\.[^.]+\./, 'materials.*.')];
}
function control(path, value) {
  const row = document.createElement('label');
  row.className = 'row';
  row.append(path.split('.').slice(-1)[0] + ' ');
  const choices = enumOf(path);
  if (choices) {
    const sel = document.createElement('select');
    sel.dataset.path = path;
    for (const c of choices) sel.add(new Option(String(c), JSON.stringify(c), false, c === value));
    sel.onchange = () => set(path, sel.value);
    row.append(sel);
    return row;
  }
  const values = Array.isArray(value) ? value : [value];
  const lim = limitOf(path);
  const inputs = values.map((v) => {
    const input = document.createElement('input');
    input.type = lim ? 'range' : 'number';
    if (lim) { // the loader's slider range, widened to the scene's value when it lies outside
      input.min = Math.min(lim[0], v); input.max = Math.max(lim[1], v); input.step = lim[2] ? 1 : 'any';
    }
    else input.step = 0.1;
    input.value = v;
    input.title = path;
    return input;
  });
  const out = document.createElement('span');
  const show = () => { out.textContent = inputs.map((i) => Number(i.value).toPrecision(3)).join(' '); };
  for (const input of inputs) {
    input.dataset.path = path;
    input.oninput = () => {
      show();
      const nums = inputs.map((i) => Number(i.value));
      set(path, JSON.stringify(Array.isArray(value) ? nums : nums[0]));
    };
    row.append(input);
  }
  show();
  row.append(out);
  return row;
}
function section(title, entries) {
  const box = document.createElement('fieldset');
  box.innerHTML = `<legend>${title}</legend>`;
  for (const [path, value] of entries) box.append(control(path, value));
  return box;
}
function buildPanel(scene) {
  const panel = $('panel');
  panel.textContent = '';
  const r = scene.render || {};
  const top = [['render.pipeline', r.pipeline], ['render.model', r.model],
    ['render.max_depth', r.max_depth], ['render.tree_attenuation', r.tree_attenuation],
    ['render.antialias.mode', r.antialias && r.antialias.mode], ['ambient', scene.ambient],
    ['attenuation_k', scene.attenuation_k]];
  if ('attenuation' in scene) top.push(['attenuation', scene.attenuation]);
  panel.append(section('render', top.filter(([, v]) => v !== undefined)));
  (scene.lights || []).forEach((l, i) => {
    panel.append(section(`lights.${i}`, [[`lights.${i}.intensity`, l.intensity],
      [`lights.${i}.position`, l.position]].filter(([, v]) => v !== undefined)));
  });
  for (const [name, m] of Object.entries(scene.materials || {})) {
    const keys = ['ka', 'kd', 'ks', 'n', 'reflection', 'transparency', 'ior', 'reflectance'];
    panel.append(section(`materials.${name}`,
      keys.filter((k) => k in m).map((k) => [`materials.${name}.${k}`, m[k]])));
  }
}

// --- the canvas: each band drawn as it comes, coarse passes scaled up (nearest pixel)
function drawBand(m) {
  const canvas = $('image');
  const W = state.scene.image.width, H = state.scene.image.height;
  if (canvas.width !== W || canvas.height !== H) { canvas.width = W; canvas.height = H; }
  const ctx = canvas.getContext('2d');
  const rows = m.rgba.byteLength / (4 * m.width);
  const data = new ImageData(new Uint8ClampedArray(m.rgba), m.width, rows);
  if (m.width === W && m.height === H) { ctx.putImageData(data, 0, m.y0); return; }
  if (!pass || pass.width !== m.width || pass.height !== m.height) {
    pass = document.createElement('canvas');
    pass.width = m.width; pass.height = m.height;
  }
  pass.getContext('2d').putImageData(data, 0, m.y0);
  ctx.imageSmoothingEnabled = false;
  const sy = H / m.height;
  ctx.drawImage(pass, 0, m.y0, m.width, rows, 0, Math.round(m.y0 * sy), W, Math.round(rows * sy));
}

worker.onmessage = (e) => {
  const m = e.data;
  if (m.type === 'ready') {
    state.limits = m.limits;
    const sel = $('scenes');
    for (const [name, text] of m.demos) sel.add(new Option(name, name, false, name === state.source));
    readFragment();
    showSource(state.source);
    render();
    return;
  }
  if (m.type === 'tree') {
    const tree = JSON.parse(m.json);
    $('tree').textContent = JSON.stringify(tree, null, 1);
    drawRays(tree);
    if (state.treeWaiter) state.treeWaiter(m.json), state.treeWaiter = null;
    return;
  }
  if (m.type === 'bench') { if (state.benchWaiter) state.benchWaiter(m.ms); return; }
  if (m.gen !== state.gen) return; // an older edit's
  if (m.type === 'error') {
    showError(m.message);
    status('error: the last good image is kept');
    // A scene that never loaded: back to the one whose image and panel are shown (the menu too).
    if (state.good && state.source !== state.good.source) {
      state.source = state.good.source;
      state.sets = new Map(state.good.sets);
      showSource(state.source);
    }
    settle();
  } else if (m.type === 'scene') {
    showError('');
    state.scene = m.scene;
    state.good = { source: state.source, sets: new Map(state.sets) };
    if (state.panelFor !== state.source) { buildPanel(m.scene); state.panelFor = state.source; }
  } else if (m.type === 'band') drawBand(m);
  else if (m.type === 'pass') {
    const rps = m.rays / (m.ms / 1000);
    status(`pass ${m.pass + 1}/${m.passes}: ${m.ms.toFixed(1)} ms, ` +
      `${(rps / 1e6).toFixed(2)} M rays/s`);
  } else if (m.type === 'done') settle();
};

// --- scenes: built-in, from disk (with meshes), from the URL fragment
function showSource(source) {
  const sel = $('scenes');
  if (![...sel.options].some((o) => o.value === source)) sel.add(new Option(source, source));
  sel.value = source;
}
function chooseSource(source) {
  state.source = source;
  showSource(source);
  state.sets.clear();
  render();
}
$('scenes').onchange = (e) => chooseSource(e.target.value);
async function loadFiles(files) {
  const main = files.find((f) => /\.(json|nff)$/i.test(f.name));
  if (!main) { showError('choose a .json or .nff scene (with its .obj/.mtl files)'); return; }
  const list = await Promise.all(files.map(async (f) => ({ name: f.name, bytes: await f.arrayBuffer() })));
  worker.postMessage({ type: 'files', files: list }, list.map((f) => f.bytes));
  chooseSource(main.name);
}
$('file').onchange = (e) => loadFiles([...e.target.files]);
function readFragment() {
  const params = new URLSearchParams(location.hash.slice(1));
  const scene = params.get('scene');
  if (!scene) return;
  if (scene.startsWith('demo:')) state.source = scene;
  else { // the scene's JSON text itself
    const bytes = new TextEncoder().encode(scene).buffer;
    worker.postMessage({ type: 'files', files: [{ name: 'fragment.json', bytes }] }, [bytes]);
    state.source = 'fragment.json';
  }
  for (const s of params.getAll('set')) { const i = s.indexOf('='); state.sets.set(s.slice(0, i), s.slice(i + 1)); }
}
$('term').onchange = (e) => { state.term = Number(e.target.value); render(); };
for (let i = 0; i < TERMS.length; ++i) $('term').add(new Option(TERMS[i], i));

// --- the mouse: a click shows the pixel's ray tree; drag orbits, shift-drag pans, wheel zooms
const sub = (a, b) => a.map((v, i) => v - b[i]);
const add = (a, b) => a.map((v, i) => v + b[i]);
const scale = (a, s) => a.map((v) => v * s);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => scale(a, 1 / Math.hypot(...a));
function camera() { return state.scene.camera; }
function moveCamera(position, lookAt) {
  const round = (v) => v.map((x) => Number(x.toFixed(6)));
  state.sets.set('camera.position', JSON.stringify(round(position)));
  state.sets.set('camera.look_at', JSON.stringify(round(lookAt)));
  state.scene.camera = { ...camera(), position, look_at: lookAt };
  render();
}
let drag = null;
$('image').onmousedown = (e) => { drag = { x: e.offsetX, y: e.offsetY, moved: false, shift: e.shiftKey }; };
$('image').onmousemove = (e) => {
  if (!drag || !state.scene) return;
  const dx = e.offsetX - drag.x, dy = e.offsetY - drag.y;
  if (!drag.moved && Math.hypot(dx, dy) < 3) return;
  drag.moved = true; drag.x = e.offsetX; drag.y = e.offsetY;
  const c = camera(), up = norm(c.up || [0, 1, 0]);
  const back = sub(c.position, c.look_at), dist = Math.hypot(...back);
  const right = norm(cross(scale(back, -1), up)), upv = norm(cross(right, scale(back, -1)));
  if (drag.shift) { // pan: both points move in the image plane
    const d = add(scale(right, -dx * dist / 400), scale(upv, dy * dist / 400));
    moveCamera(add(c.position, d), add(c.look_at, d));
  } else { // orbit about the look-at point (Rodrigues about up, then about right)
    const rot = (v, k, t) => add(add(scale(v, Math.cos(t)), scale(cross(k, v), Math.sin(t))),
      scale(k, (k[0] * v[0] + k[1] * v[1] + k[2] * v[2]) * (1 - Math.cos(t))));
    let b = rot(back, up, -dx * 0.01);
    b = rot(b, norm(cross(up, b)), dy * 0.01);
    moveCamera(add(c.look_at, b), c.look_at);
  }
};
$('image').onmouseup = (e) => {
  if (drag && !drag.moved) worker.postMessage({ type: 'tree', x: e.offsetX, y: e.offsetY });
  drag = null;
};
$('image').onwheel = (e) => {
  if (!state.scene) return;
  e.preventDefault();
  const c = camera(), k = e.deltaY > 0 ? 1.1 : 1 / 1.1;
  moveCamera(add(c.look_at, scale(sub(c.position, c.look_at), k)), c.look_at);
};

// --- a pixel's ray tree drawn over the image: each ray from its origin to its hit (or out of
// the picture), projected with the camera of docs/SCENES.md#geometry (x = 2px/W − 1, y = 1 − 2py/H)
function project(P) {
  const c = camera(), W = state.scene.image.width, H = state.scene.image.height;
  const w = norm(sub(c.position, c.look_at)), u = norm(cross(c.up || [0, 1, 0], w)), v = cross(w, u);
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const d = sub(P, c.position);
  let x, y;
  if (c.projection === 'orthographic') {
    x = dot(d, u) / (c.view_height * W / H / 2);
    y = dot(d, v) / (c.view_height / 2);
  } else {
    const z = -dot(d, w);
    if (z <= 1e-6) return null;
    const t = Math.tan((c.fov_y * Math.PI) / 360);
    x = dot(d, u) / z / (t * W / H);
    y = dot(d, v) / z / t;
  }
  return [(x + 1) * W / 2, (1 - y) * H / 2];
}
const RAY_COLOURS = { primary: '#fff', shadow: '#ff0', reflection: '#0ff', refraction: '#f0f' };
function drawRays(tree) {
  const overlay = $('rays'), image = $('image');
  overlay.width = image.width; overlay.height = image.height;
  const ctx = overlay.getContext('2d');
  ctx.clearRect(0, 0, overlay.width, overlay.height);
  if (!state.scene || !tree.nodes) return;
  for (const n of tree.nodes) {
    const far = n.point || add(n.origin, scale(n.direction, 1e3));
    const a = n.kind === 'primary' ? [tree.pixel[0] + 0.5, tree.pixel[1] + 0.5] : project(n.origin);
    const b = project(far);
    if (!a || !b) continue;
    ctx.strokeStyle = RAY_COLOURS[n.kind] || '#f80';
    ctx.beginPath(); ctx.moveTo(...a); ctx.lineTo(...b); ctx.stroke();
  }
}

// --- saving
function download(blob, name) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  a.click();
}
$('save-png').onclick = () => $('image').toBlob((b) => download(b, 'luz.png'), 'image/png');
$('save-json').onclick = () => state.scene &&
  download(new Blob([JSON.stringify(state.scene, null, 2)], { type: 'application/json' }), 'scene.json');

// --- what scripts and tests call (the panel's programmatic equivalent)
window.luzPage = {
  set: (path, json) => set(path, json),
  source: (s) => chooseSource(s),
  idle: () => new Promise((r) => (state.done ? r() : state.waiters.push(r))),
  error: () => state.error,
  pixels: () => {
    const c = $('image');
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let s = '';
    for (let i = 0; i < d.length; i += 0x8000) s += String.fromCharCode(...d.subarray(i, i + 0x8000));
    return { width: c.width, height: c.height, rgba: btoa(s) };
  },
  tree: (x, y) => new Promise((r) => { state.treeWaiter = r; worker.postMessage({ type: 'tree', x, y }); }),
  files: (list) => loadFiles(list.map((f) => new File([f.text], f.name))),
  bench: (frames) => new Promise((r) => { state.benchWaiter = r; worker.postMessage({ type: 'bench', frames }); }),
};
