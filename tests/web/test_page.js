// The authoring page in a real browser (headless Chromium over its DevTools pipe, tests/web/cdp.js):
// it loads and draws the explosion, an edit changes the picture, a broken edit shows its line and
// the old scene plays on, a click sets off an effect where it was clicked, the address brings the
// scene back, and nothing reaches the console as an error. Prints "ok - x" / "not ok - x: why".
// Usage: node tests/web/test_page.js BUILD_WEB [--quick]   (--quick: the page-load case only)
"use strict";

const { serve, Browser } = require("./cdp.js");

const W = 320, H = 180; // the drawing buffer (?size=): small, for SwiftShader
const LEVELS = 24;       // a pixel differs when a channel moves more than this (of 255)

let failures = 0;
function report(name, why) {
  if (why) {
    failures++;
    console.log(`not ok - ${name}: ${why}`);
  } else {
    console.log(`ok - ${name}`);
  }
}

// The pixels (x, y down) where two frames differ by more than LEVELS in a channel.
function differing(a, b) {
  const out = [];
  for (let i = 0; i < W * H; i++) {
    const o = i * 4;
    if (Math.max(Math.abs(a[o] - b[o]), Math.abs(a[o + 1] - b[o + 1]), Math.abs(a[o + 2] - b[o + 2])) > LEVELS)
      out.push([i % W, H - 1 - Math.floor(i / W)]);
  }
  return out;
}

function centroid(points) {
  const s = points.reduce((acc, p) => [acc[0] + p[0], acc[1] + p[1]], [0, 0]);
  return [s[0] / points.length, s[1] / points.length];
}

const sceneTextJs = "document.getElementById('scene-text').value";

// The explosion's text with its timeline moved out of reach: the same ground, sky and camera, no effect.
function emptyScene(text) {
  const empty = text.replace(/time = 0\.0;/, "time = 100000.0;");
  if (empty === text) throw new Error("scenes/explosion.cfg has no 'time = 0.0;' timeline entry to move");
  return empty;
}

async function loads(page, text) {
  return page.eval(`sbfxPage.loadText(${JSON.stringify(text)})`);
}

async function frameAt(page, t) {
  await page.eval(`sbfxPage.drawAt(${t})`);
  return page.pixels();
}

async function drawsTheExplosion(page, ctx) {
  const empty = emptyScene(ctx.explosion);
  if (!(await loads(page, empty))) return "the explosion without its timeline did not load";
  const empty1 = await frameAt(page, 1.0), empty2 = await frameAt(page, 2.0);
  if (!(await loads(page, ctx.explosion))) return "scenes/explosion.cfg did not load";
  const boom1 = await frameAt(page, 1.0), boom2 = await frameAt(page, 2.0);
  ctx.boom1 = boom1;
  const d1 = differing(empty1, boom1), d2 = differing(empty2, boom2);
  if (d1.length < W * H * 0.02) return `at 1 s only ${d1.length} pixels differ from the empty scene`;
  if (d2.length < W * H * 0.02) return `at 2 s only ${d2.length} pixels differ from the empty scene`;
  // the cloud moves: where it covers the picture at 1 s and at 2 s is not the same
  const key = (p) => p[0] + p[1] * W;
  const at1 = new Set(d1.map(key)), at2 = new Set(d2.map(key));
  let changed = 0;
  for (const k of at1) if (!at2.has(k)) changed++;
  for (const k of at2) if (!at1.has(k)) changed++;
  if (changed < W * H * 0.005) return `the explosion did not move between 1 s and 2 s (${changed} pixels changed)`;
  const stats = await page.eval("sbfxPage.stats()");
  if (stats.particles_alive <= 0 || stats.draw_calls <= 0) return `counters say nothing was drawn: ${JSON.stringify(stats)}`;
  return "";
}

async function editChangesPicture(page, ctx) {
  // the dust's colour turned blue, typed into the editor (the debounced reload)
  ctx.edited = ctx.explosion.replace("color = [0.80, 0.70, 0.56]", "color = [0.20, 0.40, 0.95]");
  if (ctx.edited === ctx.explosion) return "scenes/explosion.cfg's dust colour is not where the test expects it";
  await page.eval(`(() => { const a = document.getElementById('scene-text'); a.value = ${JSON.stringify(ctx.edited)};
    a.dispatchEvent(new Event('input')); })()`);
  await page.eval("new Promise((r) => setTimeout(r, 900))");
  const good = await page.eval("sbfxPage.page.goodText");
  if (good !== ctx.edited) return "the edit was not reloaded within 0.9 s";
  ctx.edited1 = await frameAt(page, 1.0);
  const d = differing(ctx.boom1, ctx.edited1);
  if (d.length < 50) return `the edit changed ${d.length} pixels`;
  return "";
}

async function brokenEditKeepsScene(page, ctx) {
  const lines = ctx.edited.split("\n");
  lines.splice(4, 0, "render_oops = ;"); // line 5
  await page.eval(`(() => { const a = document.getElementById('scene-text'); a.value = ${JSON.stringify(lines.join("\n"))};
    a.dispatchEvent(new Event('input')); })()`);
  await page.eval("new Promise((r) => setTimeout(r, 900))");
  const shown = await page.eval(`(() => { const e = document.getElementById('scene-error');
    return { hidden: e.hidden, text: e.textContent, role: e.getAttribute('role'),
             invalid: document.getElementById('scene-text').getAttribute('aria-invalid') }; })()`);
  if (shown.hidden) return "no error shown";
  if (!/Line 5\b/.test(shown.text)) return `the error does not name line 5: ${shown.text.trim()}`;
  if (shown.role !== "alert" || shown.invalid !== "true") return "the error is not announced (role=alert, aria-invalid)";
  const after = await frameAt(page, 1.0);
  const d = differing(ctx.edited1, after);
  if (d.length) return `the old scene did not play on: ${d.length} pixels differ from it`;
  return "";
}

async function clickSetsOffEffect(page, ctx) {
  if (!(await loads(page, emptyScene(ctx.explosion)))) return "the empty scene did not load";
  const base = await frameAt(page, 1.5);
  await page.eval("sbfxPage.drawAt(0.5)");
  const target = [-1.6, 0, 1.2];
  const [cx, cy] = await page.eval(`sbfxPage.project(${target.join(",")})`);
  const rect = await page.eval(`(() => { const r = document.getElementById('sbfx-canvas').getBoundingClientRect();
    return [r.left, r.top, r.width, r.height]; })()`);
  await page.click(rect[0] + (cx * rect[2]) / W, rect[1] + (cy * rect[3]) / H);
  const at = await page.eval("[0, 1, 2].map((a) => sbfxPage.page.api.clickCoordinate(a))");
  const miss = Math.hypot(at[0] - target[0], at[2] - target[2]);
  if (!(miss < 0.15)) return `the click landed at (${at.map((v) => v.toFixed(2))}), ${miss.toFixed(2)} m from (${target})`;
  const fired = (await page.eval("sbfxPage.stats()")).triggers_fired;
  if (fired !== 1) return `triggers_fired ${fired} after one click`;
  const after = await frameAt(page, 1.5);
  const d = differing(base, after);
  if (d.length < 100) return `the effect a second after the click changed ${d.length} pixels`;
  const [mx] = centroid(d);
  if (Math.abs(mx - cx) > W * 0.1) return `the effect is centred at x=${mx.toFixed(0)}, the click at x=${cx.toFixed(0)}`;
  const bottom = Math.max(...d.map((p) => p[1]));
  if (Math.abs(bottom - cy) > H * 0.12) return `the effect stands on y=${bottom}, the click was at y=${cy.toFixed(0)}`;
  return "";
}

async function addressRoundTrips(browser, origin, ctx) {
  const url = ctx.address;
  if (!/#scene=|#text=/.test(url)) return `the address holds no scene: ${url}`;
  const page = await browser.newPage();
  await page.goto(url);
  await page.eval("sbfxPage.ready", 120000);
  const text = await page.eval(sceneTextJs);
  if (text !== ctx.edited) return "the editor of the page opened from the address does not hold the edited scene";
  const px = await frameAt(page, 1.0);
  const d = differing(ctx.edited1, px);
  if (d.length) return `the scene from the address draws ${d.length} pixels differently`;
  ctx.pages.push(page);
  return "";
}

// A scene's frame budget without timer queries: the page times sbfx_render itself (the fallback).
async function budgetIsTimed(page, ctx) {
  const text = ctx.explosion.replace("render = {", "render = {\n  budget_ms = 16.0;");
  if (!(await loads(page, text))) return "the explosion with a frame budget did not load";
  for (let i = 0; i <= 4; i++) await page.eval(`sbfxPage.drawAt(${i} / 4)`);
  const s = await page.eval("sbfxPage.stats()");
  if (s.budget_ms !== 16) return `budget_ms ${s.budget_ms}, the scene says 16`;
  if (!(s.gpu_ms > 0)) return `the budget got no time (gpu_ms ${s.gpu_ms}): the fallback was not fed`;
  return "";
}

// Keyboard: the picture takes focus, arrows move the aim, Enter sets the effect off there.
async function keyboardSetsOffEffect(page, ctx) {
  if (!(await loads(page, emptyScene(ctx.explosion)))) return "the empty scene did not load";
  await page.eval("sbfxPage.drawAt(0.5)");
  await page.eval("document.getElementById('sbfx-canvas').focus()");
  const key = async (key, code, vk) => {
    for (const type of ["keyDown", "keyUp"])
      await page.send("Input.dispatchKeyEvent", { type, key, code, windowsVirtualKeyCode: vk, nativeVirtualKeyCode: vk });
  };
  await key("ArrowLeft", "ArrowLeft", 37);
  await key("Enter", "Enter", 13);
  const fired = (await page.eval("sbfxPage.stats()")).triggers_fired;
  if (fired !== 1) return `triggers_fired ${fired} after Enter on the focused picture`;
  const said = await page.eval("document.getElementById('click-status').textContent");
  if (!/^explosion at \(/.test(said)) return `the status line says "${said}"`;
  return "";
}

// Every form control has a label a screen reader reads (label, aria-label or its text).
async function controlsAreLabelled(page) {
  const unlabelled = await page.eval(`[...document.querySelectorAll("input, select, textarea, button, canvas")]
    .filter((e) => !((e.labels && e.labels.length) || e.getAttribute("aria-label") || e.textContent.trim()))
    .map((e) => e.id || e.tagName)`);
  return unlabelled.length ? `no label: ${unlabelled.join(", ")}` : "";
}

async function brokenLinkFallsBack(browser, origin, ctx) {
  const page = await browser.newPage();
  await page.goto(`${origin}/index.html?size=${W}x${H}&paused#scene=not-a-deflated-scene`);
  await page.eval("sbfxPage.ready", 120000);
  ctx.pages.push(page);
  const text = await page.eval(sceneTextJs);
  if (text !== ctx.explosion) return "a link whose scene cannot be read did not fall back to the example";
  const warned = page.console.some((c) => /cannot be read/.test(c.text));
  if (!warned) return "the page did not say that the link's scene cannot be read";
  return "";
}

async function main() {
  const root = process.argv[2];
  const quick = process.argv.includes("--quick");
  if (!root) throw new Error("usage: node tests/web/test_page.js BUILD_WEB [--quick]");
  const srv = await serve(root);
  const browser = await Browser.launch();
  const ctx = { pages: [] };
  try {
    const page = await browser.newPage();
    ctx.pages.push(page);
    await page.goto(`${srv.origin}/index.html?size=${W}x${H}&paused`);
    await page.eval("sbfxPage.ready", 120000);
    const info = await page.eval("sbfxPage.info()");
    console.log(`# ${browser.version}: ${info.version}, particle target ${info.target_format}`);
    ctx.explosion = await page.eval(sceneTextJs);
    const cases = [["page_loads_and_draws_the_explosion", () => drawsTheExplosion(page, ctx)]];
    if (!quick)
      cases.push(
        ["an_edit_changes_the_picture", () => editChangesPicture(page, ctx)],
        ["a_broken_edit_shows_its_line_and_the_old_scene_plays_on", () => brokenEditKeepsScene(page, ctx)],
        ["the_address_holds_the_scene", async () => { ctx.address = await page.eval("sbfxPage.address()"); return ""; }],
        ["a_click_sets_off_the_effect_where_clicked", () => clickSetsOffEffect(page, ctx)],
        ["a_link_reproduces_the_scene", () => addressRoundTrips(browser, srv.origin, ctx)],
        ["the_keyboard_sets_off_an_effect", () => keyboardSetsOffEffect(page, ctx)],
        ["every_control_is_labelled", () => controlsAreLabelled(page)],
        ["a_scene_budget_is_timed_by_the_page", () => budgetIsTimed(page, ctx)],
        ["a_broken_link_plays_the_example", () => brokenLinkFallsBack(browser, srv.origin, ctx)],
      );
    for (const [name, run] of cases) {
      let why;
      try {
        why = await run();
      } catch (e) {
        why = e.message;
      }
      report(name, why);
    }
    const errors = ctx.pages.flatMap((p) => p.errors);
    report("no_console_errors", errors.length ? errors.join("; ") : "");
    if (srv.missing.length) report("no_missing_files", srv.missing.join(", "));
  } finally {
    await browser.close();
    srv.server.close();
  }
  process.exit(failures ? 1 : 0);
}

main().catch((e) => {
  console.log(`not ok - web_page: ${e.message}`);
  process.exit(1);
});
