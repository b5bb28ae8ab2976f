/**
 * The first-person camera's lens. Its horizontal field of view is the study's `fov_angle`, so the screen's
 * left and right edges are the edges of the participant's field of view (docs/domain.md §2).
 *
 * - Up to `RECTILINEAR_LIMIT` (100°) an ordinary perspective (rectilinear) camera: straight lines stay
 *   straight, and the stretch at the edges (1 / cos² of half the angle: 2.4× at 100°) stays tolerable.
 * - Wider (the paper's 120° and up to 360°) a rectilinear camera would stretch the edges without bound (4× at
 *   120°, infinite at 180°). Instead the view is a **cylindrical projection**: the scene is rendered in
 *   `slices` narrow perspective views (each at most 90° wide) side by side into one texture, and a
 *   full-screen pass maps every screen column to an azimuth (linear in angle, like a panorama) and every row
 *   to a height on the cylinder. Vertical lines stay vertical and straight, the scale is the same across
 *   the width, and nothing bulges like a fisheye; horizontal lines far from the horizon curve gently, as in
 *   any panorama.
 *
 * Vertically the horizon sits at `HORIZON` (25 %) from the top, so the counter in front of the cook and what
 * lies on it are in view (its top centre is 24° below the eyes, kit.js); a lens too narrow for that (below
 * about 58°) is pitched down just enough, and then its side edges are no longer exactly the field of view's
 * vertical edges (they tilt with the pitch: a few per cent of the width more is shown at the eye line).
 */

export const RECTILINEAR_LIMIT = 100;
export const HORIZON = 0.25;
const SLICE_MAX = 90;
const MIN_DOWN = (25 * Math.PI) / 180;

const rad = (deg) => (deg * Math.PI) / 180;

/**
 * The lens for a horizontal field of view of `fov` degrees on a viewport of `aspect` (width / height).
 * Rectilinear: `{kind, left, right, top, bottom, pitch}` (frustum edges at distance 1, pitch in radians).
 * Cylindrical: `{kind, fov, slices, slice, up, down, sliceTop, sliceBottom, halfTan}` (angles in radians,
 * heights on the unit cylinder).
 */
export function lensFor(fov, aspect) {
  const angle = Math.min(Math.max(fov, 1), 360);
  if (angle <= RECTILINEAR_LIMIT) {
    const half = Math.tan(rad(angle) / 2);
    const total = (2 * half) / aspect;
    const up = HORIZON * total;
    const down = total - up;
    const pitch = Math.max(0, MIN_DOWN - Math.atan(down));
    return { kind: "rectilinear", left: -half, right: half, top: up, bottom: -down, pitch };
  }
  const width = rad(angle);
  const slices = Math.ceil(angle / SLICE_MAX);
  const slice = width / slices;
  const total = width / aspect;
  const up = HORIZON * total;
  const down = total - up;
  const edge = Math.cos(slice / 2);
  return { kind: "cylindrical", fov: width, slices, slice, up, down, sliceTop: up / edge, sliceBottom: -down / edge,
           halfTan: Math.tan(slice / 2) };
}

/**
 * Where a direction lands on the screen of a lens: `azimuth` (radians, positive to the right of the facing)
 * and `elevation` (radians, positive up) → `[u, v]` in [0, 1] from the left and from the bottom, or null
 * outside the view. The tests use it to check that the screen's edges are the field of view's.
 */
export function screenOf(lens, azimuth, elevation) {
  if (lens.kind === "rectilinear") {
    // The direction in the camera's frame (pitched down by lens.pitch), then its perspective projection.
    const [c, s] = [Math.cos(lens.pitch), Math.sin(lens.pitch)];
    const ahead = Math.cos(azimuth) * Math.cos(elevation);
    const depth = c * ahead - s * Math.sin(elevation);
    if (depth <= 0) return null;
    const x = (Math.sin(azimuth) * Math.cos(elevation)) / depth;
    const y = (c * Math.sin(elevation) + s * ahead) / depth;
    const u = (x - lens.left) / (lens.right - lens.left);
    const v = (y - lens.bottom) / (lens.top - lens.bottom);
    return u < 0 || u > 1 || v < 0 || v > 1 ? null : [u, v];
  }
  const u = azimuth / lens.fov + 0.5;
  const v = (Math.tan(elevation) + lens.down) / (lens.up + lens.down);
  return u < 0 || u > 1 || v < 0 || v > 1 ? null : [u, v];
}
