// The page's picture for docs/web.md: the explosion at 1.2 s in the authoring page, 1280x1240,
// a click's effect set off on the ground to its left. Usage: node tests/web/screenshot.js BUILD_WEB OUT.png
"use strict";

const { serve, Browser } = require("./cdp.js");

(async () => {
  const [root, out] = process.argv.slice(2);
  const srv = await serve(root);
  const browser = await Browser.launch();
  try {
    const page = await browser.newPage();
    await page.send("Emulation.setDeviceMetricsOverride", { width: 1280, height: 1240, deviceScaleFactor: 1, mobile: false });
    await page.goto(`${srv.origin}/index.html?paused`);
    await page.eval("sbfxPage.ready", 120000);
    await page.eval("sbfxPage.drawAt(0.4)");
    const [x, y] = await page.eval("sbfxPage.project(-2.2, 0, 1.0)");
    await page.eval(`sbfxPage.triggerAt(${x}, ${y})`);
    await page.eval("sbfxPage.drawAt(1.2)");
    await page.eval("new Promise((r) => setTimeout(r, 600))"); // the panels' next update
    await page.screenshot(out);
    if (page.errors.length) throw new Error(page.errors.join("; "));
  } finally {
    await browser.close();
    srv.server.close();
  }
})().catch((e) => {
  console.error(`screenshot: ${e.message}`);
  process.exit(1);
});
