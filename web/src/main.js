// walkrad's web viewer: opens a bake folder's manifest.json, plays its walkthrough (play/pause, step,
// a time slider) or lets the user fly (WASD + mouse drag), and streams the chunks the frames ahead
// need under a memory budget (streamer.js). Colours exactly as walkrad-view draws them: COLOR_0 is
// linear radiance already exposed, interpolated, clamped to [0, 1] and sRGB-encoded in the fragment
// shader (runtime/src/renderer.cpp), with the same camera and clip planes (runtime/src/camera.cpp).
//
// URL parameters: bake=URL of the bake folder (default: this page's folder), budget=MB (10^6 bytes;
// default: none), lookahead=frames (90), fps=frames per second (30), play=1 (start playing; play=once:
// once through, then stop), frame=N (show frame N), width/height (a fixed canvas size, for tests).
// window.walkrad exposes the state and, for tests, renderFrame(i) (a still frame with its chunks).
import * as THREE from 'three';
import { ChunkStreamer } from './streamer.js';
import { chunkPriorities, chunksNeeded } from './priority.js';

const params = new URLSearchParams(location.search);
const bakeUrl = (params.get('bake') || './').replace(/\/?$/, '/');
const fps = Number(params.get('fps') || 30);
const lookahead = Number(params.get('lookahead') || 90);
const budgetBytes = Math.round(Number(params.get('budget') || 0) * 1e6);
const fixedWidth = Number(params.get('width') || 0), fixedHeight = Number(params.get('height') || 0);

const vertexShader = `precision highp float;
in vec3 position;
in vec3 color;
uniform mat4 modelViewMatrix;
uniform mat4 projectionMatrix;
out vec3 linear_color;
void main() {
  linear_color = color;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(position, 1.0);
}`;
const fragmentShader = `precision highp float;
in vec3 linear_color;
out vec4 frag_color;
vec3 srgb_encode(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
void main() {
  frag_color = vec4(srgb_encode(linear_color), 1.0);
}`;

const state = { ready: false, error: null, frame: 0, playing: false, once: false, flying: false, firstFrameMs: null,
                frameTimes: [], stats: null, done: false };
window.walkrad = state;

function fail(message) {
  state.error = message;
  document.getElementById('overlay').textContent = 'walkrad: ' + message;
  console.error('walkrad: ' + message);
}

async function main() {
  const start = performance.now();
  const response = await fetch(bakeUrl + 'manifest.json');
  if (!response.ok) return fail(`${bakeUrl}manifest.json: HTTP ${response.status}`);
  const manifest = await response.json();
  if (!Array.isArray(manifest.chunks) || !Array.isArray(manifest.viewpoints) || !manifest.bounds)
    return fail(`${bakeUrl}manifest.json: not a walkrad manifest (chunks, viewpoints, bounds)`);
  const frames = manifest.viewpoints.length;

  const canvas = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true });
  renderer.setPixelRatio(1);
  renderer.setClearColor(0x000000, 1);
  const material = new THREE.RawShaderMaterial({ vertexShader, fragmentShader, glslVersion: THREE.GLSL3,
                                                 side: THREE.DoubleSide });
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera();
  const lo = new THREE.Vector3(...manifest.bounds.min), hi = new THREE.Vector3(...manifest.bounds.max);
  const diagonal = hi.distanceTo(lo), centre = lo.clone().add(hi).multiplyScalar(0.5);

  const streamer = new ChunkStreamer(manifest, bakeUrl, { budgetBytes }, (c, meshes) => {
    for (const m of meshes) { m.material = material; m.frustumCulled = false; scene.add(m); }
  }, (c, meshes) => { for (const m of meshes) scene.remove(m); });
  state.stats = streamer.stats;
  state.missLog = streamer.missLog;

  function resize() {
    const w = fixedWidth || canvas.clientWidth || 640, h = fixedHeight || canvas.clientHeight || 480;
    if (canvas.width !== w || canvas.height !== h) renderer.setSize(w, h, !!fixedWidth);
  }

  // The camera of walkrad-view: pinhole at the viewpoint, clip planes from the scene's bounds.
  function place(position, forward, up, yfov) {
    const p = new THREE.Vector3(...position);
    camera.fov = THREE.MathUtils.radToDeg(yfov);
    camera.aspect = canvas.width / canvas.height;
    camera.near = Math.max(1e-3 * diagonal, 1e-4);
    camera.far = Math.max(4 * diagonal + centre.distanceTo(p), 2 * camera.near);
    camera.position.copy(p);
    camera.up.set(...up);
    camera.lookAt(p.clone().add(new THREE.Vector3(...forward)));
    camera.updateProjectionMatrix();
    camera.updateMatrixWorld(true);
  }
  function cameraPlace() {
    const vp = new THREE.Matrix4().multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse);
    return { position: camera.position.toArray(), pathFrame: state.flying ? null : state.frame, loop: !state.once,
             viewProjection: vp.elements };
  }
  function showFrame(i) {
    state.frame = Math.max(0, Math.min(frames - 1, i));
    const v = manifest.viewpoints[state.frame];
    place(v.position, v.forward, v.up, v.yfov);
  }

  // ---- controls: play/pause, step, slider; WASD + drag to fly, Escape back to the path ----
  const slider = document.getElementById('time');
  slider.max = String(Math.max(0, frames - 1));
  const playButton = document.getElementById('play');
  const setPlaying = (on) => { state.playing = on; playButton.textContent = on ? 'pause' : 'play'; clock = performance.now() - state.frame * 1000 / fps; };
  let clock = performance.now();
  playButton.onclick = () => { state.flying = false; setPlaying(!state.playing); };
  document.getElementById('back').onclick = () => { setPlaying(false); showFrame(state.frame - 1); };
  document.getElementById('step').onclick = () => { setPlaying(false); showFrame(state.frame + 1); };
  slider.oninput = () => { state.flying = false; setPlaying(false); showFrame(Number(slider.value)); };
  const keys = new Set();
  window.addEventListener('keydown', (e) => {
    if (e.key === 'Escape') { state.flying = false; showFrame(state.frame); return; }
    if ('wasdqe'.includes(e.key.toLowerCase())) { keys.add(e.key.toLowerCase()); state.flying = true; setPlaying(false); }
  });
  window.addEventListener('keyup', (e) => keys.delete(e.key.toLowerCase()));
  let drag = null;
  canvas.addEventListener('pointerdown', (e) => { drag = [e.clientX, e.clientY]; state.flying = true; setPlaying(false); });
  window.addEventListener('pointerup', () => { drag = null; });
  window.addEventListener('pointermove', (e) => {
    if (!drag) return;
    const [dx, dy] = [e.clientX - drag[0], e.clientY - drag[1]];
    drag = [e.clientX, e.clientY];
    camera.quaternion.multiply(new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(1, 0, 0), -dy * 0.004));
    camera.quaternion.premultiply(new THREE.Quaternion().setFromAxisAngle(camera.up, -dx * 0.004));
  });
  function fly(seconds) {
    const speed = 0.1 * diagonal * seconds, move = new THREE.Vector3();
    if (keys.has('w')) move.z -= 1;
    if (keys.has('s')) move.z += 1;
    if (keys.has('a')) move.x -= 1;
    if (keys.has('d')) move.x += 1;
    if (keys.has('e')) move.y += 1;
    if (keys.has('q')) move.y -= 1;
    camera.position.add(move.applyQuaternion(camera.quaternion).multiplyScalar(speed));
    camera.updateMatrixWorld(true);
  }

  // ---- the overlay: frame time (median of the last 60), resident bytes, loads and misses ----
  const overlay = document.getElementById('overlay');
  function drawOverlay() {
    const t = [...state.frameTimes.slice(-60)].sort((a, b) => a - b);
    const median = t.length ? t[t.length >> 1] : 0;
    const s = streamer.stats;
    overlay.textContent = `${state.flying ? 'flying' : `frame ${state.frame + 1}/${frames}`}  ` +
      `${median.toFixed(1)} ms  resident ${(s.residentBytes / 1e6).toFixed(2)}` +
      `${budgetBytes ? '/' + (budgetBytes / 1e6).toFixed(2) : ''} MB  loads ${s.loads}  misses ${s.misses}`;
    slider.value = String(state.frame);
  }

  // Frame time: from `t0` (the frame's start: the streaming update, as walkrad-view counts it) to the
  // image finished (gl.finish).
  function render(t0 = performance.now()) {
    renderer.render(scene, camera);
    const gl = renderer.getContext();
    gl.finish();
    state.frameTimes.push(performance.now() - t0);
    if (state.firstFrameMs === null && streamer.resident.size) state.firstFrameMs = performance.now() - start;
    drawOverlay();
  }

  // Frame i, still, once every chunk it needs has arrived, and those of the `preroll` frames after it
  // as far as the budget holds them (before playing: the first second must not wait). Returns how
  // many chunks frame i lacks (0 unless the budget cannot hold them).
  state.renderFrame = async (i, preroll = 0) => {
    setPlaying(false);
    state.flying = false;
    const wanted = new Set();
    for (let k = Math.min(frames - 1, i + preroll); k >= i; --k) {  // the frame itself last: it ends in place
      showFrame(k);
      for (const c of chunksNeeded(manifest, cameraPlace())) wanted.add(c);
    }
    const needed = chunksNeeded(manifest, cameraPlace());
    for (let round = 0; round < 1000 && [...wanted].some((c) => !streamer.isResident(c)); ++round) {
      streamer.update(chunkPriorities(manifest, cameraPlace(), preroll), needed);
      if (!streamer.loading.size) break;  // the budget holds no more of them
      await streamer.settle();
    }
    render();
    return needed.filter((c) => !streamer.isResident(c)).length;
  };

  resize();
  window.addEventListener('resize', resize);
  state.once = params.get('play') === 'once';
  // The first frame waits for its chunks (time to first frame); playing starts from there.
  await state.renderFrame(Number(params.get('frame') || 0), params.get('play') ? Math.round(fps) : 0);
  if (params.get('play')) setPlaying(true);
  let last = performance.now();
  function tick(now) {
    const t0 = performance.now();
    resize();
    if (state.flying) fly((now - last) / 1000);
    last = now;
    if (state.playing) {
      const f = Math.floor((now - clock) * fps / 1000);
      if (f >= frames && state.once) { setPlaying(false); state.done = true; }
      else showFrame(state.once ? f : f % frames);
    } else if (!state.flying) {
      showFrame(state.frame);
    }
    const where = cameraPlace();
    const needed = chunksNeeded(manifest, where);
    streamer.update(chunkPriorities(manifest, where, state.flying ? 0 : lookahead), needed);
    if (!state.done) {
      if (state.playing) streamer.countMisses(needed, state.frame);
      render(t0);
    }
    drawOverlay();  // loads land between frames too
    requestAnimationFrame(tick);
  }
  state.ready = true;
  requestAnimationFrame(tick);
}

main().catch((e) => fail(e.message));
