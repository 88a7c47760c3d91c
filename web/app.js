// The authoring page (docs/web.md): the scene text beside the running picture. The WebGL 2
// module (sbfx.js, platform/web/) draws the frame at the page's time; this file owns the
// timeline, the editor, the settings, the panels and the address. window.sbfxPage is what the
// browser tests (tests/web/) drive.
"use strict";

const $ = (id) => document.getElementById(id);
const params = new URLSearchParams(location.search);
const RELOAD_DELAY_MS = 300; // the editor's debounce, as sbfx-play --watch settles an edit
const SCENE_NAME = "scene.cfg";

const page = {
  module: null,
  api: null,
  time: 0, // seconds since the scene's timeline started
  playing: !params.has("paused"),
  dirty: true, // draw even when paused
  lastNow: null,
  goodText: "", // the text of the scene that plays
  errorLine: 0,
  reloadTimer: 0,
  fixedSize: null, // ?size=WxH: the drawing buffer's size, whatever the layout and pixel ratio
  aim: null, // the keyboard's aim on the canvas, in canvas pixels
  frames: 0,
  lastStats: 0,
};

// ---- the module --------------------------------------------------------------------------

function wrap(m) {
  const c = (name, ret, args) => m.cwrap(name, ret, args);
  return {
    start: c("sbfx_web_start", "number", ["string", "number", "number"]),
    resize: c("sbfx_web_resize", "number", ["number", "number"]),
    load: c("sbfx_web_load", "number", ["string", "string"]),
    settings: c("sbfx_web_settings", "number", ["number", "number", "number", "number", "number", "number"]),
    frame: c("sbfx_web_frame", "number", ["number"]),
    readPixels: c("sbfx_web_read_pixels", "number", []),
    trigger: c("sbfx_web_trigger", "number", ["number", "number", "number"]),
    effectName: c("sbfx_web_effect_name", "string", ["number"]),
    clickCoordinate: c("sbfx_web_click_coordinate", "number", ["number"]),
    pick: c("sbfx_web_pick", "number", ["number", "number", "number"]),
    project: c("sbfx_web_project", "number", ["number", "number", "number", "number"]),
    stats: c("sbfx_web_stats", "string", []),
    info: c("sbfx_web_info", "string", []),
    message: c("sbfx_web_message", "string", []),
  };
}

function log(level, text) {
  const li = document.createElement("li");
  li.className = ["error", "warning", "info"][level] || "info";
  li.textContent = `${new Date().toLocaleTimeString()} ${li.className}: ${text}`;
  const list = $("log");
  list.appendChild(li);
  while (list.children.length > 200) list.removeChild(list.firstChild);
  // the library's errors reach the console: the browser tests fail on them
  if (level === 0) console.error("sbfx: " + text);
  else if (level === 1) console.warn("sbfx: " + text);
}

// ---- size: the canvas at the device's pixel ratio -----------------------------------------

function wantedSize() {
  if (page.fixedSize) return page.fixedSize;
  const canvas = $("sbfx-canvas");
  const dpr = window.devicePixelRatio || 1;
  const w = Math.max(16, Math.round(canvas.clientWidth * dpr));
  const h = Math.max(16, Math.round(canvas.clientHeight * dpr));
  return [w, h];
}

function followSize() {
  const canvas = $("sbfx-canvas");
  const [w, h] = wantedSize();
  if (canvas.width === w && canvas.height === h) return;
  canvas.width = w;
  canvas.height = h;
  if (page.api && page.api.resize(w, h) !== 0) log(0, "resize: " + page.api.message());
  page.dirty = true;
}

// ---- the scene text: reload, errors, address -----------------------------------------------

function showError(message) {
  const box = $("scene-error");
  const m = /:(\d+):/.exec(message);
  page.errorLine = m ? Number(m[1]) : 0;
  $("scene-error-text").textContent = page.errorLine
    ? `Line ${page.errorLine}: ${message.replace(/^[^:]*:\d+:\s*/, "")} (the previous scene plays on)`
    : `${message} (the previous scene plays on)`;
  $("goto-error").hidden = !page.errorLine;
  box.hidden = false;
  $("scene-text").setAttribute("aria-invalid", "true");
}

function clearError() {
  $("scene-error").hidden = true;
  $("scene-text").removeAttribute("aria-invalid");
  page.errorLine = 0;
}

function gotoErrorLine() {
  const area = $("scene-text");
  const lines = area.value.split("\n");
  const n = Math.min(page.errorLine, lines.length) - 1;
  let start = 0;
  for (let i = 0; i < n; i++) start += lines[i].length + 1;
  area.focus();
  area.setSelectionRange(start, start + (lines[n] || "").length);
}

// Loads the text; true when it took over. A refused edit leaves the playing scene alone.
function loadText(text) {
  const rc = page.api.load(text, SCENE_NAME);
  if (rc !== 0) {
    showError(page.api.message());
    return false;
  }
  page.goodText = text;
  clearError();
  page.time = 0;
  page.dirty = true;
  fillEffects();
  writeAddress(text);
  return true;
}

function scheduleReload() {
  clearTimeout(page.reloadTimer);
  page.reloadTimer = setTimeout(() => loadText($("scene-text").value), RELOAD_DELAY_MS);
}

// The scene in the fragment: #scene=<base64url of the deflate-raw bytes> where the browser has
// CompressionStream, else #text=<base64url of the UTF-8 bytes>; both are read.
function toBase64Url(bytes) {
  let s = "";
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(s).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}

function fromBase64Url(s) {
  const bin = atob(s.replace(/-/g, "+").replace(/_/g, "/"));
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return bytes;
}

async function pipeBytes(bytes, stream) {
  const out = new Response(new Blob([bytes]).stream().pipeThrough(stream));
  return new Uint8Array(await out.arrayBuffer());
}

async function encodeScene(text) {
  const bytes = new TextEncoder().encode(text);
  if (typeof CompressionStream === "function")
    return "scene=" + toBase64Url(await pipeBytes(bytes, new CompressionStream("deflate-raw")));
  return "text=" + toBase64Url(bytes);
}

async function decodeScene(fragment) {
  const f = new URLSearchParams(fragment.replace(/^#/, ""));
  if (f.has("scene"))
    return new TextDecoder().decode(await pipeBytes(fromBase64Url(f.get("scene")), new DecompressionStream("deflate-raw")));
  if (f.has("text")) return new TextDecoder().decode(fromBase64Url(f.get("text")));
  return null;
}

let addressWrite = Promise.resolve();
function writeAddress(text) {
  addressWrite = addressWrite.then(async () => {
    const fragment = text ? "#" + (await encodeScene(text)) : "";
    history.replaceState(null, "", location.pathname + location.search + fragment);
  });
  return addressWrite;
}

// ---- effects, clicks and the keyboard's aim -----------------------------------------------

function fillEffects() {
  const select = $("effect");
  const old = select.value;
  select.textContent = "";
  for (let i = 0; ; i++) {
    const name = page.api.effectName(i);
    if (!name) break;
    select.add(new Option(name, String(i)));
  }
  if ([...select.options].some((o) => o.value === old)) select.value = old;
}

function triggerAt(x, y) {
  const effect = Number($("effect").value || 0);
  const rc = page.api.trigger(x, y, effect);
  if (rc !== 0) {
    $("click-status").textContent = page.api.message();
    return null;
  }
  const p = [0, 1, 2].map((a) => page.api.clickCoordinate(a));
  $("click-status").textContent =
    `${$("effect").selectedOptions[0].text} at (${p[0].toFixed(2)}, 0, ${p[2].toFixed(2)}) m, t = ${page.time.toFixed(2)} s`;
  page.dirty = true;
  return p;
}

function canvasPixel(event) {
  const canvas = $("sbfx-canvas");
  const r = canvas.getBoundingClientRect();
  return [((event.clientX - r.left) * canvas.width) / r.width, ((event.clientY - r.top) * canvas.height) / r.height];
}

function showAim() {
  const canvas = $("sbfx-canvas");
  const aim = $("aim");
  if (!page.aim) {
    aim.hidden = true;
    return;
  }
  aim.hidden = false;
  aim.style.left = `${(page.aim[0] * canvas.clientWidth) / canvas.width}px`;
  aim.style.top = `${(page.aim[1] * canvas.clientHeight) / canvas.height}px`;
}

function onCanvasKey(event) {
  const canvas = $("sbfx-canvas");
  if (!page.aim) page.aim = [canvas.width / 2, canvas.height * 0.75];
  const step = (event.shiftKey ? 0.1 : 0.02) * canvas.width;
  const moves = { ArrowLeft: [-step, 0], ArrowRight: [step, 0], ArrowUp: [0, -step], ArrowDown: [0, step] };
  if (moves[event.key]) {
    page.aim[0] = Math.min(canvas.width - 1, Math.max(0, page.aim[0] + moves[event.key][0]));
    page.aim[1] = Math.min(canvas.height - 1, Math.max(0, page.aim[1] + moves[event.key][1]));
  } else if (event.key === "Enter" || event.key === " ") {
    triggerAt(page.aim[0], page.aim[1]);
  } else {
    return;
  }
  event.preventDefault();
  showAim();
}

// ---- the timeline ----------------------------------------------------------------------

function loopSeconds() {
  const v = Number($("loop-seconds").value);
  return v > 0 ? v : 8;
}

function setPlaying(on) {
  page.playing = on;
  const b = $("play");
  b.textContent = on ? "Pause" : "Play";
  b.setAttribute("aria-pressed", String(on));
  page.lastNow = null;
}

function setTime(t) {
  page.time = Math.max(0, t);
  page.dirty = true;
}

function showTime() {
  const scrub = $("scrub");
  const max = $("loop").checked ? loopSeconds() : Math.max(loopSeconds(), Math.ceil(page.time));
  scrub.max = String(max);
  scrub.value = String(page.time);
  const text = `${page.time.toFixed(2)} s`;
  scrub.setAttribute("aria-valuetext", text);
  $("time").textContent = text;
}

function drawFrame() {
  const rc = page.api.frame(page.time);
  if (rc !== 0) log(0, "frame: " + page.api.message());
  page.frames++;
  page.dirty = false;
}

function tick(now) {
  followSize();
  if (page.playing) {
    const dt = page.lastNow === null ? 0 : Math.min((now - page.lastNow) / 1000, 0.25);
    page.lastNow = now;
    page.time += dt;
    if ($("loop").checked && page.time >= loopSeconds()) page.time = 0; // starts the timeline again
    page.dirty = true;
  }
  if (page.dirty) {
    drawFrame();
    showTime();
  }
  if (now - page.lastStats > 250) {
    showStats();
    if (page.infoPending) showInfo(); // the particle target is made at the first frame that draws
    page.lastStats = now;
  }
  requestAnimationFrame(tick);
}

// ---- settings and panels ---------------------------------------------------------------

function applySettings() {
  const n = (id) => Number($(id).value);
  const exposure = $("q-exposure").value === "" ? 0 : Number($("q-exposure").value);
  const rc = page.api.settings(n("q-scale"), n("q-opacity"), n("q-format"), n("q-upsample"), n("q-tone-map"), exposure);
  if (rc !== 0) log(0, "settings refused (the previous ones stay): " + page.api.message());
  page.dirty = true;
  showInfo();
}

function showStats() {
  const s = JSON.parse(page.api.stats());
  const dl = $("stats");
  dl.textContent = "";
  for (const [k, v] of Object.entries(s)) {
    const dt = document.createElement("dt");
    dt.textContent = k;
    const dd = document.createElement("dd");
    dd.textContent = typeof v === "number" && !Number.isInteger(v) ? v.toFixed(3) : String(v);
    dl.append(dt, dd);
  }
}

function showInfo() {
  const i = JSON.parse(page.api.info());
  page.infoPending = i.target_format === "default";
  $("gl-status").textContent = `${i.version} · ${i.renderer} · target ${i.target_format}`;
  const notes = [
    i.timer_query
      ? "GPU timer queries: offered."
      : "No GPU timer queries in WebGL 2 (GL_EXT_disjoint_timer_query): a scene's frame budget cannot measure itself; the library takes its fallback, the time this page measures around sbfx_render (glFinish before and after).",
    i.color_buffer_float || i.color_buffer_half_float
      ? `Float targets colour-renderable (EXT_color_buffer_${i.color_buffer_float ? "float" : "half_float"}): the particle target is ${i.target_format}.`
      : "No float colour targets here: the particle target falls back to RGBA8 (logged), as on a GLES 3.0 GPU without EXT_color_buffer_half_float.",
    i.float_blend ? "Blending into 32-bit float targets: offered (EXT_float_blend)." : "No blending into RGBA32F (EXT_float_blend missing): rgba32f falls back as on GLES 3.0.",
    "Detail clips (FFmpeg), V4L2 cameras, GPIO, DIS and MQTT triggers are sbfx-play's, not the page's: clicks and the scene's timeline set effects off here.",
    "Reversed-Z needs glClipControlEXT: Chromium offers WebGL's EXT_clip_control, but this build's emscripten (Debian 12's 3.1.6) does not bind it; the page's host uses the default depth, as sbfx-play does.",
  ];
  const ul = $("webgl-notes");
  ul.textContent = "";
  for (const t of notes) {
    const li = document.createElement("li");
    li.textContent = t;
    ul.appendChild(li);
  }
}

// ---- examples and download ---------------------------------------------------------------

async function listExamples() {
  try {
    const names = await (await fetch("scenes/index.json")).json();
    for (const name of names) $("example").add(new Option(name, name));
  } catch (e) {
    log(1, "no example list (scenes/index.json): " + e);
  }
}

async function openExample() {
  const name = $("example").value;
  if (!name) return;
  const text = await (await fetch("scenes/" + encodeURIComponent(name))).text();
  $("scene-text").value = text;
  clearTimeout(page.reloadTimer);
  loadText(text);
}

function download() {
  const blob = new Blob([$("scene-text").value], { type: "text/plain" });
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  const example = $("example").value;
  a.download = example || SCENE_NAME;
  document.body.appendChild(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

async function copyLink() {
  await addressWrite;
  try {
    await navigator.clipboard.writeText(location.href);
    $("click-status").textContent = "Link copied: it opens this scene.";
  } catch (e) {
    $("click-status").textContent = "The address bar holds the link to this scene.";
  }
}

// ---- start ----------------------------------------------------------------------------

function wireControls() {
  $("scene-text").addEventListener("input", scheduleReload);
  $("goto-error").addEventListener("click", gotoErrorLine);
  $("play").addEventListener("click", () => setPlaying(!page.playing));
  $("restart").addEventListener("click", () => setTime(0));
  $("scrub").addEventListener("input", (e) => {
    setPlaying(false);
    setTime(Number(e.target.value));
  });
  $("open-example").addEventListener("click", openExample);
  $("download").addEventListener("click", download);
  $("copy-link").addEventListener("click", copyLink);
  for (const id of ["q-scale", "q-opacity", "q-format", "q-upsample", "q-tone-map", "q-exposure"])
    $(id).addEventListener("change", applySettings);
  const canvas = $("sbfx-canvas");
  canvas.addEventListener("click", (e) => {
    const [x, y] = canvasPixel(e);
    page.aim = [x, y];
    showAim();
    triggerAt(x, y);
  });
  canvas.addEventListener("keydown", onCanvasKey);
  window.addEventListener("hashchange", async () => {
    const text = await decodeScene(location.hash);
    if (text !== null && text !== page.goodText) {
      $("scene-text").value = text;
      loadText(text);
    }
  });
}

// What the browser tests use: a frame at a time, its pixels, the module's answers.
window.sbfxPage = {
  page,
  setPlaying,
  setTime,
  loadText,
  triggerAt,
  drawAt(t) {
    setPlaying(false);
    page.time = t;
    drawFrame();
    showTime();
  },
  pixels() {
    const ptr = page.api.readPixels();
    if (!ptr) throw new Error(page.api.message());
    const canvas = $("sbfx-canvas");
    return page.module.HEAPU8.slice(ptr, ptr + canvas.width * canvas.height * 4);
  },
  project: (x, y, z) => [page.api.project(x, y, z, 0), page.api.project(x, y, z, 1)],
  pick: (x, y) => [0, 1, 2].map((a) => page.api.pick(x, y, a)),
  stats: () => JSON.parse(page.api.stats()),
  info: () => JSON.parse(page.api.info()),
  address: () => addressWrite.then(() => location.href),
  ready: null,
};

async function main() {
  const size = /^(\d+)x(\d+)$/.exec(params.get("size") || "");
  if (size) page.fixedSize = [Number(size[1]), Number(size[2])];
  wireControls();
  setPlaying(page.playing);
  const canvas = $("sbfx-canvas");
  if (page.fixedSize) canvas.classList.add("fixed");
  page.module = await createSbfx({ onSbfxLog: log, print: (t) => log(2, t), printErr: (t) => log(1, t) });
  page.api = wrap(page.module);
  const [w, h] = wantedSize();
  canvas.width = w;
  canvas.height = h;
  if (page.api.start("#sbfx-canvas", w, h) !== 0) {
    $("gl-status").textContent = "sbfx could not start: " + page.api.message();
    console.error("sbfx: start: " + page.api.message());
    return;
  }
  let fromAddress = null;
  try {
    fromAddress = location.hash ? await decodeScene(location.hash) : null;
  } catch (e) {
    log(1, `the address's scene cannot be read (${e.message || e}): the example plays`);
  }
  const example = params.get("example");
  await listExamples();
  let text = fromAddress;
  if (text === null && example) {
    text = await (await fetch("scenes/" + encodeURIComponent(example))).text();
    $("example").value = example;
  }
  if (text === null) {
    text = await (await fetch("scenes/explosion.cfg")).text();
    $("example").value = "explosion.cfg";
  }
  $("scene-text").value = text;
  if (!loadText(text)) log(1, "the scene from the address did not load: the built-in explosion plays");
  fillEffects();
  drawFrame(); // the first frame: the target format in use is known after it
  showInfo();
  requestAnimationFrame(tick);
}

window.sbfxPage.ready = main().catch((e) => {
  console.error("sbfx page: " + (e && e.stack ? e.stack : e));
  throw e;
});
