// Chunk priority, as walkrad-view computes it (runtime/include/walkrad/runtime/chunk_priority.h):
// which chunks the camera needs now and which it will need soon, from the manifest alone.
//
// On the walkthrough, a chunk's importance for a viewpoint is the fraction of that viewpoint's image it
// covers (the manifest's per-viewpoint coverage), widened to the largest over the frames just before
// and after. At frame i, looking L frames ahead, let k be the first k = 0..L with importance > 0:
//   p(c) = (L + 1 − k + importance / 2) / (L + 1)  +  1e-7 / (1 + d(c))
// and p(c) = 1e-7 / (1 + d(c)) when no frame ahead sees it (d: the camera's distance to the chunk's
// bounds). Off the path (free flight): p(c) = (in the view frustum ? 1 : 1/4) / (1 + d(c)).

const kDistanceWeight = 1e-7;
const kOutsideFrustumWeight = 0.25;

function importanceAt(chunk, frame) {
  let most = 0;
  for (let f = Math.max(0, frame - 1); f <= frame + 1; ++f)
    if (f < chunk.importance.length) most = Math.max(most, chunk.importance[f]);
  return most;
}

export function distanceToBounds(p, b) {
  const d = [0, 1, 2].map((a) => Math.max(b.min[a] - p[a], 0, p[a] - b.max[a]));
  return Math.hypot(d[0], d[1], d[2]);
}

// Conservative: false only when all 8 corners lie outside one plane of the frustum. viewProjection is
// a column-major 4×4 (three.js Matrix4.elements).
export function boundsInFrustum(viewProjection, box) {
  const m = viewProjection;
  const outside = [0, 0, 0, 0, 0, 0];
  for (let corner = 0; corner < 8; ++corner) {
    const p = [corner & 1 ? box.max[0] : box.min[0], corner & 2 ? box.max[1] : box.min[1], corner & 4 ? box.max[2] : box.min[2]];
    const c = [0, 1, 2, 3].map((r) => m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r]);
    for (let a = 0; a < 3; ++a) {
      if (c[a] < -c[3]) ++outside[2 * a];
      if (c[a] > c[3]) ++outside[2 * a + 1];
    }
  }
  return !outside.some((n) => n === 8);
}

// camera: {position: [x,y,z], pathFrame: index or null, loop: bool, viewProjection: for free flight}.
export function chunkPriorities(manifest, camera, lookahead) {
  const frames = manifest.viewpoints.length;
  return manifest.chunks.map((chunk) => {
    const near = 1 / (1 + distanceToBounds(camera.position, chunk.bounds));
    if (camera.pathFrame === null || camera.pathFrame >= frames)
      return (boundsInFrustum(camera.viewProjection, chunk.bounds) ? 1 : kOutsideFrustumWeight) * near;
    let ahead = 0;
    for (let k = 0; k <= lookahead; ++k) {
      let frame = camera.pathFrame + k;
      if (frame >= frames) {
        if (!camera.loop) break;
        frame %= frames;
      }
      const importance = importanceAt(chunk, frame);
      if (importance > 0) {
        ahead = (lookahead + 1 - k + 0.5 * Math.min(importance, 1)) / (lookahead + 1);
        break;
      }
    }
    return ahead + kDistanceWeight * near;
  });
}

// The chunks a frame cannot do without: on the path, those its viewpoint (or a neighbour) sees; off
// it, those whose bounds meet the frustum.
export function chunksNeeded(manifest, camera) {
  const onPath = camera.pathFrame !== null && camera.pathFrame < manifest.viewpoints.length;
  const needed = [];
  manifest.chunks.forEach((chunk, c) => {
    if (onPath ? importanceAt(chunk, camera.pathFrame) > 0 : boundsInFrustum(camera.viewProjection, chunk.bounds)) needed.push(c);
  });
  return needed;
}
