// The accuracy suites on a second OpenGL ES implementation (docs/web.md "A second OpenGL ES"):
// each GL suite built with emscripten (make test-web-suites) runs in a page of headless
// Chromium, WebGL 2 through ANGLE over SwiftShader, its tests one after another (CHECK_NOFORK);
// its lines are read off the console and printed prefixed "browser:" (and "browser-precision:"
// for the run under SBFX_MEDIUMP=native SBFX_FILTER_BITS=8, as tests/precision.sh runs them).
// Exits 1 when a test failed or a suite did not finish.
// Usage: node tests/web/suites.js SUITES_DIR NAME...   (SUITE_TIMEOUT: seconds per suite, 600)
"use strict";

const fs = require("fs");
const path = require("path");
const { serve, Browser } = require("./cdp.js");

const RUNS = [
  { prefix: "browser:", env: "" },
  { prefix: "browser-precision:", env: "SBFX_MEDIUMP=native,SBFX_FILTER_BITS=8" },
];
// and, as tests/precision.sh's part 6-bit, the hard cases NVIDIA failed again at 6 bits
const SIX_BIT = { prefix: "browser-6-bit:", env: "SBFX_MEDIUMP=native,SBFX_FILTER_BITS=6", suite: "test_gl_hard_cases" };
function sixBitCases() {
  const m = /SIX_BIT_CASES="([^"]*)"/.exec(fs.readFileSync(path.join(__dirname, "..", "precision.sh"), "utf8"));
  return m[1].split(/\s+/).filter(Boolean);
}

// One page: the suite (or its test `only`); its exit status and console lines.
async function runPage(browser, origin, name, run, only) {
  const page = await browser.newPage();
  const started = Date.now();
  await page.goto(`${origin}/suite.html?name=${name}&env=${run.env}${only ? `&only=${only}` : ""}`);
  const limit = Number(process.env.SUITE_TIMEOUT || 600) * 1000;
  let exit;
  while ((exit = await page.eval("window.suiteExit", limit)) === undefined) {
    if (Date.now() - started > limit || page.errors.some((e) => e.startsWith("exception"))) break;
    await new Promise((r) => setTimeout(r, 500));
  }
  const lines = page.console.map((c) => c.text);
  await page.send("Target.closeTarget", { targetId: page.targetId }).catch(() => {});
  return { exit, lines, errors: page.errors };
}

// The suite's tests in their order (tests/gl/NAME.c's CHECK_TEST lines).
function testNames(name) {
  const source = fs.readFileSync(path.join(__dirname, "..", "gl", `${name}.c`), "utf8");
  return [...source.matchAll(/^CHECK_TEST\((\w+)\)/gm)].map((m) => m[1]);
}

// A suite in the browser. check.h's CHECK_SKIP ends the process (exit 77: a forked test's way);
// with no fork that ends the page, so the skipped test is reported here with its reason, and the
// tests after it run each in a page of its own.
async function runSuite(browser, origin, name, run) {
  const started = Date.now();
  const counts = { ok: 0, "not ok": 0, skip: 0 };
  const reported = new Set();
  const print = (r) => {
    for (const line of r.lines) {
      const m = /^(ok|not ok|skip) - [^/]*\/(\w+)(.*)$/.exec(line);
      if (m) {
        counts[m[1]]++;
        reported.add(m[2]);
        console.log(`${m[1]} - ${run.prefix}${name}/${m[2]}${m[3]}`);
      } else if (line.startsWith("#") && !line.startsWith("#SKIP")) {
        console.log(line);
      } else if (/^WebGL: /.test(line)) {
        console.log(`# ${line}`); // what the browser says about a refused call
      }
    }
  };
  const ended = (r, expected) => {
    if (r.exit === 77) {
      const skip = r.lines.filter((l) => l.startsWith("#SKIP ")).pop() || "#SKIP (no reason printed)";
      const test = expected.find((t) => !reported.has(t));
      counts.skip++;
      reported.add(test);
      console.log(`skip - ${run.prefix}${name}/${test}: ${skip.slice(6)}`);
      return true;
    }
    if (r.exit === undefined) {
      counts["not ok"]++;
      console.log(`not ok - ${run.prefix}${name}: did not finish within its limit: ${r.errors.join("; ")}`);
    } else if (r.exit !== 0 && !r.lines.some((l) => l.startsWith("not ok - "))) {
      counts["not ok"]++;
      console.log(`not ok - ${run.prefix}${name}: exited with status ${r.exit} without reporting a failed test: ${r.errors.join("; ")}`);
    }
    return false;
  };
  const all = testNames(name);
  let r = await runPage(browser, origin, name, run, null);
  print(r);
  if (ended(r, all))
    for (const test of all.filter((t) => !reported.has(t))) {
      r = await runPage(browser, origin, name, run, test);
      print(r);
      ended(r, [test]);
    }
  console.log(`# ${run.prefix}${name}: ${counts.ok} ok, ${counts["not ok"]} not ok, ${counts.skip} skipped, ` +
    `${((Date.now() - started) / 1000).toFixed(1)} s`);
  return counts["not ok"];
}

async function runSixBit(browser, origin) {
  let failed = 0;
  for (const test of sixBitCases()) {
    const r = await runPage(browser, origin, SIX_BIT.suite, SIX_BIT, test);
    const result = r.lines.find((l) => /^(ok|not ok|skip) - /.test(l));
    for (const l of r.lines) if (l.startsWith("#") && !l.startsWith("#SKIP")) console.log(l);
    if (!result || r.exit === undefined) {
      failed++;
      console.log(`not ok - ${SIX_BIT.prefix}${SIX_BIT.suite}/${test}: no result (exit ${r.exit})`);
    } else {
      if (result.startsWith("not ok")) failed++;
      console.log(result.replace(/ - [^/]*\//, ` - ${SIX_BIT.prefix}${SIX_BIT.suite}/`));
    }
  }
  return failed;
}

async function main() {
  const [root, ...names] = process.argv.slice(2);
  if (!names.length) throw new Error("usage: node tests/web/suites.js SUITES_DIR NAME...");
  const srv = await serve(root);
  const browser = await Browser.launch();
  let failed = 0;
  try {
    for (const run of RUNS) for (const name of names) failed += await runSuite(browser, srv.origin, name, run);
    if (names.includes(SIX_BIT.suite)) failed += await runSixBit(browser, srv.origin);
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
