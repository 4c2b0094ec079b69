// The web viewer in headless Chromium: Debian's chromium driven by playwright-core, WebGL
// on SwiftShader, every file served from disk through the page's routes (no server, no network).
// For each bake given:
//  - no console error and no page error;
//  - the manifest's viewpoints (every one up to 60, else 60 spread along the path) drawn by the viewer
//    are compared with walkrad-view's headless frames of the same viewpoints and size: the mean
//    absolute difference per channel is at most 2/255.
// With --stream BAKE: the path plays once in real time at 30 frames/s with a budget of half the
// bake's chunk bytes: no chunk missed, the budget never exceeded, chunks evicted (the budget binds).
// Prints time to first frame and frame times (docs/performance.md).
// Each bake is first copied into WORK_DIR and given the viewer by `walkrad web` (what a user serves).
// Usage: node test_web.mjs WALKRAD WALKRAD_VIEW WORK_DIR [--stream] BAKE_DIR... [--chromium PATH]
import { execFileSync } from 'node:child_process';
import { cpSync, existsSync, mkdirSync, readFileSync, rmSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { launch, openBake } from './harness.mjs';

const args = process.argv.slice(2);
let executablePath = '/usr/bin/chromium';
const at = args.indexOf('--chromium');
if (at >= 0) executablePath = args.splice(at, 2)[1];
const [walkrad, walkradView, work] = args.slice(0, 3).map((p) => resolve(p));
const bakes = [];
for (let i = 3; i < args.length; ++i)
  if (args[i] === '--stream') bakes.push({ dir: resolve(args[++i]), stream: true });
  else bakes.push({ dir: resolve(args[i]), stream: false });
if (!bakes.length) {
  console.error('usage: node test_web.mjs WALKRAD WALKRAD_VIEW WORK_DIR [--stream] BAKE_DIR...');
  process.exit(2);
}
if (!existsSync(executablePath)) {
  console.error(`test_web: ${executablePath} is missing: scripts/install-deps.sh installs Debian's chromium`);
  process.exit(1);
}
rmSync(work, { recursive: true, force: true });
mkdirSync(work, { recursive: true });

const WIDTH = 192, HEIGHT = 128, LIMIT = 2 / 255;
const failures = [];
const check = (ok, message) => { if (!ok) failures.push(message); };

const browser = await launch(executablePath);
try {
  for (const [n, bake] of bakes.entries()) {
    const name = `bake${n}`;
    const served = join(work, name);
    cpSync(bake.dir, served, { recursive: true });
    execFileSync(walkrad, ['web', served], { stdio: 'ignore' });
    const manifest = JSON.parse(readFileSync(join(bake.dir, 'manifest.json'), 'utf8'));
    const frames = join(work, `${name}-frames`);
    execFileSync(walkradView, [bake.dir, '--headless', '--frames', frames, '--width', String(WIDTH), '--height', String(HEIGHT)],
                 { stdio: 'ignore' });
    const errors = [];
    const page = await openBake(browser, { bake: served, frames }, WIDTH, HEIGHT, errors);

    // Viewpoints, still, against walkrad-view's frame: every one up to 60, else 60 spread evenly along
    // the path (the office's 240 took 68 s of a CI budget; the renderer is the same at every camera).
    await page.goto(`http://walkrad.test/bake/index.html?width=${WIDTH}&height=${HEIGHT}`);
    await page.waitForFunction(() => window.walkrad && (window.walkrad.ready || window.walkrad.error), null, { timeout: 60000 });
    let worst = 0, worstFrame = -1, sum = 0;
    const count = manifest.viewpoints.length, step = Math.ceil(count / 60);
    let compared = 0;
    for (let i = 0; i < count; i += step, ++compared) {
      const reference = `/frames/frame-${String(i).padStart(5, '0')}.png`;
      const d = await page.evaluate(async ([i, reference]) => {
        const missing = await window.walkrad.renderFrame(i);
        const gl = document.getElementById('view');
        const bitmap = await createImageBitmap(await (await fetch(reference)).blob(),
                                               { colorSpaceConversion: 'none', premultiplyAlpha: 'none' });
        const read = (source) => {
          const c = new OffscreenCanvas(gl.width, gl.height);
          const x = c.getContext('2d');
          x.drawImage(source, 0, 0);
          return x.getImageData(0, 0, gl.width, gl.height).data;
        };
        const a = read(gl), b = read(bitmap);
        const total = [0, 0, 0];
        for (let p = 0; p < a.length; p += 4) for (let k = 0; k < 3; ++k) total[k] += Math.abs(a[p + k] - b[p + k]);
        return { missing, mean: total.map((t) => t / (a.length / 4) / 255), size: [bitmap.width, bitmap.height, gl.width, gl.height] };
      }, [i, reference]);
      check(d.size[0] === d.size[2] && d.size[1] === d.size[3], `${bake.dir} frame ${i}: sizes ${d.size}`);
      check(d.missing === 0, `${bake.dir} frame ${i}: ${d.missing} chunks missing`);
      const m = Math.max(...d.mean);
      sum += m;
      if (m > worst) { worst = m; worstFrame = i; }
      check(m <= LIMIT, `${bake.dir} frame ${i}: mean absolute difference ${(m * 255).toFixed(3)}/255 > 2/255`);
    }
    console.log(`${bake.dir}: ${compared} of ${count} viewpoints, mean absolute difference per channel: ` +
                `mean ${(sum / compared * 255).toFixed(3)}/255, ` +
                `worst ${(worst * 255).toFixed(3)}/255 (frame ${worstFrame})`);

    if (bake.stream) {
      const bytes = manifest.chunks.reduce((s, c) => s + c.bytes, 0);
      const budget = bytes / 2;
      await page.goto(`http://walkrad.test/bake/index.html?width=${WIDTH}&height=${HEIGHT}` +
                      `&budget=${budget / 1e6}&play=once&fps=30`);
      await page.waitForFunction(() => window.walkrad && (window.walkrad.done || window.walkrad.error), null,
                                 { timeout: 120000, polling: 100 });
      await page.waitForTimeout(500);  // loads in flight land, the overlay catches up
      const r = await page.evaluate(() => ({ stats: window.walkrad.stats, misses: window.walkrad.missLog, first: window.walkrad.firstFrameMs,
                                             times: window.walkrad.frameTimes,
                                             overlay: document.getElementById('overlay').textContent }));
      // What the user reads: the overlay's counters.
      const shown = /loads (\d+)\s+misses (\d+)/.exec(r.overlay);
      check(shown && Number(shown[1]) === r.stats.loads && Number(shown[2]) === r.stats.misses,
            `streaming: the overlay says '${r.overlay}', the counters ${JSON.stringify(r.stats)}`);
      console.log(`overlay: ${r.overlay}`);
      const t = [...r.times].sort((a, b) => a - b);
      const q = (f) => t[Math.min(t.length - 1, Math.floor(f * t.length))];
      console.log(`stream: budget ${(budget / 1e6).toFixed(3)} MB of ${(bytes / 1e6).toFixed(3)} MB; ${JSON.stringify(r.stats)}; ` +
                  `first frame ${r.first.toFixed(0)} ms; frame times (${t.length}) median ${q(0.5).toFixed(2)} ms, ` +
                  `90th ${q(0.9).toFixed(2)} ms`);
      check(r.stats.misses === 0, `streaming: ${r.stats.misses} chunk misses: ${JSON.stringify(r.misses)}`);
      check(r.stats.maxResidentBytes <= budget, `streaming: ${r.stats.maxResidentBytes} B resident, over the budget ${budget}`);
      check(r.stats.evictions > 0, 'streaming: no chunk evicted: the budget does not bind');
      check(r.stats.loadErrors === 0, `streaming: ${r.stats.loadErrors} chunks failed to load`);
    }
    check(errors.length === 0, `${bake.dir}: console errors: ${errors.slice(0, 5).join(' | ')}`);
    await page.close();
  }
} finally {
  await browser.close();
}
for (const f of failures.slice(0, 40)) console.log('FAIL:', f);
process.exit(failures.length ? 1 : 0);
