/**
 * Drawing the kitchen scene through the cook's eyes with the lens of lens.js: one perspective render for a
 * rectilinear lens, or the slices and the cylindrical resampling pass for a wide one; then the cook's hands
 * on top (their own little scene and camera, so they never hide the counter in front).
 */

import * as THREE from "../../vendor/three/three.module.js";
import { unbake } from "./kit.js";
import { lensFor } from "./lens.js";

const NEAR = 0.05;
const FAR = 80;
/** Pixels of the slices per screen pixel at the centre: 0.75 draws about 0.7× the screen's pixels for the
 * two slices of 120° (the resampling pass smooths the difference), where 1.0 would draw 1.3×. */
const SLICE_SCALE = 0.75;

const RESAMPLE = `
  uniform sampler2D map;
  uniform float fov, up, down, slices, slice, halfTan, sliceTop, sliceBottom;
  varying vec2 vUv;
  void main() {
    float azimuth = (vUv.x - 0.5) * fov;
    float height = mix(-down, up, vUv.y);
    float k = clamp(floor((azimuth + 0.5 * fov) / slice), 0.0, slices - 1.0);
    float local = azimuth - (-0.5 * fov + (k + 0.5) * slice);
    float u = 0.5 + 0.5 * tan(local) / halfTan;
    float v = (height / cos(local) - sliceBottom) / (sliceTop - sliceBottom);
    gl_FragColor = texture2D(map, vec2((k + clamp(u, 0.0, 1.0)) / slices, v));
    #include <colorspace_fragment>
  }`;

const PASS_VERTEX = `
  varying vec2 vUv;
  void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }`;

function frustum(camera, left, right, top, bottom) {
  camera.projectionMatrix.makePerspective(left * NEAR, right * NEAR, top * NEAR, bottom * NEAR, NEAR, FAR);
  camera.projectionMatrixInverse.copy(camera.projectionMatrix).invert();
}

export class EyeCamera {
  /** `head`: the group at the cook's eyes (the camera is its child, looking along its −z). */
  constructor(head) {
    this.camera = new THREE.PerspectiveCamera(70, 1, NEAR, FAR);
    this.slicer = new THREE.PerspectiveCamera(70, 1, NEAR, FAR);
    head.add(this.camera, this.slicer);
    this.target = null;
    this.pass = null;
    this.lens = null;
    this.hands = new THREE.Scene();
    this.hands.add(new THREE.HemisphereLight(0xffffff, 0x6b5a48, 2.6));
    const light = new THREE.DirectionalLight(0xffffff, 1.2);
    light.position.set(-1, 2, 1);
    this.hands.add(light);
    this.handsCamera = new THREE.PerspectiveCamera(62, 1, 0.05, 5);
    this.held = null;
  }

  /** Set up the lens for a horizontal field of view of `fov` degrees on `width` × `height` device pixels. */
  configure(fov, width, height) {
    const lens = lensFor(fov, width / height);
    this.lens = lens;
    this.handsCamera.aspect = width / height;
    this.handsCamera.updateProjectionMatrix();
    if (lens.kind === "rectilinear") {
      frustum(this.camera, lens.left, lens.right, lens.top, lens.bottom);
      this.camera.position.set(0, 0, 0);
      this.camera.rotation.set(-lens.pitch, 0, 0);
      this.freeTarget();
      return lens;
    }
    frustum(this.slicer, -lens.halfTan, lens.halfTan, lens.sliceTop, lens.sliceBottom);
    const perRadian = (SLICE_SCALE * width) / lens.fov;
    const sliceW = Math.max(16, Math.round(perRadian * 2 * lens.halfTan));
    const sliceH = Math.max(16, Math.round(perRadian * (lens.sliceTop - lens.sliceBottom)));
    this.freeTarget();
    this.target = new THREE.WebGLRenderTarget(sliceW * lens.slices, sliceH, { depthBuffer: true });
    this.sliceSize = [sliceW, sliceH];
    const material = new THREE.ShaderMaterial({
      vertexShader: PASS_VERTEX, fragmentShader: RESAMPLE, depthTest: false, depthWrite: false,
      uniforms: {
        map: { value: this.target.texture }, fov: { value: lens.fov }, up: { value: lens.up },
        down: { value: lens.down }, slices: { value: lens.slices }, slice: { value: lens.slice },
        halfTan: { value: lens.halfTan }, sliceTop: { value: lens.sliceTop }, sliceBottom: { value: lens.sliceBottom },
      },
    });
    const quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), material);
    quad.frustumCulled = false;
    this.pass = { scene: new THREE.Scene(), camera: new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1), quad };
    this.pass.scene.add(quad);
    return lens;
  }

  freeTarget() {
    if (this.target) this.target.dispose();
    if (this.pass) {
      this.pass.quad.geometry.dispose();
      this.pass.quad.material.dispose();
    }
    this.target = null;
    this.pass = null;
  }

  /** Show `model` (a group in camera space, or null) as the cook's hands. */
  setHands(model) {
    if (this.held) {
      this.hands.remove(this.held);
      unbake(this.held);
    }
    this.held = model;
    if (model) this.hands.add(model);
  }

  /** Draw one frame of `scene` to the canvas. */
  render(renderer, scene) {
    renderer.autoClear = true;
    if (this.lens.kind === "rectilinear") {
      renderer.setRenderTarget(null);
      renderer.render(scene, this.camera);
    } else {
      const [w, h] = this.sliceSize;
      const { slices, slice, fov } = this.lens;
      for (let k = 0; k < slices; k += 1) {
        this.slicer.rotation.set(0, -(-fov / 2 + (k + 0.5) * slice), 0);
        this.slicer.updateMatrixWorld();
        this.target.viewport.set(k * w, 0, w, h);
        this.target.scissor.set(k * w, 0, w, h);
        this.target.scissorTest = true;
        renderer.setRenderTarget(this.target);
        renderer.render(scene, this.slicer);
      }
      renderer.setRenderTarget(null);
      renderer.render(this.pass.scene, this.pass.camera);
    }
    if (this.held) {
      renderer.autoClear = false;
      renderer.clearDepth();
      renderer.render(this.hands, this.handsCamera);
      renderer.autoClear = true;
    }
  }

  dispose() {
    this.freeTarget();
  }
}
