// The web viewer beside walkrad-view: time to first frame and frame
// times playing a bake's whole path once at 30 frames/s, no budget, at one size. walkrad-view runs
// headless on Mesa (its stats.json); the web viewer in Debian's chromium on SwiftShader
// (web/test/harness.mjs), after `walkrad web` on a copy of the bake. Both times are CPU rendering.
// Usage: node bench/web_viewer.mjs WALKRAD WALKRAD_VIEW BAKE_DIR WORK_DIR [WIDTH HEIGHT]   (960 × 640)
import { execFileSync } from 'node:child_process';
import { cpSync, readFileSync, rmSync } from 'node:fs';
import { join, resolve } from 'node:path';
import { launch, openBake } from '../web/test/harness.mjs';

const [walkrad, view, bake, work] = process.argv.slice(2, 6).map((p) => resolve(p));
const width = Number(process.argv[6] || 960), height = Number(process.argv[7] || 640);
rmSync(work, { recursive: true, force: true });
const served = join(work, 'bake');
cpSync(bake, served, { recursive: true });
execFileSync(walkrad, ['web', served], { stdio: 'ignore' });

const frames = join(work, 'frames');
execFileSync(view, [bake, '--headless', '--frames', frames, '--width', String(width), '--height', String(height), '--fps', '30'],
             { stdio: 'ignore' });
const native = JSON.parse(readFileSync(join(frames, 'stats.json'), 'utf8'));

const browser = await launch();
const errors = [];
const page = await openBake(browser, { bake: served }, width, height, errors);
const started = Date.now();
await page.goto(`http://walkrad.test/bake/index.html?width=${width}&height=${height}&play=once&fps=30`);
await page.waitForFunction(() => window.walkrad && (window.walkrad.done || window.walkrad.error), null, { timeout: 300000, polling: 100 });
const web = await page.evaluate(() => ({ first: window.walkrad.firstFrameMs, times: window.walkrad.frameTimes, stats: window.walkrad.stats }));
const wall = (Date.now() - started) / 1000;
await browser.close();

const quantile = (values, q) => { const t = [...values].sort((a, b) => a - b); return t[Math.min(t.length - 1, Math.floor(q * t.length))]; };
const native_times = native.frame_cpu_ms.each;
console.log(`${bake}, ${width} × ${height}, ${native.frames} path frames, the path played once at 30 frames/s, no budget`);
console.log('| viewer | renderer | time to first frame (ms) | frames drawn | frame time median (ms) | 90th percentile (ms) | max (ms) |');
console.log('| --- | --- | --- | --- | --- | --- | --- |');
console.log(`| walkrad-view --headless | ${native.renderer} | ${native.time_to_first_frame_ms.toFixed(0)} | ${native_times.length} | ` +
            `${quantile(native_times, 0.5).toFixed(2)} | ${quantile(native_times, 0.9).toFixed(2)} | ${Math.max(...native_times).toFixed(2)} |`);
console.log(`| web viewer (Chromium) | SwiftShader (WebGL 2) | ${web.first.toFixed(0)} | ${web.times.length} | ` +
            `${quantile(web.times, 0.5).toFixed(2)} | ${quantile(web.times, 0.9).toFixed(2)} | ${Math.max(...web.times).toFixed(2)} |`);
console.log(`web: ${JSON.stringify(web.stats)}, page ${wall.toFixed(1)} s${errors.length ? ', errors: ' + errors.join(' | ') : ''}`);
