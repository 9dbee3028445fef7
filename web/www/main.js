// The creature playground: the library (WebAssembly) makes and animates the creatures,
// three.js draws them. Every creature, pose and downloaded file comes from `creature`.
import init, {
  World, Creature2d, glb_3d, preview_3d_png, glb_2d, preview_2d_png, generate_3d_vertices,
} from './pkg/creature_web.js';
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const $ = (id) => document.getElementById(id);
const statusLine = $('status');
const canvas = $('view');

// What the browser test reads: errors, readiness, state and the figures it prints.
const playground = { ready: false, frames: 0, simTime: 0, updateMs: 0, mode: 'single' };
window.playground = playground;

// After an error in a tab's frame or rebuild, that tab keeps drawing but moves nothing until its
// creature is made again; the other tab is not affected.
const broken = { '3d': false, '2d': false };
function report(e) {
  console.error(e);
  statusLine.textContent = `error: ${e.message ?? e}`;
}
function fail(e) {
  report(e);
  broken[tab] = true;
}

/** The herd size field, clamped to 10–1,000. */
function herdSize() {
  return Math.min(1000, Math.max(10, Math.round(Number($('herd-size').value) || 10)));
}

await init();

const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));

// ---------------------------------------------------------------- 3D
const scene = new THREE.Scene();
scene.background = new THREE.Color(0x9fc4e0);
scene.fog = new THREE.Fog(0x9fc4e0, 60, 160);
scene.add(new THREE.HemisphereLight(0xdfefff, 0x4a4030, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 2.2);
sun.position.set(3, 6, 2);
scene.add(sun);
const camera = new THREE.PerspectiveCamera(45, 1, 0.01, 500);
const controls = new OrbitControls(camera, canvas);
controls.enableDamping = true;

const skinMaterial = new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.75 });
const groundMaterial = new THREE.MeshStandardMaterial({ vertexColors: true, roughness: 0.95 });
// Swimmers swim in water (`waterVolume`), drawn after the rest.
const skyColour = new THREE.Color(0x9fc4e0);
const waterColour = new THREE.Color(0x3f7fa8);
const waterMaterial = new THREE.MeshStandardMaterial({
  color: 0x2f7fb8,
  roughness: 0.2,
  transparent: true,
  opacity: 0.35,
  depthWrite: false,
});
const marker = new THREE.Mesh(
  new THREE.RingGeometry(0.7, 1, 32).rotateX(-Math.PI / 2),
  new THREE.MeshBasicMaterial({ color: 0xffe066, side: THREE.DoubleSide }),
);
marker.visible = false;
scene.add(marker);

let world = null;
let terrainMesh = null;
let water = null;
let meshes = [];
let skinBuffer = new Float32Array(0);

/** The page's 3D parameters: each empty field is the library's default range. */
function params() {
  const value = (id) => {
    const v = $(id).value.trim();
    return v === '' ? undefined : Number(v);
  };
  return [value('body-scale'), value('head-size'), value('snout-length'), value('neck-width')];
}

function seedOf(id) {
  return Number($(id).value);
}

/** The terrain's mesh, coloured grass on the level, rock on steep faces (a step's riser). */
function terrainGeometry() {
  const g = new THREE.BufferGeometry();
  const positions = world.terrain_positions();
  const normals = world.terrain_normals();
  g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  g.setAttribute('normal', new THREE.BufferAttribute(normals, 3));
  g.setIndex(new THREE.BufferAttribute(world.terrain_indices(), 1));
  const colours = new Float32Array(positions.length);
  const grass = new THREE.Color(0x6f9a4e);
  const dry = new THREE.Color(0xa4a35f);
  const rock = new THREE.Color(0x8a8175);
  const c = new THREE.Color();
  let low = Infinity;
  let high = -Infinity;
  for (let k = 1; k < positions.length; k += 3) {
    low = Math.min(low, positions[k]);
    high = Math.max(high, positions[k]);
  }
  for (let k = 0; k < positions.length; k += 3) {
    const up = normals[k + 1];
    const h = high > low ? (positions[k + 1] - low) / (high - low) : 0;
    c.copy(grass).lerp(dry, 0.6 * h).lerp(rock, 1 - THREE.MathUtils.smoothstep(up, 0.8, 0.93));
    c.toArray(colours, k);
  }
  g.setAttribute('color', new THREE.BufferAttribute(colours, 3));
  return g;
}

/** Where there are swimmers, the water over the whole terrain: a box from its lowest ground to
 * above its highest by the longest swimmer's length and a fifth (a swimmer keeps just above the
 * ground under and ahead of it, so none breaks the surface); `null` without swimmers. */
function waterVolume() {
  let longest = 0;
  for (let i = 0; i < world.len(); i++) {
    if (world.kind(i) === 'swimmer') longest = Math.max(longest, world.length(i));
  }
  if (longest === 0) return null;
  terrainMesh.geometry.computeBoundingBox();
  const box = terrainMesh.geometry.boundingBox;
  const top = box.max.y + 1.2 * longest;
  const size = box.getSize(new THREE.Vector3());
  const centre = box.getCenter(new THREE.Vector3());
  const volume = new THREE.Mesh(new THREE.BoxGeometry(size.x, top - box.min.y, size.z), waterMaterial);
  volume.position.set(centre.x, (top + box.min.y) / 2, centre.z);
  volume.renderOrder = 1;
  volume.userData.box = new THREE.Box3(
    new THREE.Vector3(box.min.x, box.min.y, box.min.z),
    new THREE.Vector3(box.max.x, top, box.max.z),
  );
  return volume;
}

/** Seen from outside, the water tints what is behind its faces; from inside, the world fades
 * to its colour with distance instead (the fog and background turn to water). */
function underwater() {
  const inside = water !== null && water.userData.box.containsPoint(camera.position);
  if (water) water.visible = !inside;
  const colour = inside ? waterColour : skyColour;
  if (!scene.background.equals(colour)) {
    scene.background.copy(colour);
    scene.fog.color.copy(colour);
  }
}

/** Creature `i` of the world as a skinned mesh whose skinning matrices the animator writes. */
function creatureMesh(i) {
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(world.positions(i), 3));
  g.setAttribute('normal', new THREE.BufferAttribute(world.normals(i), 3));
  g.setAttribute('color', new THREE.BufferAttribute(world.colours(i), 3));
  g.setAttribute('skinIndex', new THREE.Uint16BufferAttribute(world.joints(i), 4));
  g.setAttribute('skinWeight', new THREE.BufferAttribute(world.weights(i), 4));
  g.setIndex(new THREE.BufferAttribute(world.indices(i), 1));
  const bones = Array.from({ length: world.joint_count(i) }, () => new THREE.Bone());
  // Bind inverses of identity: the animator's matrices already are joint world × inverse bind.
  const skeleton = new THREE.Skeleton(bones, bones.map(() => new THREE.Matrix4()));
  skeleton.update = function update() {
    if (this.boneTexture) this.boneTexture.needsUpdate = true;
  };
  const mesh = new THREE.SkinnedMesh(g, skinMaterial);
  mesh.bind(skeleton, new THREE.Matrix4());
  mesh.frustumCulled = false;
  return mesh;
}

function clearWorld() {
  for (const m of meshes) {
    scene.remove(m);
    m.geometry.dispose();
    m.skeleton.dispose();
  }
  meshes = [];
  if (terrainMesh) {
    scene.remove(terrainMesh);
    terrainMesh.geometry.dispose();
    terrainMesh = null;
  }
  if (water) {
    scene.remove(water);
    water.geometry.dispose();
    water = null;
  }
  if (world) world.free();
  world = null;
  marker.visible = false;
}

function showWorld() {
  terrainMesh = new THREE.Mesh(terrainGeometry(), groundMaterial);
  scene.add(terrainMesh);
  water = waterVolume();
  if (water) scene.add(water);
  meshes = Array.from({ length: world.len() }, (_, i) => creatureMesh(i));
  for (const m of meshes) scene.add(m);
  let floats = 0;
  for (let i = 0; i < world.len(); i++) floats += 16 * world.joint_count(i);
  skinBuffer = new Float32Array(floats);
  world.update(0);
  pushPoses();
}

function pushPoses() {
  world.all_skinning(skinBuffer);
  let at = 0;
  for (const m of meshes) {
    const n = 16 * m.skeleton.bones.length;
    m.skeleton.boneMatrices.set(skinBuffer.subarray(at, at + n));
    at += n;
  }
}

/** One creature on terrain sized to it, the camera on it. */
function single() {
  clearWorld();
  playground.mode = 'single';
  const kind = $('kind').value;
  const seed = seedOf('seed');
  world = World.for_creature(seedOf('terrain-seed'), kind, seed, ...params());
  showWorld();
  broken['3d'] = false;
  const length = world.length(0);
  const [x, y, z] = world.place(0);
  marker.scale.setScalar(0.25 * length);
  controls.target.set(x, y + 0.4 * length, z);
  camera.position.set(x + 2.2 * length, y + 1.5 * length, z - 2.6 * length);
  scene.fog.near = 20 * length;
  scene.fog.far = 40 * length;
  statusLine.textContent =
    `${world.kind(0)} ${seed}: ${length.toFixed(2)} m, ${world.positions(0).length / 3} vertices, ` +
    `${world.joint_count(0)} joints — click the ground`;
}

/** `n` creatures (seeds from the seed field on) wandering a 80 m square of terrain. */
function herd(n) {
  clearWorld();
  playground.mode = 'herd';
  const kind = $('kind').value;
  const first = seedOf('seed');
  const size = 80;
  // Built aside and shown only once every creature is in it.
  const herdWorld = new World(seedOf('terrain-seed'), size);
  let s = first >>> 0;
  const random = () => {
    // mulberry32: the herd's places, the same for the same seed.
    s = (s + 0x6d2b79f5) >>> 0;
    let t = s;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
  const p = params();
  try {
    for (let k = 0; k < n; k++) {
      const x = (random() - 0.5) * 0.8 * size;
      const z = (random() - 0.5) * 0.8 * size;
      const i = herdWorld.add(kind, first + k, ...p, x, z, random() * 2 * Math.PI);
      herdWorld.set_wander(i, true);
    }
  } catch (e) {
    herdWorld.free();
    throw e;
  }
  world = herdWorld;
  showWorld();
  broken['3d'] = false;
  marker.scale.setScalar(1);
  controls.target.set(0, 0, 0);
  camera.position.set(0, 0.45 * size, -0.75 * size);
  scene.fog.near = size;
  scene.fog.far = 2.5 * size;
  statusLine.textContent = `herd of ${n} from seed ${first}`;
}

// Click (not drag) on the ground: the creature goes there; in herd mode, every creature.
const raycaster = new THREE.Raycaster();
let down = null;
canvas.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
canvas.addEventListener('pointerup', (e) => {
  if (!down || !world || !terrainMesh || tab !== '3d') return;
  const moved = Math.hypot(e.clientX - down[0], e.clientY - down[1]);
  down = null;
  if (moved > 5) return;
  const r = canvas.getBoundingClientRect();
  const ndc = new THREE.Vector2(
    ((e.clientX - r.left) / r.width) * 2 - 1,
    -((e.clientY - r.top) / r.height) * 2 + 1,
  );
  raycaster.setFromCamera(ndc, camera);
  const hit = raycaster.intersectObject(terrainMesh)[0];
  if (!hit) return;
  try {
    for (let i = 0; i < world.len(); i++) {
      world.set_wander(i, false);
      world.go_to(i, hit.point.x, hit.point.z);
    }
    marker.position.copy(hit.point).add(new THREE.Vector3(0, 0.02, 0));
    marker.visible = true;
  } catch (err) {
    fail(err);
  }
});

function download(bytes, name, type) {
  const url = URL.createObjectURL(new Blob([bytes], { type }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

const guard = (f) => () => {
  try {
    f();
  } catch (e) {
    fail(e);
  }
};
// A failed download reports and leaves the live creature alone.
const guardDownload = (f) => () => {
  try {
    f();
  } catch (e) {
    report(e);
  }
};
$('new').addEventListener('click', guard(() => {
  $('seed').value = seedOf('seed') + 1;
  if (playground.mode === 'herd') herd(herdSize());
  else single();
}));
for (const id of ['kind', 'seed', 'terrain-seed', 'body-scale', 'head-size', 'snout-length', 'neck-width']) {
  $(id).addEventListener('change', guard(() => {
    if (playground.mode === 'herd') herd(herdSize());
    else single();
  }));
}
$('herd').addEventListener('click', guard(() => {
  statusLine.textContent = 'generating the herd…';
  setTimeout(guard(() => herd(herdSize())), 0);
}));
$('single').addEventListener('click', guard(single));
$('download-glb').addEventListener('click', guardDownload(() => {
  const kind = $('kind').value;
  download(glb_3d(kind, seedOf('seed'), ...params()), `${kind}-${seedOf('seed')}.glb`, 'model/gltf-binary');
}));
$('download-png').addEventListener('click', guardDownload(() => {
  const kind = $('kind').value;
  download(preview_3d_png(kind, seedOf('seed'), ...params()), `${kind}-${seedOf('seed')}.png`, 'image/png');
}));

// ---------------------------------------------------------------- 2D
const scene2d = new THREE.Scene();
scene2d.background = new THREE.Color(0xf3efe6);
const camera2d = new THREE.OrthographicCamera(-1, 1, 1, -1, -10, 10);
let flat = null;
let flatMesh = null;
let eyes = [];
const eyeWhite = new THREE.MeshBasicMaterial({ color: 0xffffff });
const eyePupil = new THREE.MeshBasicMaterial({ color: 0x111111 });
const disc = new THREE.CircleGeometry(1, 24);

function single2d() {
  if (flatMesh) {
    scene2d.remove(flatMesh);
    flatMesh.geometry.dispose();
    flatMesh.material.map.dispose();
    flatMesh.material.dispose();
    for (const e of eyes) scene2d.remove(e);
    eyes = [];
  }
  if (flat) flat.free();
  flat = null;
  flatMesh = null;
  const seed = seedOf('seed-2d');
  flat = new Creature2d(seed, 256);
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(flat.pose(0), 3));
  g.setAttribute('uv', new THREE.BufferAttribute(flat.uvs(), 2));
  g.setIndex(new THREE.BufferAttribute(flat.indices(), 1));
  const texture = new THREE.DataTexture(
    flat.texture(), flat.texture_width(), flat.texture_height(), THREE.RGBAFormat,
  );
  texture.colorSpace = THREE.SRGBColorSpace;
  texture.needsUpdate = true;
  const material = new THREE.MeshBasicMaterial({ map: texture, transparent: true, side: THREE.DoubleSide });
  flatMesh = new THREE.Mesh(g, material);
  scene2d.add(flatMesh);
  const eyeData = flat.eyes(0);
  for (let k = 0; k < eyeData.length; k += 3) {
    const white = new THREE.Mesh(disc, eyeWhite);
    const pupil = new THREE.Mesh(disc, eyePupil);
    eyes.push(white, pupil);
    scene2d.add(white, pupil);
  }
  const [x0, y0, x1, y1] = flat.bounds();
  const pad = 0.1 * Math.max(x1 - x0, y1 - y0);
  camera2d.userData.box = [x0 - pad, y0 - pad, x1 + pad, y1 + pad];
  resize();
  broken['2d'] = false;
  statusLine.textContent = `2D creature ${seed}: ${flat.uvs().length / 2} vertices`;
}

function pose2d(t) {
  flatMesh.geometry.attributes.position.array.set(flat.pose(t));
  flatMesh.geometry.attributes.position.needsUpdate = true;
  const e = flat.eyes(t);
  for (let k = 0; k < e.length / 3; k++) {
    const [x, y, r] = [e[3 * k], e[3 * k + 1], e[3 * k + 2]];
    // As the preview draws them: each eye's white, then its pupil, over the eyes before it.
    eyes[2 * k].position.set(x, y, 2 + 0.02 * k);
    eyes[2 * k].scale.setScalar(r);
    eyes[2 * k + 1].position.set(x, y, 2.01 + 0.02 * k);
    eyes[2 * k + 1].scale.setScalar(0.5 * r);
  }
}

$('new-2d').addEventListener('click', guard(() => {
  $('seed-2d').value = seedOf('seed-2d') + 1;
  single2d();
}));
$('seed-2d').addEventListener('change', guard(single2d));
$('download-glb-2d').addEventListener('click', guardDownload(() => {
  download(glb_2d(seedOf('seed-2d')), `creature-${seedOf('seed-2d')}.glb`, 'model/gltf-binary');
}));
$('download-png-2d').addEventListener('click', guardDownload(() => {
  download(preview_2d_png(seedOf('seed-2d')), `creature-${seedOf('seed-2d')}.png`, 'image/png');
}));

// ---------------------------------------------------------------- tabs, keys, frames
let tab = '3d';
function show(which) {
  tab = which;
  $('tab-3d').classList.toggle('active', which === '3d');
  $('tab-2d').classList.toggle('active', which === '2d');
  $('controls-3d').hidden = which !== '3d';
  $('controls-2d').hidden = which !== '2d';
  if (which === '2d' && !flat) single2d();
}
$('tab-3d').addEventListener('click', () => show('3d'));
$('tab-2d').addEventListener('click', guard(() => show('2d')));
window.addEventListener('keydown', (e) => {
  if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement) return;
  if (e.key === 'n' || e.key === 'N' || e.key === ' ') {
    e.preventDefault();
    $(tab === '3d' ? 'new' : 'new-2d').click();
  }
});

function resize() {
  const w = canvas.clientWidth;
  const h = canvas.clientHeight;
  const ratio = renderer.getPixelRatio();
  if (canvas.width !== Math.floor(w * ratio) || canvas.height !== Math.floor(h * ratio)) {
    renderer.setSize(w, h, false);
  }
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  const box = camera2d.userData.box;
  if (box) {
    const [x0, y0, x1, y1] = box;
    const cx = 0.5 * (x0 + x1);
    const cy = 0.5 * (y0 + y1);
    let hw = 0.5 * (x1 - x0);
    let hh = 0.5 * (y1 - y0);
    if (hw / hh < w / h) hw = (hh * w) / h;
    else hh = (hw * h) / w;
    Object.assign(camera2d, { left: cx - hw, right: cx + hw, top: cy + hh, bottom: cy - hh });
    camera2d.updateProjectionMatrix();
  }
}
window.addEventListener('resize', resize);

let last = performance.now();
let fps = 60;
function frame(now) {
  // rAF's time can precede the `performance.now()` it started from: never a negative step.
  const dt = Math.min(Math.max((now - last) / 1000, 0), 0.1);
  last = now;
  fps += (1 / Math.max(dt, 1e-3) - fps) * 0.05;
  try {
    resize();
    if (tab === '3d' && world) {
      if (!broken['3d']) {
        const t0 = performance.now();
        world.update(dt);
        pushPoses();
        const ms = performance.now() - t0;
        playground.updateMs += (ms - playground.updateMs) * 0.1;
        playground.simTime += dt;
        if (playground.mode === 'single') {
          // The camera follows the creature, keeping its offset.
          const [x, y, z] = world.place(0);
          const length = world.length(0);
          const to = new THREE.Vector3(x, y + 0.4 * length, z);
          const step = to.sub(controls.target).multiplyScalar(Math.min(1, 3 * dt));
          controls.target.add(step);
          camera.position.add(step);
        }
        if (!world.target(0)) marker.visible = false;
      }
      controls.update();
      underwater();
      renderer.render(scene, camera);
      if (playground.frames % 30 === 0) {
        document.title = `creature playground — ${fps.toFixed(0)} fps, animator ${playground.updateMs.toFixed(2)} ms`;
      }
    } else if (tab === '2d' && flat) {
      if (!broken['2d']) pose2d(now / 1000);
      renderer.render(scene2d, camera2d);
    }
    playground.frames += 1;
  } catch (e) {
    fail(e);
  }
  requestAnimationFrame(frame);
}

// ---------------------------------------------------------------- what the test drives
Object.assign(playground, {
  /** Creature 0's place and target, and the world's size. */
  state() {
    if (!world || world.len() === 0) return null;
    const target = world.target(0);
    return {
      mode: playground.mode,
      count: world.len(),
      place: Array.from(world.place(0)),
      target: target ? Array.from(target) : null,
      length: world.length(0),
      kind: world.kind(0),
      frames: playground.frames,
      simTime: playground.simTime,
      updateMs: playground.updateMs,
    };
  },
  /** Every creature's place (`x, y, z, heading`). */
  places() {
    return Array.from({ length: world.len() }, (_, i) => Array.from(world.place(i)));
  },
  /** Where the ground point under `(x, z)` is on screen (CSS pixels), for a click. */
  screenOf(x, z) {
    const y = world.height_at(x, z) ?? 0;
    const v = new THREE.Vector3(x, y, z).project(camera);
    const r = canvas.getBoundingClientRect();
    return [r.left + ((v.x + 1) / 2) * r.width, r.top + ((1 - v.y) / 2) * r.height];
  },
  /** The ground point under the screen point `(x, y)` (CSS pixels), or null. */
  groundAt(x, y) {
    const r = canvas.getBoundingClientRect();
    const ndc = new THREE.Vector2(((x - r.left) / r.width) * 2 - 1, -((y - r.top) / r.height) * 2 + 1);
    raycaster.setFromCamera(ndc, camera);
    const hit = raycaster.intersectObject(terrainMesh)[0];
    return hit ? [hit.point.x, hit.point.y, hit.point.z] : null;
  },
  /** The fraction of the canvas the creatures cover: a render without them compared. */
  creaturePixels() {
    const grab = () => {
      renderer.render(scene, camera);
      const c = document.createElement('canvas');
      c.width = 200;
      c.height = 140;
      const g = c.getContext('2d', { willReadFrequently: true });
      g.drawImage(canvas, 0, 0, c.width, c.height);
      return g.getImageData(0, 0, c.width, c.height).data;
    };
    const shown = grab();
    for (const m of meshes) m.visible = false;
    const hidden = grab();
    for (const m of meshes) m.visible = true;
    let differing = 0;
    for (let k = 0; k < shown.length; k += 4) {
      const d = Math.abs(shown[k] - hidden[k]) + Math.abs(shown[k + 1] - hidden[k + 1])
        + Math.abs(shown[k + 2] - hidden[k + 2]);
      if (d > 24) differing++;
    }
    return differing / (shown.length / 4);
  },
  /** How much of the canvas differs from its background colour (0 to 1), and its colours. */
  canvasStats() {
    const c = document.createElement('canvas');
    c.width = 96;
    c.height = 64;
    const g = c.getContext('2d', { willReadFrequently: true });
    g.drawImage(canvas, 0, 0, c.width, c.height);
    const px = g.getImageData(0, 0, c.width, c.height).data;
    const bg = (tab === '3d' ? scene.background : scene2d.background).clone().convertLinearToSRGB();
    const [br, bgg, bb] = [bg.r * 255, bg.g * 255, bg.b * 255];
    let differing = 0;
    const colours = new Set();
    for (let k = 0; k < px.length; k += 4) {
      if (Math.abs(px[k] - br) + Math.abs(px[k + 1] - bgg) + Math.abs(px[k + 2] - bb) > 24) differing++;
      colours.add((px[k] >> 3) * 1024 + (px[k + 1] >> 3) * 32 + (px[k + 2] >> 3));
    }
    return { differing: differing / (px.length / 4), colours: colours.size };
  },
  /** Median times (ms) of what the issue measures, in this browser. */
  bench({ seeds = 20, walkers = 1000, frames = 60 } = {}) {
    const median = (xs) => xs.sort((a, b) => a - b)[xs.length >> 1];
    const out = {};
    for (const kind of ['walker', 'flier', 'swimmer', 'slitherer']) {
      const times = [];
      for (let s = 0; s < seeds; s++) {
        const t0 = performance.now();
        generate_3d_vertices(kind, s, false);
        times.push(performance.now() - t0);
      }
      out[`generate_3d_${kind}_ms`] = median(times);
    }
    {
      const times = [];
      for (let s = 0; s < seeds; s++) {
        const t0 = performance.now();
        generate_3d_vertices('walker', s, true);
        times.push(performance.now() - t0);
      }
      out.generate_3d_walker_with_clips_ms = median(times);
    }
    {
      const times = [];
      for (let s = 0; s < seeds; s++) {
        const t0 = performance.now();
        new Creature2d(s, 256).free();
        times.push(performance.now() - t0);
      }
      out.generate_2d_textured_ms = median(times);
    }
    const herdWorld = new World(3, 80);
    for (let k = 0; k < walkers; k++) {
      const i = herdWorld.add('walker', k, undefined, undefined, undefined, undefined,
        ((k % 32) / 32 - 0.5) * 60, (Math.floor(k / 32) / 32 - 0.5) * 60, 0);
      herdWorld.set_wander(i, true);
    }
    for (let f = 0; f < 30; f++) herdWorld.update(1 / 60);
    const times = [];
    for (let f = 0; f < frames; f++) {
      const t0 = performance.now();
      herdWorld.update(1 / 60);
      times.push(performance.now() - t0);
    }
    herdWorld.free();
    out[`update_${walkers}_walkers_ms`] = median(times);
    return out;
  },
});

try {
  single();
} catch (e) {
  fail(e);
}
playground.ready = true;
requestAnimationFrame(frame);
