// Headless Chromium driven over its DevTools protocol through a pipe (--remote-debugging-pipe:
// JSON messages ended by a NUL byte on file descriptors 3 and 4), with a static file server of
// its own for build/web/: nothing but node and Debian's chromium (tests/web/; docs/web.md).
"use strict";

const { spawn } = require("child_process");
const fs = require("fs");
const http = require("http");
const os = require("os");
const path = require("path");

const TYPES = {
  ".html": "text/html; charset=utf-8",
  ".js": "text/javascript; charset=utf-8",
  ".css": "text/css; charset=utf-8",
  ".wasm": "application/wasm",
  ".json": "application/json",
  ".cfg": "text/plain; charset=utf-8",
  ".png": "image/png",
};

// Serves `root` on 127.0.0.1 at a free port; resolves to { server, origin, missing: [urls] }.
function serve(root) {
  const missing = [];
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, "http://127.0.0.1");
    const file = path.join(root, path.normalize(decodeURIComponent(url.pathname)).replace(/^(\.\.[/\\])+/, ""));
    fs.readFile(file.endsWith("/") ? file + "index.html" : file, (err, data) => {
      if (err) {
        missing.push(url.pathname);
        res.writeHead(404);
        res.end();
        return;
      }
      res.writeHead(200, { "Content-Type": TYPES[path.extname(file)] || "application/octet-stream" });
      res.end(data);
    });
  });
  return new Promise((resolve) =>
    server.listen(0, "127.0.0.1", () => resolve({ server, origin: `http://127.0.0.1:${server.address().port}`, missing })));
}

// The flags: headless, WebGL 2 through ANGLE over SwiftShader (no GPU needed), and none of the
// background connections a closed network refuses (docs/web.md).
function chromiumArgs(profile) {
  return [
    "--headless=new", "--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
    "--remote-debugging-pipe", `--user-data-dir=${profile}`, "--disable-background-networking",
    "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-default-apps",
    "--disable-extensions", "--mute-audio", "--hide-scrollbars", "--window-size=1280,900", "about:blank",
  ];
}

class Browser {
  static async launch(executable = process.env.CHROMIUM || "/usr/bin/chromium") {
    const profile = fs.mkdtempSync(path.join(os.tmpdir(), "sbfx-web-"));
    const child = spawn(executable, chromiumArgs(profile), { stdio: ["ignore", "ignore", "pipe", "pipe", "pipe"] });
    const b = new Browser(child, profile);
    child.stderr.on("data", (d) => { b.stderr += d; });
    await b.send("Browser.getVersion").then((v) => { b.version = v.product; });
    return b;
  }

  constructor(child, profile) {
    this.child = child;
    this.profile = profile;
    this.stderr = "";
    this.nextId = 1;
    this.pending = new Map();
    this.listeners = [];
    let buffer = Buffer.alloc(0);
    child.stdio[4].on("data", (chunk) => {
      buffer = Buffer.concat([buffer, chunk]);
      for (let end; (end = buffer.indexOf(0)) >= 0; buffer = buffer.subarray(end + 1)) this.receive(JSON.parse(buffer.subarray(0, end)));
    });
    this.exited = new Promise((resolve) => child.on("exit", resolve));
    this.exited.then((code) => {
      for (const { reject } of this.pending.values()) reject(new Error(`chromium exited (${code}): ${this.stderr.slice(-2000)}`));
    });
  }

  receive(msg) {
    if (msg.id && this.pending.has(msg.id)) {
      const { resolve, reject, method } = this.pending.get(msg.id);
      this.pending.delete(msg.id);
      if (msg.error) reject(new Error(`${method}: ${msg.error.message} ${msg.error.data || ""}`));
      else resolve(msg.result);
      return;
    }
    for (const l of this.listeners) l(msg);
  }

  send(method, params = {}, sessionId, timeoutMs = 120000) {
    const id = this.nextId++;
    const msg = { id, method, params };
    if (sessionId) msg.sessionId = sessionId;
    return new Promise((resolve, reject) => {
      const timer = setTimeout(() => {
        this.pending.delete(id);
        reject(new Error(`${method}: no answer within ${timeoutMs / 1000} s`));
      }, timeoutMs);
      this.pending.set(id, {
        method,
        resolve: (r) => { clearTimeout(timer); resolve(r); },
        reject: (e) => { clearTimeout(timer); reject(e); },
      });
      this.child.stdio[3].write(JSON.stringify(msg) + "\0");
    });
  }

  async newPage() {
    const { targetId } = await this.send("Target.createTarget", { url: "about:blank" });
    const { sessionId } = await this.send("Target.attachToTarget", { targetId, flatten: true });
    const page = new Page(this, sessionId, targetId);
    this.listeners.push((msg) => { if (msg.sessionId === sessionId) page.event(msg); });
    await page.send("Runtime.enable");
    await page.send("Log.enable");
    await page.send("Page.enable");
    return page;
  }

  async close() {
    try {
      await this.send("Browser.close", {}, undefined, 10000);
    } catch (e) {
      this.child.kill("SIGKILL");
    }
    await this.exited;
    fs.rmSync(this.profile, { recursive: true, force: true });
  }
}

class Page {
  constructor(browser, sessionId, targetId) {
    this.browser = browser;
    this.sessionId = sessionId;
    this.targetId = targetId;
    this.console = []; // { type, text }
    this.errors = []; // console errors, exceptions, error log entries
    this.loadWaiters = [];
  }

  send(method, params, timeoutMs) { return this.browser.send(method, params, this.sessionId, timeoutMs); }

  event(msg) {
    const p = msg.params || {};
    if (msg.method === "Runtime.consoleAPICalled") {
      const text = p.args.map((a) => (a.value !== undefined ? String(a.value) : a.description || "")).join(" ");
      this.console.push({ type: p.type, text });
      if (p.type === "error" || p.type === "assert") this.errors.push(`console.${p.type}: ${text}`);
    } else if (msg.method === "Runtime.exceptionThrown") {
      const d = p.exceptionDetails;
      this.errors.push(`exception: ${d.exception ? d.exception.description : d.text}`);
    } else if (msg.method === "Log.entryAdded") {
      // the browser's own messages: a refused WebGL call ("WebGL: INVALID_VALUE: ...") is a warning
      this.console.push({ type: `log-${p.entry.level}`, text: p.entry.text });
      if (p.entry.level === "error") this.errors.push(`log: ${p.entry.source}: ${p.entry.text} ${p.entry.url || ""}`);
    } else if (msg.method === "Page.loadEventFired") {
      this.loadWaiters.splice(0).forEach((w) => w());
    }
  }

  async goto(url) {
    const loaded = new Promise((resolve) => this.loadWaiters.push(resolve));
    const r = await this.send("Page.navigate", { url });
    if (r.errorText) throw new Error(`navigate ${url}: ${r.errorText}`);
    await loaded;
  }

  // The value of an expression in the page (promises awaited), as JSON.
  async eval(expression, timeoutMs) {
    const r = await this.send("Runtime.evaluate", { expression, awaitPromise: true, returnByValue: true }, timeoutMs);
    if (r.exceptionDetails) {
      const d = r.exceptionDetails;
      throw new Error(`in the page: ${d.exception ? d.exception.description : d.text}`);
    }
    return r.result.value;
  }

  // RGBA bytes of the page's last frame (bottom row first, as glReadPixels gives them).
  async pixels() {
    const b64 = await this.eval(`(() => { const p = sbfxPage.pixels(); let s = "";
      for (let i = 0; i < p.length; i += 0x8000) s += String.fromCharCode.apply(null, p.subarray(i, i + 0x8000));
      return btoa(s); })()`);
    return Buffer.from(b64, "base64");
  }

  async click(x, y) {
    for (const type of ["mouseMoved", "mousePressed", "mouseReleased"])
      await this.send("Input.dispatchMouseEvent", { type, x, y, button: type === "mouseMoved" ? "none" : "left", clickCount: 1 });
  }

  async screenshot(file) {
    const { data } = await this.send("Page.captureScreenshot", { format: "png" });
    fs.writeFileSync(file, Buffer.from(data, "base64"));
  }
}

module.exports = { serve, Browser };
