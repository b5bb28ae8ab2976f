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

/** Colour between `a` and `b` (hex strings) at `t` in [0, 1], as a hex string. */
export function mix(a, b, t) {
  return `#${new THREE.Color(a).lerp(new THREE.Color(b), Math.min(Math.max(t, 0), 1)).getHexString()}`;
}
