/**
 * The objects of the kitchen in 3D (planner/objects.py): onion, raw meat, dirty plate, clean plate, plated
 * steak and the finished dish, plus the chopped-onion garnish and a steak that darkens as it cooks. Each
 * model stands on the origin (its base at y = 0) and fits a disc of radius about 0.25, so the same model
 * sits on a counter, in a robot's grip or in the cook's hands. Colours and silhouettes follow the top-down
 * drawings (game/items.js): purple onion with a green sprout, red meat with a fat stripe, white plates
 * with brown spots (dirty) or a blue rim (clean).
 */

import * as THREE from "../../vendor/three/three.module.js";
import { COLORS } from "../game/palette.js";
import { ball, box, cylinder, mix } from "./kit.js";

const PLATE_H = 0.035;

export function onion(group, x = 0, z = 0, y = 0) {
  ball(group, COLORS.onion, 0.11, x, y + 0.1, z);
  cylinder(group, COLORS.garnish, 0.015, 0.07, x, y + 0.19, z, { rTop: 0.004, sides: 5 });
}

export function meat(group, x = 0, z = 0, y = 0, cooked = 0) {
  const color = mix(COLORS.meatRaw, COLORS.meatCooked, cooked);
  box(group, color, 0.3, 0.06, 0.2, x, y, z);
  box(group, COLORS.fat, 0.3, 0.012, 0.03, x, y + 0.06, z + 0.05);
}

function plate(group, rim, x, z, y) {
  cylinder(group, COLORS.plate, 0.2, PLATE_H, x, y, z, { rTop: 0.23, sides: 14 });
  cylinder(group, rim, 0.232, 0.008, x, y + PLATE_H, z, { sides: 14 });
  cylinder(group, COLORS.plate, 0.17, 0.01, x, y + PLATE_H, z, { sides: 14 });
}

export function dirtyPlate(group, x = 0, z = 0, y = 0) {
  plate(group, COLORS.plateRim, x, z, y);
  for (const [dx, dz] of [[-0.08, 0.03], [0.06, -0.07], [0.04, 0.09]]) {
    cylinder(group, COLORS.dirt, 0.035, 0.006, x + dx, y + PLATE_H + 0.01, z + dz, { sides: 6 });
  }
}

export function cleanPlate(group, x = 0, z = 0, y = 0) {
  plate(group, COLORS.cleanRim, x, z, y);
}

export function garnish(group, x = 0, z = 0, y = 0) {
  for (const [dx, dz] of [[-0.05, -0.03], [0.04, -0.05], [0.0, 0.04], [0.06, 0.04], [-0.06, 0.05]]) {
    box(group, COLORS.onion, 0.045, 0.03, 0.045, x + dx, y, z + dz);
  }
}

export function steakPlate(group, x = 0, z = 0, y = 0) {
  cleanPlate(group, x, z, y);
  meat(group, x, z, y + PLATE_H + 0.01, 1);
}

export function dish(group, x = 0, z = 0, y = 0) {
  steakPlate(group, x, z, y);
  garnish(group, x + 0.03, z - 0.02, y + PLATE_H + 0.08);
}

export const ITEMS = {
  onion,
  meat,
  dirty_plate: dirtyPlate,
  clean_plate: cleanPlate,
  steak_plate: steakPlate,
  dish,
};

/** A group holding the model of `kind` (an unknown kind becomes a grey box, never nothing). */
export function itemModel(kind) {
  const group = new THREE.Group();
  group.name = `item:${kind}`;
  (ITEMS[kind] || ((g) => box(g, "#888888", 0.2, 0.2, 0.2)))(group);
  return group;
}
