/**
 * The low-poly building blocks of the first-person kitchen: one shared material per colour (flat-shaded
 * Lambert, the colours of the top-down drawing's palette, game/palette.js) and small helpers that place a
 * box, cylinder or sphere in a group. One world unit is one grid cell (about a metre); `y` is up; a cell's
 * centre is at (x, 0, y) of the grid. Geometries and materials are shared and kept for the page's lifetime
 * (a few dozen small buffers), so views can come and go without rebuilding them.
 */

import * as THREE from "../../vendor/three/three.module.js";

export const COUNTER_TOP = 0.92;
/** The cook's eyes: at 1.5 (a little under a standing adult's, so the counter top in front is in view) and
 * `EYE_BACK` behind the centre of the cook's cell, so the counter the cook faces is not under the chin. */
export const EYE_HEIGHT = 1.5;
export const EYE_BACK = 0.3;

const materials = new Map();
const geometries = new Map();

/** The shared flat-shaded material of a colour (`emissive` for glowing parts such as a hot grill). */
export function material(color, { emissive = null, opacity = 1 } = {}) {
  const key = `${color}|${emissive}|${opacity}`;
  if (!materials.has(key)) {
    const options = { color, flatShading: true };
    if (emissive) Object.assign(options, { emissive, emissiveIntensity: 0.8 });
    if (opacity < 1) Object.assign(options, { transparent: true, opacity });
    materials.set(key, new THREE.MeshLambertMaterial(options));
  }
  return materials.get(key);
}

function shared(key, make) {
  if (!geometries.has(key)) geometries.set(key, make());
  return geometries.get(key);
}

function place(group, mesh, x, y, z) {
  mesh.position.set(x, y, z);
  group.add(mesh);
  return mesh;
}

/** A box of size (w, h, d) whose bottom face sits at height `y`, centred on (x, z). */
export function box(group, color, w, h, d, x = 0, y = 0, z = 0, options = {}) {
  const geometry = shared(`box ${w} ${h} ${d}`, () => new THREE.BoxGeometry(w, h, d));
  return place(group, new THREE.Mesh(geometry, material(color, options)), x, y + h / 2, z);
}

/** An upright cylinder (radius r at both ends unless `rTop` differs) whose bottom sits at height `y`. */
export function cylinder(group, color, r, h, x = 0, y = 0, z = 0, { rTop = r, sides = 10, ...options } = {}) {
  const geometry = shared(`cyl ${r} ${rTop} ${h} ${sides}`, () => new THREE.CylinderGeometry(rTop, r, h, sides));
  return place(group, new THREE.Mesh(geometry, material(color, options)), x, y + h / 2, z);
}

/** A low-poly ball of radius r centred at (x, y, z). */
export function ball(group, color, r, x = 0, y = 0, z = 0, options = {}) {
  const geometry = shared(`ball ${r}`, () => new THREE.IcosahedronGeometry(r, 1));
  return place(group, new THREE.Mesh(geometry, material(color, options)), x, y, z);
}

/** A dome (upper half sphere) of radius r whose rim sits at height `y`. */
export function dome(group, color, r, x = 0, y = 0, z = 0) {
  const geometry = shared(`dome ${r}`, () => new THREE.SphereGeometry(r, 12, 6, 0, Math.PI * 2, 0, Math.PI / 2));
  return place(group, new THREE.Mesh(geometry, material(color)), x, y, z);
}

const BAKED = new THREE.MeshLambertMaterial({ vertexColors: true, flatShading: true });

/**
 * One mesh for all the meshes of `group` (their shapes moved into the group's frame, their colours baked
 * into the vertices), keeping the group's other children (sprites): one draw call instead of dozens, which
 * is what software WebGL (SwiftShader) spends most of its time on. Glowing parts keep their own mesh. (Not
 * three's BufferGeometryUtils: that addon imports the bare specifier "three", which needs an import map, an
 * inline script the page's Content-Security-Policy forbids.)
 */
export function bake(group) {
  group.updateMatrixWorld(true);
  const inverse = group.matrixWorld.clone().invert();
  const parts = [];
  const keep = [];
  group.traverse((node) => {
    if (node === group) return;
    if (node.isMesh && !node.material.emissive?.getHex()) parts.push(node);
    else if (!node.isGroup) keep.push(node);
  });
  let count = 0;
  const pieces = parts.map((mesh) => {
    const geometry = mesh.geometry.index ? mesh.geometry.toNonIndexed() : mesh.geometry.clone();
    geometry.applyMatrix4(new THREE.Matrix4().multiplyMatrices(inverse, mesh.matrixWorld));
    count += geometry.attributes.position.count;
    return [geometry, mesh.material.color];
  });
  const position = new Float32Array(count * 3);
  const color = new Float32Array(count * 3);
  let offset = 0;
  for (const [geometry, tint] of pieces) {
    const n = geometry.attributes.position.count;
    position.set(geometry.attributes.position.array, offset * 3);
    for (let i = 0; i < n; i += 1) color.set([tint.r, tint.g, tint.b], (offset + i) * 3);
    offset += n;
    geometry.dispose();
  }
  const merged = new THREE.BufferGeometry();
  merged.setAttribute("position", new THREE.BufferAttribute(position, 3));
  merged.setAttribute("color", new THREE.BufferAttribute(color, 3));
  const out = new THREE.Group();
  out.name = group.name;
  out.position.copy(group.position);
  out.rotation.copy(group.rotation);
  if (count) out.add(new THREE.Mesh(merged, BAKED));
  for (const node of keep) {
    node.updateMatrixWorld(true);
    const placed = node.clone();
    new THREE.Matrix4().multiplyMatrices(inverse, node.matrixWorld).decompose(placed.position, placed.quaternion, placed.scale);
    out.add(placed);
  }
  return out;
}

/** Free the baked geometry of a group made by `bake` (the shared materials stay). */
export function unbake(group) {
  group.traverse((node) => {
    if (node.isMesh && node.material === BAKED) node.geometry.dispose();
  });
}

/** Colour between `a` and `b` (hex strings) at `t` in [0, 1], as a hex string. */
export function mix(a, b, t) {
  return `#${new THREE.Color(a).lerp(new THREE.Color(b), Math.min(Math.max(t, 0), 1)).getHexString()}`;
}
