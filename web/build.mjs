// Builds the web viewer into one folder (default: ./dist, or the first argument): index.html, the
// viewer and three.js bundled into walkrad-viewer.js (esbuild), and three.js's Draco decoder
// (draco/). Nothing is fetched at run time: `walkrad web BAKE` copies this folder into a bake.
import { build } from 'esbuild';
import { copyFileSync, mkdirSync, rmSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const out = resolve(process.argv[2] || join(here, 'dist'));
rmSync(out, { recursive: true, force: true });
mkdirSync(join(out, 'draco'), { recursive: true });
await build({
  entryPoints: [join(here, 'src/main.js')],
  bundle: true,
  format: 'esm',
  minify: true,
  legalComments: 'eof',
  outfile: join(out, 'walkrad-viewer.js'),
  logLevel: 'warning',
});
copyFileSync(join(here, 'index.html'), join(out, 'index.html'));
const draco = join(here, 'node_modules/three/examples/jsm/libs/draco/gltf');
for (const f of ['draco_decoder.wasm', 'draco_wasm_wrapper.js']) copyFileSync(join(draco, f), join(out, 'draco', f));
console.log(`walkrad web viewer built in ${out}`);
