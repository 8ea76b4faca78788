// route.html's own script (and compare.html's, route-fan.html's, sweep.html's): the routes of the
// JSON block #route-data played in 3-D with three.js, by its mode: "route" one route, "compare"
// both dynamics, each its own colour, one time moving both, "fan" many CM paths over the ground
// (with the scene as written, if it ran).
// Axes as the scene's: X forward, Y up, Z lateral (right-handed, as three.js's). The block is a
// group placed at each pose (its origin the row's point, its rotation a quaternion); between
// poses the position is linear and the rotation spherical-linear in time.
// The page honours a hash: #t=end or #t=SECONDS (paused there), view=fit|plan|side, play=0.
// It writes what it shows into the element #status as JSON, for tests.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const D = JSON.parse(document.getElementById('route-data').textContent);
const statusEl = document.getElementById('status');
const status = { ready: false, frames: 0 };
const report = () => { statusEl.textContent = JSON.stringify(status); };
window.addEventListener('error', (e) => { status.error = String(e.message); report(); });

// The routes (one on route.html, both dynamics on compare.html, the scene as written, if any,
// on a fan page) and the fan's CM paths (route-fan.html, sweep.html).
const R = D.routes;
const L = D.L;
const hex = (c) => '#' + c.toString(16).padStart(6, '0');
const T0 = R.length ? Math.min(...R.map((r) => r.poses.t[0])) : 0;
const T1 = R.length ? Math.max(...R.map((r) => r.poses.t[r.poses.t.length - 1])) : 0;

const hash = new URLSearchParams(location.hash.replace(/^#/, ''));
const canvas = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio || 1);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xf4f1ea);
const camera = new THREE.PerspectiveCamera(40, 1, 0.01 * L, 1e4 * L);
const controls = new OrbitControls(camera, canvas);
controls.enableDamping = false;

scene.add(new THREE.HemisphereLight(0xffffff, 0x8a7f6a, 1.4));
const sun = new THREE.DirectionalLight(0xffffff, 2.0);
scene.add(sun);
scene.add(sun.target);

const srgb = (r, g, b) => new THREE.Color().setRGB(r, g, b, THREE.SRGBColorSpace);

// The foundation: world axes, a colour a corner (by dip), flat-shaded.
{
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(D.ground.positions, 3));
  const c = D.ground.colors;
  const lin = new Float32Array(c.length);
  for (let k = 0; k < c.length; k += 3) {
    const col = srgb(c[k], c[k + 1], c[k + 2]);
    lin[k] = col.r; lin[k + 1] = col.g; lin[k + 2] = col.b;
  }
  g.setAttribute('color', new THREE.BufferAttribute(lin, 3));
  g.computeVertexNormals();
  const m = new THREE.MeshLambertMaterial({
    vertexColors: true, side: THREE.DoubleSide,
    polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
  });
  scene.add(new THREE.Mesh(g, m));
  const triangles = D.ground.positions.length / 9;
  const creases = new THREE.EdgesGeometry(g, triangles > 200 ? 20 : 1);
  scene.add(new THREE.LineSegments(creases, new THREE.LineBasicMaterial({ color: 0x6b5d45 })));
}

// Each route: its block (its mesh in its own axes, its base on y' = 0), the block at the start
// (pale), its contacts (or a base's corners) coloured by their state, its CM path and CM.
// One route's CM path is red and its block grey; on compare.html each route takes its colour,
// the block tinted by it.
const TOUCH = {
  1: { color: 0x1f5fbf, name: 'sticking' },
  2: { color: 0xe07b00, name: 'slipping' },
  3: { color: 0x2a9d3a, name: 'carrying' },
};
const dotGeometry = new THREE.SphereGeometry(0.03 * L, 16, 12);
function blockGroup(route, opacity) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(route.block.positions, 3));
  g.setIndex(route.block.triangles);
  g.computeVertexNormals();
  const color = new THREE.Color(0xbdb8ad);
  if (D.mode === 'compare') color.lerp(new THREE.Color(route.color), 0.45);
  const m = new THREE.MeshStandardMaterial({
    color, roughness: 0.85, metalness: 0.0,
    transparent: opacity < 1, opacity, depthWrite: opacity >= 1,
  });
  const group = new THREE.Group();
  group.add(new THREE.Mesh(g, m));
  const edges = new THREE.LineSegments(new THREE.EdgesGeometry(g, 20),
    new THREE.LineBasicMaterial({ color: 0x333333, transparent: opacity < 1, opacity }));
  group.add(edges);
  return group;
}
const drawn = R.map((route, k) => {
  const P = route.poses;
  const block = blockGroup(route, 1);
  scene.add(block);
  let ghost = null;
  if (k === 0) {
    ghost = blockGroup(route, 0.22);
    scene.add(ghost);
  }
  const dots = [];
  for (let c = 0; c < route.points.length / 3; c++) {
    const dot = new THREE.Mesh(dotGeometry, new THREE.MeshBasicMaterial({ color: 0x1f5fbf }));
    dot.position.set(route.points[3 * c], route.points[3 * c + 1], route.points[3 * c + 2]);
    block.add(dot);
    dots.push(dot);
  }
  // The CM path, and the CM: drawn over everything (the paper's CM lies in the base plane, on
  // the ground; a monolith's inside it).
  const cmDot = new THREE.Mesh(new THREE.SphereGeometry(0.02 * L, 12, 8),
    new THREE.MeshBasicMaterial({ color: route.color, depthTest: false }));
  cmDot.renderOrder = 3;
  scene.add(cmDot);
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(P.cm, 3));
  const line = new THREE.Line(g, new THREE.LineBasicMaterial({ color: route.color, depthTest: false }));
  line.renderOrder = 3;
  scene.add(line);
  return { route, P, n: P.t.length, block, ghost, dots, cmDot };
});

// The fan: every path's segments in one set of lines, over the ground.
let fanSegments = 0;
if (D.fan) {
  const F = D.fan;
  const pts = F.points;
  const ends = F.starts.slice(1).concat([pts.length / 3]);
  const seg = [];
  F.starts.forEach((s, p) => {
    for (let k = s; k + 1 < ends[p]; k++) {
      seg.push(pts[3 * k], pts[3 * k + 1], pts[3 * k + 2], pts[3 * k + 3], pts[3 * k + 4], pts[3 * k + 5]);
    }
  });
  fanSegments = seg.length / 6;
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.Float32BufferAttribute(seg, 3));
  const lines = new THREE.LineSegments(g, new THREE.LineBasicMaterial({
    color: F.color, transparent: true, opacity: 0.55, depthTest: false,
  }));
  lines.renderOrder = 2;
  scene.add(lines);
}

// The water's push at the start, on its line of action (the first route's: every route here
// starts from the same scene).
const force = R.length ? R[0].force : null;
if (force) {
  const tail = new THREE.Vector3(...force.tail);
  const head = new THREE.Vector3(...force.head);
  const dir = head.clone().sub(tail);
  const len = dir.length();
  dir.normalize();
  const r = 0.025 * len;
  const blue = new THREE.MeshBasicMaterial({ color: 0x1565c0 });
  const shaft = new THREE.Mesh(new THREE.CylinderGeometry(r, r, 0.75 * len, 12), blue);
  shaft.position.copy(tail).addScaledVector(dir, 0.375 * len);
  const tip = new THREE.Mesh(new THREE.ConeGeometry(3 * r, 0.25 * len, 16), blue);
  tip.position.copy(tail).addScaledVector(dir, 0.875 * len);
  const q = new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 1, 0), dir);
  shaft.quaternion.copy(q);
  tip.quaternion.copy(q);
  scene.add(shaft, tip);
}

// Text.
const fmt = (x, d) => (Math.abs(x) < 0.5 * 10 ** -d ? 0 : x).toFixed(d);
document.getElementById('title').textContent = D.title;
{
  const swatch = (c, extra) => `<span style="background:${c}${extra || ''}"></span>`;
  const items = [];
  const esc = (t) => String(t).replace(/&/g, '&amp;').replace(/</g, '&lt;');
  if (D.fan) items.push(`${swatch(hex(D.fan.color))}${esc(D.fan.label)}`);
  for (const route of R) {
    const what = D.mode === 'route' ? 'CM path' : `${esc(route.label)}: CM path${D.mode === 'compare' ? ' and block' : ''}`;
    items.push(`${swatch(hex(route.color))}${what}`);
  }
  if (force) {
    items.push(`${swatch('#1565c0')}water force ${fmt(force.size_n / 1e6, 2)} MN at the start, c = ${fmt(force.eccentricity_m, 2)} m`);
  }
  if (R.length) {
    const corners = R[0].corners;
    for (const k of (corners ? [3] : [1, 2])) {
      items.push(`${swatch(hex(TOUCH[k].color))}${corners ? 'corner' : 'contact'} ${TOUCH[k].name}`);
    }
    items.push(`${swatch('#bdb8ad', ';opacity:0.5')}block at the start`);
  }
  document.getElementById('legend').innerHTML = items.join(' ');
  const ends = R.map((route) => {
    const who = D.mode === 'route' ? 'The route' : route.label[0].toUpperCase() + route.label.slice(1);
    return `${who} ends at t = ${fmt(route.end.t_s, 3)} s after ${fmt(route.end.travel_m, 3)} m: ${route.end.detail || route.end.reason}`;
  });
  document.getElementById('end').textContent = ends.concat(D.notes || []).join('. ');
}
const readout = document.getElementById('readout');
if (!R.length) document.getElementById('controls').style.display = 'none';

// The pose of route `d` at time t.
const qa = new THREE.Quaternion();
const qb = new THREE.Quaternion();
function indexAt(P, n, t) {
  let lo = 0;
  let hi = n - 1;
  if (t <= P.t[0]) return 0;
  if (t >= P.t[hi]) return hi;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (P.t[mid] <= t) lo = mid; else hi = mid;
  }
  return lo;
}
function poseAt(d, t, group) {
  const { P, n } = d;
  const i = indexAt(P, n, t);
  const j = Math.min(i + 1, n - 1);
  const span = P.t[j] - P.t[i];
  const f = span > 0 ? Math.min(Math.max((t - P.t[i]) / span, 0), 1) : 0;
  const lerp = (a, k) => a[i * k] + f * (a[j * k] - a[i * k]);
  group.position.set(
    P.at[3 * i] + f * (P.at[3 * j] - P.at[3 * i]),
    P.at[3 * i + 1] + f * (P.at[3 * j + 1] - P.at[3 * i + 1]),
    P.at[3 * i + 2] + f * (P.at[3 * j + 2] - P.at[3 * i + 2]));
  qa.fromArray(P.q, 4 * i);
  qb.fromArray(P.q, 4 * j);
  group.quaternion.slerpQuaternions(qa, qb, f);
  const cm = [0, 1, 2].map((a) => P.cm[3 * i + a] + f * (P.cm[3 * j + a] - P.cm[3 * i + a]));
  return {
    cm,
    k: f < 0.5 ? i : j,
    travel: lerp(P.travel, 1),
    theta: lerp(P.theta, 1),
    alpha: lerp(P.alpha, 1),
    beta: lerp(P.beta, 1),
  };
}
for (const d of drawn) if (d.ghost) poseAt(d, d.P.t[0], d.ghost);

// The camera: the routes' extent (every pose's CM, and the block's reach round it), and the
// fan's.
const extent = new THREE.Box3();
for (const d of drawn) {
  const reach = new THREE.Box3().setFromBufferAttribute(
    new THREE.Float32BufferAttribute(d.route.block.positions, 3));
  const r = Math.max(reach.min.length(), reach.max.length());
  for (let k = 0; k < d.n; k++) {
    const p = new THREE.Vector3(d.P.at[3 * k], d.P.at[3 * k + 1], d.P.at[3 * k + 2]);
    extent.expandByPoint(p.clone().addScalar(r));
    extent.expandByPoint(p.clone().subScalar(r));
  }
}
if (D.fan) {
  const pts = D.fan.points;
  for (let k = 0; k < pts.length; k += 3) extent.expandByPoint(new THREE.Vector3(pts[k], pts[k + 1], pts[k + 2]));
}
if (force) extent.expandByPoint(new THREE.Vector3(...force.tail));
if (extent.isEmpty()) {
  extent.setFromBufferAttribute(new THREE.Float32BufferAttribute(D.ground.positions, 3));
}
if (extent.isEmpty()) extent.set(new THREE.Vector3(-L, -L, -L), new THREE.Vector3(L, L, L));
function look(kind) {
  const c = extent.getCenter(new THREE.Vector3());
  const size = extent.getSize(new THREE.Vector3());
  const vfov = THREE.MathUtils.degToRad(camera.fov);
  const hfov = 2 * Math.atan(Math.tan(vfov / 2) * camera.aspect);
  const half = (kind === 'plan') ? Math.max(size.x / 2 / Math.tan(hfov / 2), size.z / 2 / Math.tan(vfov / 2))
    : (kind === 'side') ? Math.max(size.x / 2 / Math.tan(hfov / 2), size.y / 2 / Math.tan(vfov / 2))
      : 0.5 * size.length() / Math.sin(Math.min(vfov, hfov) / 2);
  const d = 1.1 * half + (kind === 'fit' ? 0 : 0.5 * Math.max(size.x, size.y, size.z));
  const dir = kind === 'plan' ? new THREE.Vector3(0, 1, 1e-3)
    : kind === 'side' ? new THREE.Vector3(0, 0, 1)
      : new THREE.Vector3(-0.35, 0.8, 1.0);
  dir.normalize();
  camera.position.copy(c).addScaledVector(dir, d);
  camera.near = Math.max(1e-3 * d, 1e-4 * L);
  camera.far = 100 * (d + size.length());
  camera.updateProjectionMatrix();
  controls.target.copy(c);
  controls.update();
  sun.position.copy(c).add(new THREE.Vector3(-0.4 * d, d, 0.3 * d));
  sun.target.position.copy(c);
  status.view = kind;
}

function resize() {
  const w = canvas.clientWidth || window.innerWidth;
  const h = canvas.clientHeight || window.innerHeight;
  renderer.setSize(w, h, false);
  camera.aspect = w / Math.max(h, 1);
  camera.updateProjectionMatrix();
}

// Playing.
const slider = document.getElementById('slider');
const playButton = document.getElementById('play');
const speedSelect = document.getElementById('speed');
let time = T0;
let playing = T1 > T0;
const asked = hash.get('t');
if (asked !== null) {
  const t = asked === 'end' ? T1 : Number(asked);
  time = Number.isFinite(t) ? Math.min(Math.max(t, T0), T1) : T0;
  playing = false;
}
if (hash.get('play') === '0') playing = false;
const setPlaying = (p) => { playing = p; playButton.textContent = p ? 'pause' : 'play'; };
setPlaying(playing);
playButton.addEventListener('click', () => {
  if (!playing && time >= T1) time = T0;
  setPlaying(!playing);
});
slider.addEventListener('input', () => {
  time = T0 + (T1 - T0) * Number(slider.value) / 1000;
  setPlaying(false);
});
document.getElementById('fit').addEventListener('click', () => look('fit'));
document.getElementById('plan').addEventListener('click', () => look('plan'));
document.getElementById('side').addEventListener('click', () => look('side'));
window.addEventListener('resize', resize);
window.addEventListener('hashchange', () => location.reload());

function blockInView(block) {
  const box = new THREE.Box3().setFromObject(block);
  const corners = [];
  for (const x of [box.min.x, box.max.x]) {
    for (const y of [box.min.y, box.max.y]) {
      for (const z of [box.min.z, box.max.z]) corners.push(new THREE.Vector3(x, y, z));
    }
  }
  return corners.every((p) => {
    p.project(camera);
    return Math.abs(p.x) <= 1 && Math.abs(p.y) <= 1 && p.z >= -1 && p.z <= 1;
  });
}

function draw() {
  const shown = drawn.map((d) => {
    const s = poseAt(d, time, d.block);
    d.cmDot.position.set(...s.cm);
    const touch = d.P.touch[s.k];
    for (let k = 0; k < d.dots.length; k++) {
      const code = Number(touch[k] || 0);
      d.dots[k].visible = code !== 0;
      if (code) d.dots[k].material.color.setHex(TOUCH[code].color);
    }
    return s;
  });
  if (T1 > T0) slider.value = String(Math.round(1000 * (time - T0) / (T1 - T0)));
  const angles = (s) => `travel ${fmt(s.travel, 3)} m · yaw θ = ${fmt(s.theta, 2)}° · tilts α = ${fmt(s.alpha, 2)}°, β = ${fmt(s.beta, 2)}°`;
  if (D.mode === 'route' && shown.length) {
    readout.textContent = `t = ${fmt(time, 3)} s · ${angles(shown[0])}`;
  } else if (shown.length) {
    readout.innerHTML = [`t = ${fmt(time, 3)} s`].concat(shown.map((s, k) =>
      `<span style="color:${hex(R[k].color)}">${R[k].label}</span>: ${angles(s)}`)).join('<br>');
  } else {
    readout.textContent = '';
  }
  renderer.render(scene, camera);
  status.frames += 1;
  status.mode = D.mode;
  status.time = Number(fmt(time, 3));
  status.playing = playing;
  status.routes = shown.map((s, k) => ({
    label: R[k].label,
    travel: Number(fmt(s.travel, 3)),
    theta: Number(fmt(s.theta, 2)),
    poses: drawn[k].n,
    end: R[k].poses.t[drawn[k].n - 1],
    blockInView: blockInView(drawn[k].block),
  }));
  if (shown.length) {
    status.travel = status.routes[0].travel;
    status.theta = status.routes[0].theta;
    status.poses = drawn[0].n;
  }
  status.blockInView = status.routes.every((r) => r.blockInView);
  status.fanPaths = D.fan ? D.fan.starts.length : 0;
  status.fanSegments = fanSegments;
  status.ready = true;
  report();
}

let before = performance.now();
function frame(now) {
  const dt = Math.min(Math.max((now - before) / 1000, 0), 0.1);
  before = now;
  if (playing) {
    time += dt * Number(speedSelect.value);
    if (time >= T1) { time = T1; setPlaying(false); }
  }
  draw();
  requestAnimationFrame(frame);
}

resize();
look(['plan', 'side', 'fit'].includes(hash.get('view')) ? hash.get('view') : 'fit');
draw();
requestAnimationFrame(frame);
