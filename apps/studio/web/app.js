// exemplar studio: plain browser JavaScript, no build step. The server does the work
// (docs/studio.md); this file collects pointer strokes, calls the JSON API and draws answers.
'use strict';

const client = sessionStorage.getItem('studio-client') ||
  Math.random().toString(36).slice(2, 12);
sessionStorage.setItem('studio-client', client);

// What the browser test reads: timings and counts of the last answers.
const studio = { client, lastPaintMs: null, lastPreviewMs: null, previewTimes: [], paintTimes: [], paintPreviews: 0, lastSketchMs: null, paintSent: 0, paintStrokes: 0, sketch: null };
window.studio = studio;

const $ = (id) => document.getElementById(id);
function say(text) { $('status').textContent = text; }

async function api(method, path, body, raw = false) {
  const headers = { 'X-Studio-Client': client };
  let payload = body;
  if (body !== undefined && !(body instanceof Blob) && !(body instanceof ArrayBuffer)) {
    headers['Content-Type'] = 'application/json';
    payload = JSON.stringify(body);
  }
  const res = await fetch(path, { method, headers, body: payload });
  if (!res.ok) {
    let message = res.statusText;
    try { message = (await res.json()).error; } catch (e) { /* not JSON */ }
    throw new Error(`${res.status}: ${message}`);
  }
  return raw ? res : res.json();
}

function fail(error) { say(error.message); console.error(error); }

// Tabs.
for (const button of document.querySelectorAll('nav button')) {
  button.addEventListener('click', () => {
    document.querySelectorAll('nav button').forEach((b) => b.classList.toggle('active', b === button));
    document.querySelectorAll('.tab').forEach((t) => t.classList.toggle('active', t.id === `tab-${button.dataset.tab}`));
  });
}

// Pointer strokes on an element, in its own pixel coordinates. Escape while drawing drops the
// stroke: its preview is cleared (onMove with no points) and nothing is sent.
function strokes(element, onMove, onUp) {
  let points = null;
  document.addEventListener('keydown', (e) => {
    if (e.key !== 'Escape' || !points) return;
    points = null;
    onMove([]);
  });
  const at = (e) => {
    const r = element.getBoundingClientRect();
    return [e.clientX - r.left, e.clientY - r.top];
  };
  element.addEventListener('pointerdown', (e) => {
    element.setPointerCapture(e.pointerId);
    points = [at(e)];
    onMove(points);
  });
  element.addEventListener('pointermove', (e) => {
    if (!points) return;
    points.push(at(e));
    onMove(points);
  });
  const end = () => {
    if (!points) return;
    const done = points;
    points = null;
    onUp(done);
  };
  element.addEventListener('pointerup', end);
  element.addEventListener('pointercancel', end);
}

// Files: upload by drop or picker, list with download links.
async function refreshFiles() {
  const { files } = await api('GET', '/api/files');
  const list = $('file-list');
  list.replaceChildren(...files.map((f) => {
    const li = document.createElement('li');
    const a = document.createElement('a');
    a.href = `/api/files/${encodeURI(f.path)}?download=1`;
    a.textContent = f.path;
    li.append(a, ` (${f.bytes} bytes)`);
    return li;
  }));
  const images = files.map((f) => f.path).filter((p) => /\.(png|jpe?g)$/i.test(p));
  for (const select of document.querySelectorAll('.file-select')) {
    const keep = select.value;
    // An optional file (data-optional) starts at "none", which leaves it out of the job.
    const optional = 'optional' in select.dataset;
    select.replaceChildren(...(optional ? [new Option('none', '')] : []),
      ...images.map((p) => new Option(p, p)));
    if (images.includes(keep) || (optional && keep === '')) select.value = keep;
  }
  if ($('brush-palette').value !== brush.shown) await showPalette();
  if ($('stylit-exemplar').value !== stylit.shown) await showStylitExemplar();
  return files;
}

async function upload(fileList) {
  for (const file of fileList) {
    try {
      await api('PUT', `/api/files/${encodeURIComponent(file.name)}`, file);
      say(`uploaded ${file.name}`);
    } catch (e) { fail(e); }
  }
  await refreshFiles();
}
$('upload').addEventListener('change', (e) => upload(e.target.files));
const drop = $('drop');
drop.addEventListener('dragover', (e) => { e.preventDefault(); drop.classList.add('over'); });
drop.addEventListener('dragleave', () => drop.classList.remove('over'));
drop.addEventListener('drop', (e) => {
  e.preventDefault();
  drop.classList.remove('over');
  upload(e.dataTransfer.files);
});

// Paint: Brushables strokes; each pen-up repaints only the touched rectangle on the server.
const paintCanvas = $('paint-canvas');
const paintOverlay = $('paint-overlay');
const paintContext = paintCanvas.getContext('2d');
const overlayContext = paintOverlay.getContext('2d');
// Settles when the last stroke's final is posted: the next stroke's requests go after it.
let paintTurn = Promise.resolve();

// An answer of RGBA bytes for the rectangle in its X-Rect header, put into `context`.
async function putRgba(res, context = paintContext) {
  const [x0, y0, x1, y1] = res.headers.get('X-Rect').split(',').map(Number);
  const bytes = new Uint8ClampedArray(await res.arrayBuffer());
  if (x1 > x0 && y1 > y0) context.putImageData(new ImageData(bytes, x1 - x0, y1 - y0), x0, y0);
}

// A stroke's preview on an overlay while it is drawn.
function drawPreview(context, points, width, colour) {
  context.clearRect(0, 0, context.canvas.width, context.canvas.height);
  drawLine(context, points, width, colour);
}

// A round-capped polyline (a dot for one point).
function drawLine(context, points, width, colour) {
  if (!points.length) return;
  if (points.length === 1) points = [points[0], [points[0][0] + 0.01, points[0][1]]];
  context.strokeStyle = colour;
  context.lineWidth = width;
  context.lineCap = context.lineJoin = 'round';
  context.beginPath();
  points.forEach(([x, y], i) => (i ? context.lineTo(x, y) : context.moveTo(x, y)));
  context.stroke();
}

$('paint-brush').addEventListener('input', (e) => { $('paint-brush-value').value = e.target.value; });
$('paint-start').addEventListener('click', async () => {
  try {
    const width = Number($('paint-width').value);
    const height = Number($('paint-height').value);
    const answer = await api('POST', '/api/paint/start', {
      exemplar: $('paint-exemplar').value, width, height, seed: Number($('paint-seed').value),
      usage: $('paint-usage').value,
    });
    for (const c of [paintCanvas, paintOverlay]) { c.width = answer.width; c.height = answer.height; }
    paintContext.clearRect(0, 0, answer.width, answer.height);
    studio.paintStrokes = 0;
    say(`painting ${answer.width}×${answer.height}`);
  } catch (e) { fail(e); }
});
// The overlay shows the stroke being drawn; an earlier stroke's answers clear it only between
// strokes.
let paintDrawing = false;
const clearOverlay = () => {
  if (!paintDrawing) overlayContext.clearRect(0, 0, paintOverlay.width, paintOverlay.height);
};
strokes(paintOverlay, (points) => {
  paintDrawing = points.length > 0;
  drawPreview(overlayContext, points, Number($('paint-brush').value),
    $('paint-comb').checked ? 'rgba(40,110,200,0.6)' : 'rgba(200,60,40,0.35)');
}, async (points) => {
  paintDrawing = false;
  const started = performance.now();
  studio.paintSent += 1;
  // Strokes go to the server in the order drawn: this stroke's requests wait until the one
  // before has posted its final (the server queues finals in the order they arrive and composes
  // each preview over every stroke queued so far, docs/studio.md, "The paint pipeline").
  const turn = paintTurn;
  let posted;
  paintTurn = new Promise((resolve) => { posted = resolve; });
  try {
    await turn;
    // Pen-up: a coarse preview of the stroke at once, then the final repaint over it
    // (docs/studio.md, "Pen-up latency").
    const stroke = { points, width: Number($('paint-brush').value), comb: $('paint-comb').checked };
    await putRgba(await api('POST', '/api/paint/preview', stroke, true));
    studio.lastPreviewMs = performance.now() - started;
    studio.previewTimes.push(studio.lastPreviewMs);
    studio.paintPreviews += 1;
    clearOverlay();
    const final = api('POST', '/api/paint/stroke', stroke, true);
    posted();
    const res = await final;
    await putRgba(res);
    studio.lastPaintMs = performance.now() - started;
    studio.paintTimes.push(studio.lastPaintMs);
    studio.paintStrokes += 1;
    say(`stroke ${studio.paintStrokes}: preview ${studio.lastPreviewMs.toFixed(0)} ms, final ${studio.lastPaintMs.toFixed(0)} ms`);
  } catch (e) {
    // 409: undone (or a new painting started) before its final; undo answered the canvas.
    if (e.message.includes('cancelled')) say('stroke undone'); else fail(e);
  } finally {
    posted();
  }
  clearOverlay();
});
// The buttons of a painting tool (paint, brush): undo, redo and save.
function canvasButtons(tool, context) {
  for (const action of ['undo', 'redo']) {
    $(`${tool}-${action}`).addEventListener('click', async () => {
      try { await putRgba(await api('POST', `/api/${tool}/${action}`, {}, true), context); } catch (e) { fail(e); }
    });
  }
  $(`${tool}-save`).addEventListener('click', async () => {
    try {
      const { path } = await api('POST', `/api/${tool}/save`, { output: $(`${tool}-output`).value });
      say(`saved ${path}`);
      await refreshFiles();
    } catch (e) { fail(e); }
  });
}
canvasButtons('paint', paintContext);

// Brush: Painting by Feature's line-feature brush. A rough line drawn on the palette picks the
// feature (snapped to its edge by the server); strokes below are painted with it.
const brush = { selection: null, fillSource: null, strokes: 0, fills: 0, shown: null };
studio.brush = brush;
const paletteCanvas = $('brush-palette-canvas');
const paletteOverlay = $('brush-palette-overlay').getContext('2d');
const brushContext = $('brush-canvas').getContext('2d');
const brushOverlay = $('brush-overlay').getContext('2d');

async function showPalette() {
  const name = $('brush-palette').value;
  if (!name) return;
  const blob = await (await fetch(`/api/files/${encodeURI(name)}`)).blob();
  const bitmap = await createImageBitmap(blob);
  for (const c of [paletteCanvas, paletteOverlay.canvas]) { c.width = bitmap.width; c.height = bitmap.height; }
  paletteCanvas.getContext('2d').drawImage(bitmap, 0, 0);
  brush.selection = null;
  brush.shown = name;
}
$('brush-palette').addEventListener('change', () => showPalette().catch(fail));
$('brush-size').addEventListener('input', (e) => { $('brush-size-value').value = e.target.value; });
const filling = () => $('brush-tool').value === 'fill';
// A region outlined with the pointer, shown closed and filled.
function drawLasso(context, points, colour) {
  context.clearRect(0, 0, context.canvas.width, context.canvas.height);
  context.fillStyle = colour;
  context.beginPath();
  points.forEach(([x, y], i) => (i ? context.lineTo(x, y) : context.moveTo(x, y)));
  context.closePath();
  context.fill();
}
$('brush-tool').addEventListener('change', () => {
  $('brush-hint').textContent = filling()
    ? 'Outline a region of the palette, then outline a region of the painting: it is filled with that texture.'
    : 'Draw along a line in the palette to pick it, then paint with it below.';
});
strokes(paletteOverlay.canvas, (points) => {
  if (filling()) drawLasso(paletteOverlay, points, 'rgba(40,150,90,0.4)');
  else drawPreview(paletteOverlay, points, Number($('brush-feature-width').value), 'rgba(230,140,20,0.45)');
}, (points) => {
  if (filling()) brush.fillSource = points;
  else brush.selection = points;
});
$('brush-start').addEventListener('click', async () => {
  try {
    if (!brush.selection) throw new Error('draw along a line in the palette first');
    const answer = await api('POST', '/api/brush/start', {
      palette: $('brush-palette').value,
      feature: { points: brush.selection, width: Number($('brush-feature-width').value) },
      width: Number($('brush-width').value), height: Number($('brush-height').value),
      seed: Number($('brush-seed').value),
    });
    for (const c of [brushContext.canvas, brushOverlay.canvas]) { c.width = answer.width; c.height = answer.height; }
    drawPreview(paletteOverlay, answer.feature, 2, 'rgba(23,105,194,0.9)');
    brush.strokes = 0;
    say(`brush painting ${answer.width}×${answer.height}`);
  } catch (e) { fail(e); }
});
strokes(brushOverlay.canvas, (points) => {
  if (filling()) drawLasso(brushOverlay, points, 'rgba(40,150,90,0.3)');
  else drawPreview(brushOverlay, points, Number($('brush-size').value), 'rgba(200,60,40,0.3)');
}, async (points) => {
  const started = performance.now();
  try {
    if (filling()) {
      if (!brush.fillSource) throw new Error('outline a region of the palette first');
      await putRgba(await api('POST', '/api/brush/fill',
        { source: brush.fillSource, target: points, seed: Number($('brush-seed').value) }, true), brushContext);
      brush.fills += 1;
      say(`fill ${brush.fills}: ${(performance.now() - started).toFixed(0)} ms`);
    } else {
      await putRgba(await api('POST', '/api/brush/stroke', { points, width: Number($('brush-size').value) }, true),
        brushContext);
      brush.strokes += 1;
      say(`brush stroke ${brush.strokes}: ${(performance.now() - started).toFixed(0)} ms`);
    }
  } catch (e) { fail(e); }
  brushOverlay.clearRect(0, 0, brushOverlay.canvas.width, brushOverlay.canvas.height);
});
canvasButtons('brush', brushContext);

// Sketch: ShipShape suggestions after every pen-up; Tab cycles, Enter (or the next stroke)
// accepts the one shown.
const svgNS = 'http://www.w3.org/2000/svg';
const sketch = { suggestions: [], current: 0 };
studio.sketch = sketch;

function pathElements(ds, classOf) {
  return ds.map((d, i) => {
    const p = document.createElementNS(svgNS, 'path');
    p.setAttribute('d', d);
    const c = classOf ? classOf(i) : '';
    if (c) p.setAttribute('class', c);
    return p;
  });
}
function showSketch(state) {
  if (state) {
    $('sketch-accepted').replaceChildren(...pathElements(state.paths));
    $('sketch-info').textContent = `${state.paths.length} paths`;
  }
  const ds = sketch.suggestions.map((s) => s.d);
  // The current suggestion last, so it is drawn on top.
  const order = ds.map((_, i) => i).filter((i) => i !== sketch.current);
  if (ds.length) order.push(sketch.current);
  $('sketch-suggestions').replaceChildren(...pathElements(order.map((i) => ds[i]),
    (k) => (order[k] === sketch.current ? 'current' : '')));
  if (ds.length) {
    const s = sketch.suggestions[sketch.current];
    $('sketch-info').textContent = `suggestion ${sketch.current + 1} of ${ds.length}` +
      (s.original ? ' (as drawn)' : ` (likelihood ${s.likelihood.toFixed(2)})`);
  }
}
async function acceptSketch() {
  if (!sketch.suggestions.length) return;
  const state = await api('POST', '/api/sketch/accept', { index: sketch.current });
  sketch.suggestions = [];
  sketch.current = 0;
  showSketch(state);
}
const sketchSvg = $('sketch-svg');
strokes(sketchSvg, (points) => {
  $('sketch-ink').setAttribute('points', points.map((p) => p.join(',')).join(' '));
}, async (points) => {
  try {
    await acceptSketch();
    const started = performance.now();
    const answer = await api('POST', '/api/sketch/stroke', { points });
    studio.lastSketchMs = performance.now() - started;
    sketch.suggestions = answer.suggestions;
    sketch.current = 0;
    showSketch();
    say(`${answer.suggestions.length} suggestions in ${studio.lastSketchMs.toFixed(0)} ms`);
  } catch (e) { fail(e); }
  $('sketch-ink').setAttribute('points', '');
});
function cycleSketch() {
  if (!sketch.suggestions.length) return;
  sketch.current = (sketch.current + 1) % sketch.suggestions.length;
  showSketch();
}
$('sketch-cycle').addEventListener('click', cycleSketch);
$('sketch-accept').addEventListener('click', () => acceptSketch().catch(fail));
document.addEventListener('keydown', (e) => {
  if (!$('tab-sketch').classList.contains('active')) return;
  if (e.key === 'Tab') { e.preventDefault(); cycleSketch(); }
  if (e.key === 'Enter') { e.preventDefault(); acceptSketch().catch(fail); }
});
for (const action of ['undo', 'redo', 'reset']) {
  $(`sketch-${action}`).addEventListener('click', async () => {
    try {
      sketch.suggestions = [];
      showSketch(await api('POST', `/api/sketch/${action}`, {}));
    } catch (e) { fail(e); }
  });
}

// A job's server-sent events: `onProgress({fraction, stage, ...})`, `onFrame({frame, path})` for
// each finished frame of a range, then `onEnd({state, output, error})`. Returns the EventSource
// (closing it stops following, not the job).
function watchJob(id, onProgress, onEnd, onFrame = () => {}) {
  const events = new EventSource(`/api/jobs/${id}/events`);
  events.addEventListener('progress', (e) => onProgress(JSON.parse(e.data)));
  events.addEventListener('frame', (e) => onFrame(JSON.parse(e.data)));
  events.addEventListener('end', (e) => {
    events.close();
    onEnd(JSON.parse(e.data));
  });
  return events;
}

// Jobs: start, follow the server-sent progress, cancel, show and download the output.
function followJob(id, output) {
  const li = document.createElement('li');
  li.dataset.job = id;
  const bar = document.createElement('progress');
  bar.max = 1;
  bar.value = 0;
  const label = document.createElement('span');
  label.className = 'job-state';
  label.textContent = 'running';
  const cancel = document.createElement('button');
  cancel.textContent = 'Cancel';
  cancel.className = 'job-cancel';
  cancel.addEventListener('click', () => api('POST', `/api/jobs/${id}/cancel`, {}).catch(fail));
  const frames = document.createElement('span');
  frames.className = 'job-frames';
  const frameFiles = [];
  li.append(`job ${id} → ${output} `, bar, ' ', label, ' ', cancel, frames);
  $('job-list').prepend(li);
  const download = (path, text) => {
    const a = document.createElement('a');
    a.href = `/api/files/${encodeURI(path)}?download=1`;
    a.textContent = text;
    return a;
  };
  watchJob(id, (p) => {
    bar.value = p.fraction;
    label.textContent = `${p.stage} ${(100 * p.fraction).toFixed(0)}%`;
  }, (end) => {
    li.dataset.state = end.state;
    label.textContent = end.state + (end.error ? `: ${end.error}` : '');
    cancel.remove();
    if (end.state === 'done') {
      bar.value = 1;
      // A range shows its first frame; every frame is linked as it is written.
      const shown = frameFiles.length ? frameFiles.sort()[0] : end.output;
      const img = document.createElement('img');
      img.src = `/api/files/${encodeURI(shown)}?t=${Date.now()}`;
      if (!frameFiles.length) li.append(download(end.output, ' download'));
      li.append(img);
    }
    if (end.state === 'done' || frameFiles.length) refreshFiles().catch(fail);
  }, (f) => {
    frameFiles.push(f.path);
    // Listed in frame order, whatever order the job finishes them in (animate's sweeps).
    const item = document.createElement('span');
    item.dataset.frame = f.frame;
    item.append(' ', download(f.path, `${f.frame}`));
    const next = [...frames.children].find((c) => Number(c.dataset.frame) > f.frame);
    frames.insertBefore(item, next || null);
  });
}
// StyLit: the exemplar painting (loaded, then painted over with the mouse) stylizes the target
// render through both renders' light-path buffers. Every change (a stroke's pen-up, another
// exemplar, buffers or seed) runs it again after a short pause; the server cancels the run
// before (docs/studio.md).
const stylit = { runs: 0, done: 0, painted: false, shown: null, timer: null, events: null, id: null };
studio.stylit = stylit;
const stylitCanvas = $('stylit-canvas');
const stylitOverlay = $('stylit-overlay').getContext('2d');
const stylitResult = $('stylit-result');

// Draws a workspace image into `canvas`, resized to it, without colour conversion.
async function showImage(canvas, name) {
  const blob = await (await fetch(`/api/files/${encodeURI(name)}?t=${Date.now()}`)).blob();
  const bitmap = await createImageBitmap(blob, { premultiplyAlpha: 'none', colorSpaceConversion: 'none' });
  canvas.width = bitmap.width;
  canvas.height = bitmap.height;
  canvas.getContext('2d').drawImage(bitmap, 0, 0);
}

async function showStylitExemplar() {
  const name = $('stylit-exemplar').value;
  if (!name || name === stylit.shown) return;
  await showImage(stylitCanvas, name);
  stylitOverlay.canvas.width = stylitCanvas.width;
  stylitOverlay.canvas.height = stylitCanvas.height;
  stylit.shown = name;
  stylit.painted = false;
}

function stylitLater() {
  if (!$('stylit-live').checked) return;
  clearTimeout(stylit.timer);
  stylit.timer = setTimeout(() => runStylit().catch(fail), 400);
}

async function runStylit() {
  clearTimeout(stylit.timer);
  await showStylitExemplar();
  let exemplar = $('stylit-exemplar').value;
  if (stylit.painted) {
    // The painted exemplar goes to the workspace first: the job reads files only.
    exemplar = $('stylit-painting').value;
    const png = await new Promise((resolve) => stylitCanvas.toBlob(resolve, 'image/png'));
    await api('PUT', `/api/files/${encodeURI(exemplar)}`, png);
  }
  const list = (id) => $(id).value.trim().split(/[\s,]+/).filter((p) => p);
  const body = {
    kind: 'stylit', exemplar, source: list('stylit-source'), target: list('stylit-target'),
    output: $('stylit-output').value, seed: Number($('stylit-seed').value),
    preview: $('stylit-preview').checked,
  };
  if (stylit.events) stylit.events.close();
  const { id } = await api('POST', '/api/jobs', body);
  stylit.runs += 1;
  stylit.id = id;
  const started = performance.now();
  $('stylit-state').textContent = 'running';
  stylit.events = watchJob(id, (p) => {
    $('stylit-progress').value = p.fraction;
  }, async (end) => {
    if (stylit.id !== id) return;
    $('stylit-state').textContent = end.state + (end.error ? `: ${end.error}` : '');
    if (end.state !== 'done') return;
    $('stylit-progress').value = 1;
    await showImage(stylitResult, end.output);
    stylit.done += 1;
    stylit.exemplar = exemplar;
    say(`stylit run ${stylit.done}: ${(performance.now() - started).toFixed(0)} ms`);
  });
}

$('stylit-brush').addEventListener('input', (e) => { $('stylit-brush-value').value = e.target.value; });
$('stylit-exemplar').addEventListener('change', () => showStylitExemplar().then(stylitLater).catch(fail));
for (const id of ['stylit-source', 'stylit-target', 'stylit-seed', 'stylit-preview']) {
  $(id).addEventListener('change', stylitLater);
}
$('stylit-run').addEventListener('click', () => runStylit().catch(fail));
strokes(stylitOverlay.canvas, (points) => {
  drawPreview(stylitOverlay, points, Number($('stylit-brush').value), $('stylit-colour').value);
}, (points) => {
  // The stroke goes into the exemplar itself, as the preview showed it.
  stylitOverlay.clearRect(0, 0, stylitOverlay.canvas.width, stylitOverlay.canvas.height);
  drawLine(stylitCanvas.getContext('2d'), points, Number($('stylit-brush').value), $('stylit-colour').value);
  stylit.painted = true;
  stylitLater();
});

// The noisy form: one frame (reference, frame) or a range (frames, first, last); more media and
// the media's orientations are comma-separated paths; empty fields are left out.
const jobShapes = {
  noisy(body) {
    for (const k of Object.keys(body)) if (body[k] === '') delete body[k];
    const list = (text) => text.split(',').map((p) => p.trim()).filter(Boolean);
    if (body['more-media']) body.exemplar = [body.exemplar, ...list(body['more-media'])];
    delete body['more-media'];
    if (body['exemplar-orientation']) body['exemplar-orientation'] = list(body['exemplar-orientation']);
    for (const k of body.frames ? ['reference', 'frame'] : ['first', 'last']) delete body[k];
  },
};

// Each job form names its kind; number fields are sent as JSON numbers, optional files left at
// "none" are left out.
for (const jobForm of document.querySelectorAll('.job-form')) {
  jobForm.addEventListener('submit', async (e) => {
    e.preventDefault();
    const body = { kind: e.target.dataset.kind };
    for (const [k, v] of new FormData(e.target)) {
      const field = e.target.elements[k];
      if (v === '' && 'optional' in field.dataset) continue;
      body[k] = field.type === 'number' ? Number(v) : v;
    }
    jobShapes[body.kind]?.(body);
    try {
      const { id } = await api('POST', '/api/jobs', body);
      followJob(id, body.output || body.alpha);
    } catch (err) { fail(err); }
  });
}

refreshFiles().catch(fail);
