// The accuracy suites on a second OpenGL ES implementation (docs/web.md "A second OpenGL ES"):
// each GL suite built with emscripten (make test-web-suites) runs in a page of headless
// Chromium, WebGL 2 through ANGLE over SwiftShader, its tests one after another (CHECK_NOFORK);
// its lines are read off the console and printed prefixed "browser:" (and "browser-precision:"
// for the run under SBFX_MEDIUMP=native SBFX_FILTER_BITS=8, as tests/precision.sh runs them).
// Exits 1 when a test failed or a suite did not finish.
// Usage: node tests/web/suites.js SUITES_DIR NAME...   (SUITE_TIMEOUT: seconds per suite, 600)
"use strict";

const { serve, Browser } = require("./cdp.js");

const RUNS = [
  { prefix: "browser:", env: "" },
  { prefix: "browser-precision:", env: "SBFX_MEDIUMP=native,SBFX_FILTER_BITS=8" },
];

async function runSuite(browser, origin, name, run) {
  const page = await browser.newPage();
  const started = Date.now();
  await page.goto(`${origin}/suite.html?name=${name}&env=${run.env}`);
  const limit = Number(process.env.SUITE_TIMEOUT || 600) * 1000;
  let exit;
  while ((exit = await page.eval("window.suiteExit", limit)) === undefined) {
    if (Date.now() - started > limit || page.errors.some((e) => e.startsWith("exception"))) break;
    await new Promise((r) => setTimeout(r, 500));
  }
  const lines = page.console.map((c) => c.text);
  await page.send("Target.closeTarget", { targetId: page.targetId }).catch(() => {});
  return { exit, lines, seconds: (Date.now() - started) / 1000, errors: page.errors };
}

async function main() {
  const [root, ...names] = process.argv.slice(2);
  if (!names.length) throw new Error("usage: node tests/web/suites.js SUITES_DIR NAME...");
  const srv = await serve(root);
  const browser = await Browser.launch();
  let failed = 0;
  try {
    for (const run of RUNS)
      for (const name of names) {
        const r = await runSuite(browser, srv.origin, name, run);
        let counts = { ok: 0, "not ok": 0, skip: 0 };
        for (const line of r.lines) {
          const m = /^(ok|not ok|skip) - (.*)$/.exec(line);
          if (m) {
            counts[m[1]]++;
            console.log(`${m[1]} - ${run.prefix}${m[2]}`);
          } else if (line.startsWith("#")) {
            console.log(line);
          } else if (/^WebGL: /.test(line)) {
            console.log(`# ${line}`); // what the browser says about a refused call
          }
        }
        failed += counts["not ok"];
        if (r.exit === undefined) {
          console.log(`not ok - ${run.prefix}${name}: did not finish within its limit`);
          failed++;
        } else if (r.exit !== 0 && !counts["not ok"]) {
          console.log(`not ok - ${run.prefix}${name}: exited with status ${r.exit} without reporting a failed test: ${r.errors.join("; ")}`);
          failed++;
        }
        console.log(`# ${run.prefix}${name}: ${counts.ok} ok, ${counts["not ok"]} not ok, ${counts.skip} skipped, ${r.seconds.toFixed(1)} s`);
      }
  } finally {
    await browser.close();
    srv.server.close();
  }
  process.exit(failed ? 1 : 0);
}

main().catch((e) => {
  console.log(`not ok - web_suites: ${e.message}`);
  process.exit(1);
});
