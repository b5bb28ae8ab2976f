/**
 * The agents in 3D: the robot partner (an orange body on a dark base, a head with a dark visor on the side it
 * faces and an antenna, as in the top-down drawing) carrying what it holds in front of it, and the cook's
 * own hands at the bottom of the view (blue sleeves, as the top-down cook's shoulders) holding what the
 * cook holds. Both are rebuilt only when what they hold changes.
 */

import * as THREE from "../../vendor/three/three.module.js";
import { COLORS, OKABE_ITO } from "../game/palette.js";
import { bake, ball, box, cylinder } from "./kit.js";
import { itemModel } from "./items.js";

const SKIN = "#E0AC8A";

/** Grid facing → rotation about the vertical axis of a model whose front is −z. */
export const YAW = { north: 0, west: Math.PI / 2, south: Math.PI, east: -Math.PI / 2 };

function holding(group, held, x, y, z) {
  if (!held) return;
  const item = itemModel(held);
  item.position.set(x, y, z);
  item.name = `held:${held}`;
  group.add(item);
}

/** The robot, its front towards −z; rotate it by `YAW[facing]`. */
export function robotModel(held) {
  const g = new THREE.Group();
  g.name = "robot";
  cylinder(g, COLORS.visor, 0.3, 0.12, 0, 0, 0, { sides: 12 });
  box(g, COLORS.robot, 0.56, 0.62, 0.46, 0, 0.12);
  box(g, COLORS.robotEdge, 0.58, 0.05, 0.48, 0, 0.74);
  box(g, COLORS.robot, 0.46, 0.32, 0.4, 0, 0.8);
  box(g, COLORS.visor, 0.38, 0.13, 0.03, 0, 0.9, -0.205);
  for (const x of [-0.09, 0.09]) ball(g, OKABE_ITO.sky, 0.03, x, 0.965, -0.22);
  cylinder(g, COLORS.robotEdge, 0.012, 0.16, 0, 1.12, 0, { sides: 5 });
  ball(g, COLORS.robot, 0.035, 0, 1.3, 0);
  for (const x of [-0.31, 0.31]) box(g, COLORS.visor, 0.06, 0.06, 0.3, x, 0.5, -0.18);
  holding(g, held, 0, 0.56, -0.42);
  return bake(g);
}

/**
 * The cook's forearms and hands, seen from the eyes (camera space: −z ahead, y up), holding `held` low in
 * front, tilted towards the eyes so its top shows; empty hands rest at the sides.
 */
export function handsModel(held) {
  const g = new THREE.Group();
  g.name = "hands";
  const reach = held ? 0.2 : 0.3;
  for (const side of [-1, 1]) {
    const arm = new THREE.Group();
    cylinder(arm, COLORS.human, 0.045, 0.3, 0, -0.3, 0, { rTop: 0.04, sides: 8 });
    ball(arm, SKIN, 0.055, 0, 0.02, 0);
    box(arm, SKIN, 0.025, 0.06, 0.025, -side * 0.045, 0.0, -0.02);
    arm.rotation.x = -Math.PI / 2.4;
    arm.rotation.z = side * 0.35;
    arm.position.set(side * reach, -0.34, -0.5);
    g.add(arm);
  }
  if (held) {
    const item = itemModel(held);
    item.name = `held:${held}`;
    item.position.set(0, -0.3, -0.8);
    item.rotation.x = 0.6;
    item.scale.setScalar(0.7);
    g.add(item);
  }
  return bake(g);
}
