// The chunk cache: keeps the chunks the walkthrough needs resident under a memory budget, as
// walkrad-view's ChunkCache does. Each update ranks the chunks (priority.js); the most useful missing
// ones are fetched and decoded (GLTFLoader + DRACOLoader, the decoder in a worker) while the budget
// allows, evicting resident chunks that are less useful than the one coming in, never one the current
// frame needs. Resident bytes are counted as the chunk files' bytes (the manifest's `bytes`), so that
// a budget reads against the bake's size on disk.
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { DRACOLoader } from 'three/examples/jsm/loaders/DRACOLoader.js';

export class ChunkStreamer {
  // budgetBytes: 0 for no limit. onLoaded(index, meshes) / onEvicted(index, meshes) place them in the scene.
  constructor(manifest, baseUrl, { budgetBytes = 0, inFlight = 4, dracoPath = './draco/' } = {}, onLoaded, onEvicted) {
    this.manifest = manifest;
    this.baseUrl = baseUrl;
    this.budget = budgetBytes;
    this.maxInFlight = inFlight;
    this.onLoaded = onLoaded;
    this.onEvicted = onEvicted;
    this.resident = new Map();  // chunk index → meshes
    this.loading = new Set();
    this.stats = { loads: 0, evictions: 0, misses: 0, residentBytes: 0, maxResidentBytes: 0, loadErrors: 0 };
    this.missLog = [];
    const draco = new DRACOLoader();
    draco.setDecoderPath(dracoPath);
    draco.setDecoderConfig({ type: 'wasm' });
    this.loader = new GLTFLoader();
    this.loader.setDRACOLoader(draco);
  }

  bytes(c) { return this.manifest.chunks[c].bytes; }
  isResident(c) { return this.resident.has(c); }
  fits(extra) { return this.budget <= 0 || this.stats.residentBytes + this.pendingBytes() + extra <= this.budget; }
  pendingBytes() { let b = 0; for (const c of this.loading) b += this.bytes(c); return b; }

  // Counts the needed chunks that are not resident: what this frame draws without. The first few are
  // logged (frame, chunk, whether it was on its way) for whoever investigates.
  countMisses(needed, frame) {
    let missing = 0;
    for (const c of needed) {
      if (this.resident.has(c)) continue;
      ++missing;
      if (this.missLog.length < 20) this.missLog.push({ frame, chunk: c, loading: this.loading.has(c) });
    }
    this.stats.misses += missing;
    return missing;
  }

  // priorities: one per chunk (larger first); needed: chunks the current frame cannot do without.
  update(priorities, needed) {
    const keep = new Set(needed);
    const order = priorities.map((p, c) => [p, c]).sort((a, b) => b[0] - a[0] || a[1] - b[1]);
    for (const [p, c] of order) {
      if (this.loading.size >= this.maxInFlight) break;
      if (this.resident.has(c) || this.loading.has(c)) continue;
      if (!this.fits(this.bytes(c))) {
        // Evict the least useful resident chunks that rank below this one.
        const victims = [...this.resident.keys()].filter((r) => !keep.has(r) && priorities[r] < p)
          .sort((a, b) => priorities[a] - priorities[b] || b - a);
        while (!this.fits(this.bytes(c)) && victims.length) this.evict(victims.shift());
        if (!this.fits(this.bytes(c))) break;  // what is left is more useful: wait
      }
      this.load(c);
    }
  }

  evict(c) {
    const meshes = this.resident.get(c);
    this.resident.delete(c);
    this.stats.residentBytes -= this.bytes(c);
    this.stats.evictions += 1;
    this.onEvicted(c, meshes);
    for (const m of meshes) m.geometry.dispose();
  }

  async load(c) {
    this.loading.add(c);
    try {
      const response = await fetch(this.baseUrl + this.manifest.chunks[c].file);
      if (!response.ok) throw new Error(`${this.manifest.chunks[c].file}: HTTP ${response.status}`);
      const gltf = await this.loader.parseAsync(await response.arrayBuffer(), this.baseUrl);
      const meshes = [];
      gltf.scene.updateMatrixWorld(true);
      gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
      this.loading.delete(c);
      this.resident.set(c, meshes);
      this.stats.loads += 1;
      this.stats.residentBytes += this.bytes(c);
      this.stats.maxResidentBytes = Math.max(this.stats.maxResidentBytes, this.stats.residentBytes);
      this.onLoaded(c, meshes);
    } catch (e) {
      this.loading.delete(c);
      this.stats.loadErrors += 1;
      console.error(`walkrad: chunk ${c}: ${e.message}`);
    }
  }

  // Resolves when nothing is loading (for a still frame: every needed chunk asked for has arrived).
  async settle() {
    while (this.loading.size) await new Promise((r) => setTimeout(r, 5));
  }
}
