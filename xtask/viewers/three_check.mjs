// Check that exported .glb files load and animate correctly in three.js (run in node, no browser).
//
// Tested with three@0.187.0 on node 20. Install once:
//     mkdir -p /tmp/viewers && cd /tmp/viewers && npm init -y && npm install three@0.187.0
// Run (from the repository root):
//     NODE_PATH=/tmp/viewers/node_modules node xtask/viewers/three_check.mjs FILE.glb...
// Node's ESM loader ignores NODE_PATH, so this script resolves `three` from NODE_PATH itself
// (falling back to a plain `import('three')`, e.g. when node_modules is in a parent folder).
//
// For each file: GLTFLoader.parse, then checks a SkinnedMesh and a non-skinned mesh (terrain),
// the skeleton, the animations, and that an AnimationMixer at mid-animation gives finite bone
// world matrices and a skinned bounding box different from frame 0's (first clip; also prints the
// lowest skinned vertex's height above the terrain). Exits 1 on any failure.
import fs from 'node:fs';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

// --- locate three (same module instance as the one GLTFLoader imports as 'three') ---
async function importThree() {
  for (const dir of (process.env.NODE_PATH || '').split(path.delimiter).filter(Boolean)) {
    const root = path.join(dir, 'three');
    if (fs.existsSync(path.join(root, 'package.json'))) {
      const url = (p) => pathToFileURL(path.join(root, p)).href;
      return [await import(url('build/three.module.js')), await import(url('examples/jsm/loaders/GLTFLoader.js'))];
    }
  }
  try {
    return [await import('three'), await import('three/addons/loaders/GLTFLoader.js')];
  } catch (e) {
    console.error(`cannot load three.js (${e.code}); set NODE_PATH to the node_modules folder holding three`);
    process.exit(2);
  }
}
const [THREE, { GLTFLoader }] = await importThree();

// --- minimal node shims ---
globalThis.self ??= globalThis; // GLTFLoader reads self.URL for embedded images
if (typeof document === 'undefined') {
  // No DOM to decode PNG/JPEG textures: hand back a 1x1 placeholder instead (geometry and
  // animation checks do not need pixels). Only used if a file has images; without it
  // GLTFLoader warns "Couldn't load texture" and drops the texture.
  THREE.ImageLoader.prototype.load = function (url, onLoad) {
    const img = { width: 1, height: 1, src: url };
    setTimeout(() => onLoad && onLoad(img), 0);
    return img;
  };
}

class CheckError extends Error {}
const check = (cond, msg) => { if (!cond) throw new CheckError(msg); };
const fmt = (v) => `(${v.x.toFixed(3)},${v.y.toFixed(3)},${v.z.toFixed(3)})`;

function parse(file) {
  const buf = fs.readFileSync(file);
  const ab = buf.buffer.slice(buf.byteOffset, buf.byteOffset + buf.byteLength);
  return new Promise((resolve, reject) => new GLTFLoader().parse(ab, path.dirname(file) + '/', resolve, reject));
}

// Skinned bounding box and lowest skinned vertex (world space, y up) at time t.
function poseAt(mixer, scene, skinned, t) {
  mixer.setTime(t);
  scene.updateMatrixWorld(true);
  skinned.computeBoundingBox(); // applies bone transforms in recent three.js
  const box = skinned.boundingBox.clone().applyMatrix4(skinned.matrixWorld);
  const v = new THREE.Vector3(), low = new THREE.Vector3(0, Infinity, 0);
  for (let i = 0; i < skinned.geometry.attributes.position.count; i++) {
    skinned.getVertexPosition(i, v); // skinned, in the mesh's local space
    v.applyMatrix4(skinned.matrixWorld);
    if (v.y < low.y) low.copy(v);
  }
  return { box, low };
}

async function checkFile(file) {
  let gltf;
  try { gltf = await parse(file); } catch (e) { throw new CheckError(`GLTFLoader.parse failed: ${e.message || e}`); }
  const { scene, animations } = gltf;

  const meshes = [];
  scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  console.log('  meshes:');
  for (const m of meshes) {
    const bones = m.isSkinnedMesh ? ` bones=${m.skeleton.bones.length}` : '';
    console.log(`    '${m.name}' ${m.type} verts=${m.geometry.attributes.position.count}${bones} parent='${m.parent?.name}'`);
  }
  const skinned = meshes.filter((m) => m.isSkinnedMesh);
  const plain = meshes.filter((m) => !m.isSkinnedMesh);
  check(skinned.length >= 1, 'no SkinnedMesh in the scene');
  check(plain.length >= 1, 'no non-skinned mesh (terrain) in the scene');
  const sk = skinned[0];
  const terrain = plain.reduce((a, b) => (b.geometry.attributes.position.count > a.geometry.attributes.position.count ? b : a));
  check(sk.skeleton.bones.length > 0, 'skeleton has no bones');
  console.log(`  skeleton: ${sk.skeleton.bones.length} bones (${sk.skeleton.bones.map((b) => b.name).join(', ')})`);

  check(animations.length >= 1, 'no animation');
  for (const a of animations) {
    console.log(`  animation '${a.name}': ${a.duration.toFixed(3)} s, ${a.tracks.length} tracks`);
    for (const tr of a.tracks) {
      const i = tr.values.findIndex((x) => !Number.isFinite(x));
      check(i < 0, `animation '${a.name}' track '${tr.name}': non-finite value at key ${Math.floor(i / tr.getValueSize())}`);
    }
  }

  const clip = animations[0];
  const mixer = new THREE.AnimationMixer(scene);
  const action = mixer.clipAction(clip).setLoop(THREE.LoopOnce); // so t=duration is the last pose, not t=0
  action.clampWhenFinished = true;
  action.play();
  const ray = new THREE.Raycaster();
  const results = [];
  for (const t of [0, clip.duration / 2, clip.duration]) {
    const r = poseAt(mixer, scene, sk, t);
    for (const b of sk.skeleton.bones) check(b.matrixWorld.elements.every(Number.isFinite), `bone '${b.name}' matrix not finite at t=${t}`);
    check([r.box.min, r.box.max].every((p) => p.toArray().every(Number.isFinite)), `skinned bounding box not finite at t=${t}`);
    // Height of the lowest skinned vertex above the terrain (downward ray from far above).
    ray.set(new THREE.Vector3(r.low.x, r.low.y + 1e4, r.low.z), new THREE.Vector3(0, -1, 0));
    const hit = ray.intersectObject(terrain, false)[0];
    const h = hit ? (r.low.y - hit.point.y).toFixed(4) : 'n/a (no terrain below)';
    console.log(`    t=${t.toFixed(3)}s: skinned bbox min=${fmt(r.box.min)} max=${fmt(r.box.max)} lowest vertex height above terrain=${h}`);
    results.push(r);
  }
  const c0 = results[0].box.getCenter(new THREE.Vector3()), c1 = results[1].box.getCenter(new THREE.Vector3());
  const size = results[0].box.getSize(new THREE.Vector3()).length();
  console.log(`  bbox centre moved ${c0.distanceTo(c1).toFixed(3)} from t=0 to mid-animation`);
  check(c0.distanceTo(c1) > 0.01 * size, 'skinned bounding box at mid-animation equals frame 0 (no motion / skinning not applied?)');
}

const files = process.argv.slice(2);
if (!files.length) { console.error('usage: node three_check.mjs FILE.glb...'); process.exit(2); }
console.log(`three.js r${THREE.REVISION}, node ${process.version}`);
const failed = [];
for (const f of files) {
  console.log(`== ${f}`);
  try { await checkFile(f); console.log('  OK'); } catch (e) {
    if (!(e instanceof CheckError)) console.log(e.stack);
    console.log(`  FAIL: ${e.message}`);
    failed.push(f);
  }
}
if (failed.length) { console.log(`FAILED: ${failed.length} of ${files.length} file(s): ${failed.join(', ')}`); process.exit(1); }
console.log(`all ${files.length} file(s) OK`);
