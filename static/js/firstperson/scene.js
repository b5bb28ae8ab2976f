/**
 * The first-person scene graph, fed one server `state` message at a time with the top-down view's rule
 * (docs/client.md): **only the cells of the latest message are drawn**. Never-seen cells are darkness (the
 * scene has no floor or walls of its own, and its background is black); a cell seen before and out of view
 * now is hidden with everything on it, so nothing stale is ever shown. The terrain of a cell is built the
 * first time it is in view and kept (walls do not move, docs/protocol.md); its contents (object, station
 * status) are rebuilt whenever they change; the robot is drawn only when the message has it.
 */

import * as THREE from "../../vendor/three/three.module.js";
import { YAW, robotModel } from "./agents.js";
import { EYE_BACK, EYE_HEIGHT, unbake } from "./kit.js";
import { Glide, poseOf } from "./motion.js";
import { contentsKey, contentsModel, terrainModel } from "./stations.js";

function dispose(group) {
  unbake(group);
  group.traverse((node) => {
    if (node.isSprite) node.material.dispose();
  });
}

export class KitchenScene {
  constructor() {
    this.scene = new THREE.Scene();
    this.scene.background = new THREE.Color(0x000000);
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x6b5a48, 2.4));
    const sun = new THREE.DirectionalLight(0xffffff, 1.6);
    sun.position.set(-3, 8, 4);
    this.scene.add(sun);
    /** The cook's body: moves and turns with the avatar; the head carries the camera at eye height. */
    this.rig = new THREE.Group();
    this.head = new THREE.Group();
    this.head.position.set(0, EYE_HEIGHT, EYE_BACK);
    this.rig.add(this.head);
    this.scene.add(this.rig);
    this.cells = new Map();
    this.robot = null;
    this.robotHeld = undefined;
    this.you = new Glide();
    this.robotGlide = new Glide();
    this.visible = [];
    this.state = null;
  }

  /** Show the state of one tick; `now` (ms) starts the glide to the new poses over `duration` ms. */
  update(state, now, duration) {
    const shown = new Set();
    for (const c of state.cells) {
      const key = `${c.x},${c.y}`;
      shown.add(key);
      let cell = this.cells.get(key);
      if (!cell) {
        cell = { terrain: terrainModel(c.terrain, c.x, c.y), key: null, contents: null };
        this.scene.add(cell.terrain);
        this.cells.set(key, cell);
      }
      cell.terrain.visible = true;
      const signature = contentsKey(c);
      if (signature !== cell.key) {
        if (cell.contents) {
          this.scene.remove(cell.contents);
          dispose(cell.contents);
        }
        cell.contents = contentsModel(c);
        cell.key = signature;
        this.scene.add(cell.contents);
      }
      cell.contents.visible = true;
    }
    for (const [key, cell] of this.cells) {
      if (shown.has(key)) continue;
      cell.terrain.visible = false;
      if (cell.contents) cell.contents.visible = false;
    }
    this.visible = state.cells.map((c) => [c.x, c.y]);
    this.you.goTo(poseOf(state.you), now, duration);
    this.showRobot(state.robot, now, duration);
    this.state = state;
  }

  showRobot(robot, now, duration) {
    const wasSeen = Boolean(this.state && this.state.robot);
    if (!robot) {
      if (this.robot) this.robot.visible = false;
      return;
    }
    if (!this.robot || this.robotHeld !== robot.held) {
      if (this.robot) {
        this.scene.remove(this.robot);
        unbake(this.robot);
      }
      this.robot = robotModel(robot.held);
      this.robotHeld = robot.held;
      this.scene.add(this.robot);
    }
    this.robot.visible = true;
    if (wasSeen) this.robotGlide.goTo(poseOf(robot), now, duration);
    else this.robotGlide.snap(poseOf(robot));
  }

  /** Place the cook and the robot where they are drawn at time `now`; true while either still glides. */
  pose(now) {
    const you = this.you.at(now);
    if (you) {
      this.rig.position.set(you.x, 0, you.z);
      this.rig.rotation.y = you.yaw;
    }
    const robot = this.robot && this.robot.visible ? this.robotGlide.at(now) : null;
    if (robot) {
      this.robot.position.set(robot.x, 0, robot.z);
      this.robot.rotation.y = robot.yaw;
    }
    return this.you.moving(now) || Boolean(robot && this.robotGlide.moving(now));
  }

  /** The yaw the cook faces in the latest state (for tests and the XR rig). */
  facingYaw() {
    return this.state ? YAW[this.state.you.facing] : 0;
  }

  /** The cells drawn now, as "x,y" in reading order (what the canvas's data-drawn attribute lists). */
  drawnCells() {
    return [...this.cells.entries()].filter(([, c]) => c.terrain.visible).map(([k]) => k.split(",").map(Number))
      .sort((a, b) => a[1] - b[1] || a[0] - b[0]).map(([x, y]) => `${x},${y}`);
  }
}
