// `exemplar studio` end to end in Debian's Chromium, driven by playwright-core (docs/studio.md,
// "Tests"): upload an exemplar (file picker, drag and drop, a refused fake), paint two strokes
// with the mouse and compare the server's painting with a stored reference, pick a line feature
// and brush with it, sketch a stroke and cycle/accept/undo its suggestions, start a job and
// cancel it, run a noisy frame, three animate frames, three noisy frames of them, fluid targets
// and frames, three npr frames and three more with a paper and the bidirectional loop, run
// StyLit and paint over its
// exemplar (the result follows),
// then stop the server with SIGINT while a job runs.
//
// Run by ctest (Browser.Studio) with EXEMPLAR_CLI set to the built command; by hand:
//   EXEMPLAR_CLI=build/release/exemplar node --test tests/browser/studio.test.mjs
// STUDIO_UPDATE_REFERENCE=1 writes the reference instead of comparing (look at it first).
// Timings of the last stroke and suggestion are printed (docs/PERFORMANCE.md), never asserted.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const source = path.resolve(here, '../..');
const chromiumPath = process.env.CHROMIUM || '/usr/bin/chromium';
const exemplarCli = process.env.EXEMPLAR_CLI || path.join(source, 'build/release/exemplar');
const referencePath = path.join(here, 'reference', 'painting.png');
const artifacts = process.env.STUDIO_ARTIFACTS || fs.mkdtempSync(path.join(os.tmpdir(), 'studio-artifacts-'));

// Paint canvas and strokes (canvas pixels): fixed, so the server's result is fixed.
const CANVAS = { width: 320, height: 240 };
const PAINT_STROKES = [
  { from: [40, 60], to: [280, 90], width: 40 },
  { from: [90, 210], to: [230, 40], width: 28 },
];

async function loadPlaywright() {
  try {
    return (await import('playwright-core')).chromium;
  } catch (e) {
    throw new Error('playwright-core is not installed: run `npm ci` in tests/browser ' +
      `(scripts/install-deps.sh does) (${e.message})`);
  }
}

function startStudio(workspace) {
  if (!fs.existsSync(exemplarCli)) throw new Error(`${exemplarCli}: no exemplar command (build it or set EXEMPLAR_CLI)`);
  const child = spawn(exemplarCli, ['studio', '--port', '0', '--workspace', workspace, '--threads', '2'],
    { stdio: ['ignore', 'pipe', 'pipe'] });
  let stderr = '';
  child.stderr.on('data', (d) => { stderr += d; });
  const exited = new Promise((resolve) => child.on('exit', (code, signal) => resolve({ code, signal, stderr })));
  const url = new Promise((resolve, reject) => {
    let out = '';
    child.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/(http:\/\/[^\s]+\/)/);
      if (m) resolve(m[1]);
    });
    exited.then((e) => reject(new Error(`exemplar studio exited (${e.code}): ${e.stderr}`)));
  });
  return { child, url, exited };
}

// Hidden files (the atomic writers' temporaries) anywhere in the workspace.
function hiddenFiles(folder) {
  const found = [];
  for (const entry of fs.readdirSync(folder, { withFileTypes: true })) {
    if (entry.name.startsWith('.')) found.push(path.join(folder, entry.name));
    else if (entry.isDirectory()) found.push(...hiddenFiles(path.join(folder, entry.name)));
  }
  return found;
}

// Draws a straight stroke with the mouse on `locator`, in its pixel coordinates.
async function drag(page, locator, points, steps = 12) {
  const box = await locator.boundingBox();
  const at = ([x, y]) => [box.x + x, box.y + y];
  await page.mouse.move(...at(points[0]));
  await page.mouse.down();
  for (const p of points.slice(1)) await page.mouse.move(...at(p), { steps });
  await page.mouse.up();
}

// RGBA pixels of workspace images, decoded by the browser without colour conversion.
async function pixelsOf(page, urls) {
  return page.evaluate(async (list) => {
    const out = [];
    for (const url of list) {
      const blob = await (await fetch(url)).blob();
      const bitmap = await createImageBitmap(blob, { premultiplyAlpha: 'none', colorSpaceConversion: 'none' });
      const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
      const context = canvas.getContext('2d');
      context.drawImage(bitmap, 0, 0);
      out.push({ width: bitmap.width, height: bitmap.height,
        data: Array.from(context.getImageData(0, 0, bitmap.width, bitmap.height).data) });
    }
    return out;
  }, urls);
}

// Mean absolute difference (0..255) over all channels, and the share of pixels differing by more
// than 24 in any channel.
function difference(a, b) {
  assert.equal(a.width, b.width);
  assert.equal(a.height, b.height);
  let sum = 0;
  let far = 0;
  for (let i = 0; i < a.data.length; i += 4) {
    let worst = 0;
    for (let c = 0; c < 4; c++) {
      const d = Math.abs(a.data[i + c] - b.data[i + c]);
      sum += d;
      worst = Math.max(worst, d);
    }
    if (worst > 24) far++;
  }
  return { mean: sum / a.data.length, far: far / (a.width * a.height) };
}

test('exemplar studio in Chromium: paint, sketch, jobs, cancel, shutdown', { timeout: 240000 }, async () => {
  if (!fs.existsSync(chromiumPath)) {
    throw new Error(`${chromiumPath} not found: install Debian's chromium ` +
      '(apt-get install chromium; scripts/install-deps.sh does)');
  }
  const chromium = await loadPlaywright();

  const workspace = fs.mkdtempSync(path.join(os.tmpdir(), 'studio-ws-'));
  fs.mkdirSync(path.join(workspace, 'texbynum'));
  for (const name of ['source_photo.png', 'source_segment.png', 'target_segment.png']) {
    fs.copyFileSync(path.join(source, 'tests/data/ebsynth/texbynum', name), path.join(workspace, 'texbynum', name));
  }
  const studio = startStudio(workspace);
  const url = await studio.url;
  const browser = await chromium.launch({
    executablePath: chromiumPath,
    headless: true,
    args: [
      ...(process.getuid && process.getuid() === 0 ? ['--no-sandbox'] : []),
      '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
      '--disable-component-update', '--disable-sync', '--font-render-hinting=none',
    ],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1280, height: 900 }, deviceScaleFactor: 1 });
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(url);
    await page.screenshot({ path: path.join(artifacts, 'files.png') });

    // Load: upload the exemplar through the file picker (the drop zone's input).
    await page.setInputFiles('#upload', path.join(source, 'tests/data/flow/synthetic-img0.png'));
    await page.waitForSelector('#file-list a:text("synthetic-img0.png")');
    assert.ok(fs.existsSync(path.join(workspace, 'synthetic-img0.png')));
    // ... and by drag and drop: a PNG is taken, a text file named .png is refused with a message.
    await page.evaluate(async () => {
      const png = await (await fetch('/api/files/synthetic-img0.png')).arrayBuffer();
      const data = new DataTransfer();
      data.items.add(new File([png], 'dropped.png', { type: 'image/png' }));
      document.getElementById('drop').dispatchEvent(
        new DragEvent('drop', { dataTransfer: data, bubbles: true, cancelable: true }));
    });
    await page.waitForSelector('#file-list a:text("dropped.png")', { state: 'attached' });
    await page.evaluate(() => {
      const data = new DataTransfer();
      data.items.add(new File(['<script>alert(1)</script>'], 'evil.png', { type: 'image/png' }));
      document.getElementById('drop').dispatchEvent(
        new DragEvent('drop', { dataTransfer: data, bubbles: true, cancelable: true }));
    });
    await page.waitForFunction(() => document.getElementById('status').textContent.startsWith('415'));
    assert.ok(fs.existsSync(path.join(workspace, 'dropped.png')));
    assert.ok(!fs.existsSync(path.join(workspace, 'evil.png')));

    // Paint: a fixed canvas, two quick strokes drawn with the mouse, each repainted on pen-up.
    await page.click('nav button[data-tab=paint]');
    await page.selectOption('#paint-exemplar', 'synthetic-img0.png');
    await page.fill('#paint-width', String(CANVAS.width));
    await page.fill('#paint-height', String(CANVAS.height));
    await page.fill('#paint-seed', '7');
    await page.click('#paint-start');
    await page.waitForFunction(() => document.getElementById('status').textContent.startsWith('painting'));
    const overlay = page.locator('#paint-overlay');
    // The strokes are drawn quickly, one after the other, without waiting for a final: the
    // server queues them in order, so the painting is the one of two strokes applied one by one.
    for (const stroke of PAINT_STROKES) {
      await page.evaluate((w) => {
        const brush = document.getElementById('paint-brush');
        brush.value = String(w);
        brush.dispatchEvent(new Event('input'));
      }, stroke.width);
      await drag(page, overlay, [stroke.from, stroke.to]);
    }
    await page.waitForFunction((n) => window.studio.paintStrokes === n, PAINT_STROKES.length, { timeout: 60000 });
    // Every stroke showed its coarse preview before the final pixels.
    assert.equal(await page.evaluate(() => window.studio.paintPreviews), PAINT_STROKES.length);
    const paintMs = await page.evaluate(() => window.studio.paintTimes);
    const previewMs = await page.evaluate(() => window.studio.previewTimes);
    await page.locator('#paint-canvas').screenshot({ path: path.join(artifacts, 'painting-canvas.png') });
    await page.fill('#paint-output', 'outputs/painting.png');
    await page.click('#paint-save');
    await page.waitForFunction(() => document.getElementById('status').textContent === 'saved outputs/painting.png');

    const saved = path.join(workspace, 'outputs', 'painting.png');
    if (process.env.STUDIO_UPDATE_REFERENCE === '1') {
      fs.mkdirSync(path.dirname(referencePath), { recursive: true });
      fs.copyFileSync(saved, referencePath);
    }
    assert.ok(fs.existsSync(referencePath), `${referencePath} missing (STUDIO_UPDATE_REFERENCE=1 makes it)`);
    fs.copyFileSync(referencePath, path.join(workspace, 'reference.png'));
    const [server, reference] = await pixelsOf(page, ['/api/files/outputs/painting.png', '/api/files/reference.png']);
    const canvas = await page.evaluate(() => {
      const c = document.getElementById('paint-canvas');
      return { width: c.width, height: c.height,
        data: Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data) };
    });
    let painted = 0;
    for (let i = 3; i < server.data.length; i += 4) painted += server.data[i] === 255 ? 1 : 0;
    assert.ok(painted > 0.15 * CANVAS.width * CANVAS.height, `only ${painted} pixels painted`);
    const vsReference = difference(server, reference);
    assert.ok(vsReference.mean < 2 && vsReference.far < 0.01,
      `the painting differs from the reference: ${JSON.stringify(vsReference)} (see ${artifacts})`);
    const vsCanvas = difference(server, canvas);
    assert.ok(vsCanvas.mean < 1 && vsCanvas.far < 0.002,
      `the canvas shows other pixels than the server painted: ${JSON.stringify(vsCanvas)}`);

    // Escape while drawing drops the stroke: nothing is sent, the preview is cleared.
    const overlayBox = await overlay.boundingBox();
    await page.mouse.move(overlayBox.x + 30, overlayBox.y + 200);
    await page.mouse.down();
    await page.mouse.move(overlayBox.x + 200, overlayBox.y + 220, { steps: 6 });
    await page.keyboard.press('Escape');
    await page.mouse.up();
    assert.equal(await page.evaluate(() => window.studio.paintSent), PAINT_STROKES.length);
    assert.equal(await page.evaluate(() => document.getElementById('paint-overlay').getContext('2d')
      .getImageData(100, 210, 1, 1).data[3]), 0, 'the dropped stroke\'s preview is still shown');

    // Undo and redo a stroke: the canvas changes and comes back.
    await page.click('#paint-undo');
    await page.waitForFunction(() => document.getElementById('paint-canvas').getContext('2d')
      .getImageData(200, 120, 1, 1).data[3] === 0);
    await page.click('#paint-redo');
    await page.waitForFunction(() => document.getElementById('paint-canvas').getContext('2d')
      .getImageData(160, 125, 1, 1).data[3] === 255);

    // Brush: pick the railing in The Scream (examples/feature) with the mouse, paint a wave with it.
    await page.setInputFiles('#upload', path.join(source, 'examples/feature/scream_railing.png'));
    await page.waitForSelector('#file-list a:text("scream_railing.png")', { state: 'attached' });
    await page.click('nav button[data-tab=brush]');
    await page.selectOption('#brush-palette', 'scream_railing.png');
    await page.waitForFunction(() => window.studio.brush.shown === 'scream_railing.png');
    await page.fill('#brush-feature-width', '24');
    await drag(page, page.locator('#brush-palette-overlay'), [[25, 39], [90, 84], [155, 130]], 6);
    await page.click('#brush-start');
    await page.waitForFunction(() => document.getElementById('status').textContent.startsWith('brush painting'),
      null, { timeout: 60000 });
    await drag(page, page.locator('#brush-overlay'), [[40, 200], [200, 120], [360, 220], [560, 140]], 10);
    await page.waitForFunction(() => window.studio.brush.strokes === 1, null, { timeout: 60000 });
    const brushed = await page.evaluate(() => {
      const c = document.getElementById('brush-canvas');
      const data = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let opaque = 0;
      for (let i = 3; i < data.length; i += 4) opaque += data[i] > 200 ? 1 : 0;
      return opaque;
    });
    assert.ok(brushed > 5000, `the brush stroke covers only ${brushed} pixels`);
    // Fill: outline a patch of the painted water in the palette, then a region of the painting;
    // it is filled (opaque) and undo takes it back.
    await page.selectOption('#brush-tool', 'fill');
    await drag(page, page.locator('#brush-palette-overlay'), [[90, 36], [170, 40], [170, 72], [100, 62], [90, 38]], 4);
    const alphaAt = (x, y) => page.evaluate(([px, py]) => document.getElementById('brush-canvas')
      .getContext('2d').getImageData(px, py, 1, 1).data[3], [x, y]);
    assert.equal(await alphaAt(470, 290), 0);
    await drag(page, page.locator('#brush-overlay'), [[400, 240], [560, 250], [540, 340], [390, 330], [400, 242]], 4);
    await page.waitForFunction(() => window.studio.brush.fills === 1, null, { timeout: 60000 });
    assert.equal(await alphaAt(470, 290), 255, 'the region is not filled');
    const fillStatus = await page.textContent('#status');
    await page.locator('#tab-brush').screenshot({ path: path.join(artifacts, 'brush.png') });
    await page.click('#brush-undo');
    await page.waitForFunction(() => document.getElementById('brush-canvas').getContext('2d')
      .getImageData(470, 290, 1, 1).data[3] === 0);
    await page.click('#brush-redo');
    await page.waitForFunction(() => document.getElementById('brush-canvas').getContext('2d')
      .getImageData(470, 290, 1, 1).data[3] === 255);

    // Sketch: a wobbly stroke, suggestions on pen-up, Tab cycles, Enter accepts, undo/redo.
    await page.click('nav button[data-tab=sketch]');
    const svg = page.locator('#sketch-svg');
    const box = await svg.boundingBox();
    await page.mouse.move(box.x + 100, box.y + 200);
    await page.mouse.down();
    for (const [x, y] of [[180, 203], [260, 198], [340, 202], [420, 199], [500, 201]]) {
      await page.mouse.move(box.x + x, box.y + y, { steps: 4 });
    }
    await page.mouse.up();
    await page.waitForFunction(() => window.studio.sketch.suggestions.length >= 2);
    const sketchMs = await page.evaluate(() => window.studio.lastSketchMs);
    const first = await page.getAttribute('#sketch-suggestions path.current', 'd');
    await page.keyboard.press('Tab');
    assert.notEqual(await page.getAttribute('#sketch-suggestions path.current', 'd'), first);
    await page.keyboard.press('Tab');
    const count = await page.evaluate(() => window.studio.sketch.suggestions.length);
    for (let i = 2; i < count; i++) await page.keyboard.press('Tab');
    assert.equal(await page.getAttribute('#sketch-suggestions path.current', 'd'), first, 'cycling comes back');
    await page.keyboard.press('Enter');
    await page.waitForFunction(() => document.querySelectorAll('#sketch-accepted path').length === 1);
    assert.equal(await page.getAttribute('#sketch-accepted path', 'd'), first);
    await page.locator('#sketch-svg').screenshot({ path: path.join(artifacts, 'sketch.png') });
    await page.click('#sketch-undo');
    await page.waitForFunction(() => document.querySelectorAll('#sketch-accepted path').length === 0);
    await page.click('#sketch-redo');
    await page.waitForFunction(() => document.querySelectorAll('#sketch-accepted path').length === 1);

    // Jobs: a long stylize job, cancelled once it reports progress; nothing is written.
    await page.click('nav button[data-tab=jobs]');
    await page.selectOption('select[name=style]', 'texbynum/source_photo.png');
    await page.selectOption('select[name=source]', 'texbynum/source_segment.png');
    await page.selectOption('select[name=target]', 'texbynum/target_segment.png');
    await page.selectOption('select[name=quality]', 'best');
    await page.fill('#job-form input[name=output]', 'outputs/cancelled.png');
    await page.click('#job-form button[type=submit]');
    await page.waitForFunction(() => {
      const bar = document.querySelector('#job-list li progress');
      return bar && bar.value > 0;
    }, null, { timeout: 60000 });
    await page.click('#job-list li .job-cancel');
    await page.waitForSelector('#job-list li[data-state=cancelled]', { timeout: 60000 });
    await page.screenshot({ path: path.join(artifacts, 'jobs.png') });
    assert.ok(!fs.existsSync(path.join(workspace, 'outputs', 'cancelled.png')));

    // A noisy frame from the second form: done, its image shown, the file in the workspace.
    await page.selectOption('#noisy-form select[name=exemplar]', 'texbynum/source_photo.png');
    await page.selectOption('#noisy-form select[name=reference]', 'texbynum/target_segment.png');
    await page.fill('#noisy-form input[name=noise]', '2');
    await page.click('#noisy-form button[type=submit]');
    await page.waitForSelector('#job-list li[data-state=done] img', { timeout: 120000 });
    assert.ok(fs.existsSync(path.join(workspace, 'outputs', 'noisy.png')));

    // Animate: three frames of the bundled disc (examples/animate) from the third form; each
    // frame is linked as it is written, and they are `exemplar animate`'s bytes.
    const animDir = path.join(source, 'examples/animate');
    const animFrames = ['0000.png', '0001.png', '0002.png'];
    await page.setInputFiles('#upload', [...animFrames.map((f) => path.join(animDir, 'frames', f)),
      path.join(animDir, 'style_input.png'), path.join(animDir, 'style_output.png')]);
    await page.waitForSelector('#file-list a:text("style_output.png")', { state: 'attached' });
    await page.selectOption('#animate-form select[name="style-input"]', 'style_input.png');
    await page.selectOption('#animate-form select[name="style-output"]', 'style_output.png');
    await page.selectOption('#animate-form select[name=quality]', 'fast');
    await page.click('#animate-form button[type=submit]');
    await page.waitForFunction(() => {
      const li = document.querySelector('#job-list li');
      return li.textContent.includes('outputs/animate/') && li.dataset.state === 'done' && li.querySelector('img');
    }, null, { timeout: 120000 });
    assert.equal(await page.locator('#job-list li:first-child .job-frames a').count(), 3);
    // Listed in frame order, though the sweeps finish them in another.
    assert.deepEqual(await page.locator('#job-list li:first-child .job-frames a').allTextContents(),
      ['0', '1', '2']);
    const animJob = path.join(artifacts, 'animate-job.json');
    fs.writeFileSync(animJob, JSON.stringify({
      frames: path.join(workspace, '%04d.png'), first: 0, last: 2, flows: 'estimate', quality: 'fast',
      style: { input: path.join(workspace, 'style_input.png'), output: path.join(workspace, 'style_output.png') },
      output: path.join(artifacts, 'animate-cli', '%04d.png'),
    }));
    fs.rmSync(path.join(artifacts, 'animate-cli'), { recursive: true, force: true });
    const animCli = spawnSync(exemplarCli, ['animate', animJob, '-q', '-j', '2']);
    assert.equal(animCli.status, 0, `exemplar animate: ${animCli.stderr}`);
    for (const f of animFrames) {
      assert.ok(fs.readFileSync(path.join(workspace, 'outputs', 'animate', f))
        .equals(fs.readFileSync(path.join(artifacts, 'animate-cli', f))), `animate frame ${f} differs from the command's`);
    }
    await page.screenshot({ path: path.join(artifacts, 'jobs-animate.png') });

    // A noisy range from the second form: the animate frames 0..2 with a noise map (frame 0's
    // grey), each frame linked as it is written; `exemplar noisy`'s bytes.
    await page.fill('#noisy-form input[name=frames]', '%04d.png');
    await page.fill('#noisy-form input[name=first]', '0');
    await page.fill('#noisy-form input[name=last]', '2');
    await page.fill('#noisy-form input[name="noise-map"]', '0000.png');
    await page.fill('#noisy-form input[name=output]', 'outputs/noisy/%04d.png');
    await page.click('#noisy-form button[type=submit]');
    await page.waitForFunction(() => {
      const li = document.querySelector('#job-list li');
      return li.textContent.includes('outputs/noisy/') && li.dataset.state === 'done' && li.querySelector('img');
    }, null, { timeout: 120000 });
    assert.deepEqual(await page.locator('#job-list li:first-child .job-frames a').allTextContents(),
      ['0', '1', '2']);
    fs.rmSync(path.join(artifacts, 'noisy-cli'), { recursive: true, force: true });
    const noisyCli = spawnSync(exemplarCli, ['noisy', '-q', '-j', '2', '--exemplar',
      path.join(workspace, 'texbynum/source_photo.png'), '--frames', path.join(workspace, '%04d.png'),
      '--first', '0', '--last', '2', '--noise', '2', '--noise-map', path.join(workspace, '0000.png'),
      '--seed', '1', '-o', path.join(artifacts, 'noisy-cli', '%04d.png')]);
    assert.equal(noisyCli.status, 0, `exemplar noisy: ${noisyCli.stderr}`);
    for (const f of animFrames) {
      assert.ok(fs.readFileSync(path.join(workspace, 'outputs', 'noisy', f))
        .equals(fs.readFileSync(path.join(artifacts, 'noisy-cli', f))), `noisy frame ${f} differs from the command's`);
    }

    // Fluid: plume targets simulated (48x48, frames 0..3), then the bundled ink over frames
    // 1..3; the frames are `exemplar fluid`'s bytes on the same targets.
    await page.setInputFiles('#upload', path.join(source, 'examples/fluid/ink.png'));
    await page.waitForSelector('#file-list a:text("ink.png")', { state: 'attached' });
    const jobDone = (text) => page.waitForFunction((t) => {
      const li = document.querySelector('#job-list li');
      return li.textContent.includes(t) && li.dataset.state === 'done';
    }, text, { timeout: 120000 });
    await page.fill('#simulate-form input[name=width]', '48');
    await page.fill('#simulate-form input[name=height]', '48');
    await page.fill('#simulate-form input[name=last]', '3');
    await page.click('#simulate-form button[type=submit]');
    await jobDone('sim/alpha/%04d.png');
    await page.selectOption('#fluid-form select[name=exemplar]', 'ink.png');
    await page.fill('#fluid-form input[name=first]', '1');
    await page.fill('#fluid-form input[name=last]', '3');
    await page.click('#fluid-form button[type=submit]');
    await jobDone('outputs/fluid/%04d.png');
    assert.equal(await page.locator('#job-list li:first-child .job-frames a').count(), 3);
    fs.rmSync(path.join(artifacts, 'fluid-cli'), { recursive: true, force: true });
    const fluidCli = spawnSync(exemplarCli, ['fluid', '-q', '-j', '2', '--exemplar', path.join(workspace, 'ink.png'),
      '--alpha', path.join(workspace, 'sim/alpha/%04d.png'), '--motion', path.join(workspace, 'sim/motion/%04d.flo'),
      '--first', '1', '--last', '3', '--seed', '1', '-o', path.join(artifacts, 'fluid-cli', '%04d.png')]);
    assert.equal(fluidCli.status, 0, `exemplar fluid: ${fluidCli.stderr}`);
    for (const f of ['0001.png', '0002.png', '0003.png']) {
      assert.ok(fs.readFileSync(path.join(workspace, 'outputs', 'fluid', f))
        .equals(fs.readFileSync(path.join(artifacts, 'fluid-cli', f))), `fluid frame ${f} differs from the command's`);
    }
    await page.screenshot({ path: path.join(artifacts, 'jobs-fluid.png') });

    // NPR: three frames of Spot zooming (exemplar render, 96x72, into the workspace) stippled
    // from the fifth form; `exemplar npr`'s bytes.
    const render = spawnSync(exemplarCli, ['render', '--scene', path.join(source, 'examples/render/spot-zoom.json'),
      '--width', '96', '--height', '72', '--spp', '1', '--frames', '0-2', '-o', path.join(workspace, 'render', 'frame_%04d'),
      '-j', '2', '-q']);
    assert.equal(render.status, 0, `exemplar render: ${render.stderr}`);
    await page.setInputFiles('#upload', path.join(source, 'examples/npr/stipple.png'));
    await page.waitForSelector('#file-list a:text("stipple.png")', { state: 'attached' });
    await page.selectOption('#npr-form select[name=pattern]', 'stipple.png');
    await page.fill('#npr-form input[name=last]', '2');
    await page.click('#npr-form button[type=submit]');
    await jobDone('outputs/npr/%04d.png');
    fs.rmSync(path.join(artifacts, 'npr-cli'), { recursive: true, force: true });
    const nprCli = spawnSync(exemplarCli, ['npr', '--pattern', path.join(workspace, 'stipple.png'),
      '--frames', path.join(workspace, 'render', 'frame_%04d'), '--first', '0', '--last', '2',
      '-o', path.join(artifacts, 'npr-cli', '%04d.png'), '-j', '2', '-q']);
    assert.equal(nprCli.status, 0, `exemplar npr: ${nprCli.stderr}`);
    for (const f of ['0000.png', '0001.png', '0002.png']) {
      assert.ok(fs.readFileSync(path.join(workspace, 'outputs', 'npr', f))
        .equals(fs.readFileSync(path.join(artifacts, 'npr-cli', f))), `npr frame ${f} differs from the command's`);
    }
    // Again with the paper layer (the halftone screen as the paper) and the bidirectional loop:
    // `exemplar npr --paper --bidirectional 2`'s bytes, the states beside each frame.
    await page.setInputFiles('#upload', path.join(source, 'examples/npr/halftone.png'));
    await page.waitForSelector('#file-list a:text("halftone.png")', { state: 'attached' });
    await page.selectOption('#npr-form select[name=paper]', 'halftone.png');
    await page.fill('#npr-form input[name=bidirectional]', '2');
    await page.fill('#npr-form input[name=output]', 'outputs/nprbi/%04d.png');
    await page.click('#npr-form button[type=submit]');
    await jobDone('outputs/nprbi/%04d.png');
    assert.equal(await page.locator('#job-list li:first-child .job-frames a').count(), 3);
    fs.rmSync(path.join(artifacts, 'nprbi-cli'), { recursive: true, force: true });
    const nprBiCli = spawnSync(exemplarCli, ['npr', '--pattern', path.join(workspace, 'stipple.png'),
      '--paper', path.join(workspace, 'halftone.png'), '--bidirectional', '2',
      '--frames', path.join(workspace, 'render', 'frame_%04d'), '--first', '0', '--last', '2',
      '-o', path.join(artifacts, 'nprbi-cli', '%04d.png'), '-j', '2', '-q']);
    assert.equal(nprBiCli.status, 0, `exemplar npr --paper --bidirectional: ${nprBiCli.stderr}`);
    for (const f of ['0000.png', '0001.png', '0002.png', '0002.png.paper.state.exr']) {
      assert.ok(fs.readFileSync(path.join(workspace, 'outputs', 'nprbi', f))
        .equals(fs.readFileSync(path.join(artifacts, 'nprbi-cli', f))), `npr frame ${f} (paper, bidirectional) differs from the command's`);
    }

    // StyLit: the bundled painting and buffers (examples/stylit) uploaded and run; the image
    // shown is the server's, and the server's is `exemplar stylit`'s byte for byte. Then a stroke
    // painted over the exemplar with the mouse runs it again by itself (live re-run).
    const stylitDir = path.join(source, 'examples/stylit');
    const buffers = (render) => ['fullgi', 'dirdif', 'dirspc', 'indirb'].map((b) => `${render}_${b}.png`);
    await page.setInputFiles('#upload',
      ['source_style.png', ...buffers('source'), ...buffers('target')].map((f) => path.join(stylitDir, f)));
    await page.waitForSelector('#file-list a:text("target_indirb.png")', { state: 'attached' });
    await page.click('nav button[data-tab=stylit]');
    await page.uncheck('#stylit-live');
    await page.selectOption('#stylit-exemplar', 'source_style.png');
    await page.waitForFunction(() => window.studio.stylit.shown === 'source_style.png');
    await page.click('#stylit-run');
    await page.waitForFunction(() => window.studio.stylit.done === 1, null, { timeout: 120000 });
    const stylitOutput = path.join(workspace, 'outputs', 'stylit.png');
    const cliStylit = (exemplar, output) => {
      const run = spawnSync(exemplarCli, ['stylit', '-q', '-j', '2', '--seed', '1', '--exemplar', exemplar,
        '--source', ...buffers('source').map((f) => path.join(workspace, f)),
        '--target', ...buffers('target').map((f) => path.join(workspace, f)), '-o', output]);
      assert.equal(run.status, 0, `exemplar stylit: ${run.stderr}`);
      return fs.readFileSync(output);
    };
    const firstStylit = fs.readFileSync(stylitOutput);
    assert.ok(firstStylit.equals(cliStylit(path.join(workspace, 'source_style.png'), path.join(artifacts, 'stylit-cli.png'))),
      'the studio\'s StyLit image differs from exemplar stylit\'s');
    const [stylitServer] = await pixelsOf(page, ['/api/files/outputs/stylit.png']);
    const stylitShown = await page.evaluate(() => {
      const c = document.getElementById('stylit-result');
      return { width: c.width, height: c.height,
        data: Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data) };
    });
    const shownVsServer = difference(stylitServer, stylitShown);
    assert.ok(shownVsServer.mean < 1 && shownVsServer.far < 0.002,
      `the StyLit result shown is not the server's: ${JSON.stringify(shownVsServer)}`);
    await page.check('#stylit-live');
    await page.evaluate(() => {
      document.getElementById('stylit-colour').value = '#1e50c8';
      const size = document.getElementById('stylit-brush');
      size.value = '30';
      size.dispatchEvent(new Event('input'));
    });
    await drag(page, page.locator('#stylit-overlay'), [[120, 330], [300, 300], [480, 340]], 8);
    await page.waitForFunction(() => window.studio.stylit.done === 2, null, { timeout: 120000 });
    await page.locator('#tab-stylit').screenshot({ path: path.join(artifacts, 'stylit.png') });
    const paintedExemplar = path.join(workspace, 'outputs', 'stylit_exemplar.png');
    assert.ok(fs.existsSync(paintedExemplar), 'the painted exemplar was not saved');
    const secondStylit = fs.readFileSync(stylitOutput);
    assert.ok(!secondStylit.equals(firstStylit), 'painting the exemplar did not change the result');
    assert.ok(secondStylit.equals(cliStylit(paintedExemplar, path.join(artifacts, 'stylit-painted-cli.png'))),
      'the re-run differs from exemplar stylit on the painted exemplar');

    // Shutdown: another job running, then SIGINT: exit 0, nothing half-written.
    await page.click('nav button[data-tab=jobs]');
    await page.fill('#job-form input[name=output]', 'outputs/interrupted.png');
    const jobsBefore = await page.locator('#job-list li').count();
    await page.click('#job-form button[type=submit]');
    await page.waitForFunction((n) => document.querySelectorAll('#job-list li').length === n &&
      document.querySelector('#job-list li progress').value > 0, jobsBefore + 1, { timeout: 60000 });
    studio.child.kill('SIGINT');
    const exit = await studio.exited;
    assert.equal(exit.code, 0, `exit ${exit.code} ${exit.signal}: ${exit.stderr}`);
    assert.ok(!fs.existsSync(path.join(workspace, 'outputs', 'interrupted.png')));
    assert.deepEqual(hiddenFiles(workspace), []);
    assert.deepEqual(errors, []);

    console.log(`studio timings: paint stroke pen-up to preview ${previewMs.map((t) => t.toFixed(0)).join(', ')} ms, to canvas ${paintMs.map((t) => t.toFixed(0)).join(', ')} ms ` +
      `(strokes of ${PAINT_STROKES.map((s) => s.width).join(', ')} px on ${CANVAS.width}x${CANVAS.height}); ` +
      `sketch suggestions ${sketchMs.toFixed(0)} ms; ${fillStatus} (160x100 px region); painting vs reference ${JSON.stringify(vsReference)}; ` +
      `screenshots in ${artifacts}`);
  } finally {
    await browser.close();
    if (studio.child.exitCode === null) studio.child.kill('SIGKILL');
    fs.rmSync(workspace, { recursive: true, force: true });
  }
});
