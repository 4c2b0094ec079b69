// The web viewer's test harness, shared by its test (test_web.mjs) and its benchmark
// (bench/web_viewer.mjs): Debian's chromium through playwright-core, WebGL on SwiftShader, and a page
// whose requests to http://walkrad.test/<root>/... are answered from folders on disk (no server).
import { existsSync, readFileSync } from 'node:fs';
import { extname, join } from 'node:path';
import { createRequire } from 'node:module';

const require = createRequire(import.meta.url);
const { chromium } = require('playwright-core');

const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.wasm': 'application/wasm',
                '.json': 'application/json', '.glb': 'model/gltf-binary', '.png': 'image/png' };

export async function launch(executablePath = '/usr/bin/chromium') {
  return chromium.launch({
    executablePath, headless: true,
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist', '--no-sandbox'],
  });
}

// A page of width × height CSS pixels (1 device pixel each) serving roots = {name: folder}; console
// errors and page errors are appended to `errors`.
export async function openBake(browser, roots, width, height, errors) {
  const page = await browser.newPage({ viewport: { width, height }, deviceScaleFactor: 1 });
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(e.message));
  await page.route('http://walkrad.test/**', (route) => {
    const path = decodeURIComponent(new URL(route.request().url()).pathname);
    const [, root, ...rest] = path.split('/');
    const base = roots[root];
    const file = base && join(base, ...rest);
    if (!file || !file.startsWith(base) || !existsSync(file)) return route.fulfill({ status: 404, body: 'not found' });
    return route.fulfill({ status: 200, body: readFileSync(file), contentType: types[extname(file)] || 'application/octet-stream' });
  });
  return page;
}
