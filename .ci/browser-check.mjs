// CI: opens a report's index.html in headless Chromium at 1400 px through the DevTools protocol
// and checks what a reader gets (issue 16, item 7). Node's standard library only: Chromium is
// driven over --remote-debugging-pipe (JSON messages ending in NUL on file descriptors 3 and 4),
// so nothing is installed from npm.
//
// usage: node .ci/browser-check.mjs <report dir> [chromium binary]
// Prints each check with its measured value; exits 1 if any fails. Writes <report>/screenshot.png
// (the first screen) and <report>/print.pdf (the page printed as Chromium prints it: A4, the
// page's print style), whose pages are counted.
import { spawn } from "node:child_process";
import { mkdtempSync, rmSync, statSync, writeFileSync, existsSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const WIDTH = 1400;
const HEIGHT = 900;
const MOST_BYTES = 3 * 1000 * 1000; // 3 MB: everything the page loads
const MOST_PAGES = 20; // printed A4 pages (issue 33: a hand-in document; 71 before the appendix moved out)
const SCREEN = { width: 1280, height: 1000 }; // the window issue 33 counted its screens in (125 for the whole report then)
const MOST_SCREENS = 35; // the main document (summary, answers, discussion): "about 35" (issue 33)
const report = resolve(process.argv[2] ?? "");
const browser = process.argv[3] ?? "/usr/bin/chromium";
const page = join(report, "index.html");
if (!existsSync(page)) {
  console.error(`no ${page}`);
  process.exit(2);
}

const profile = mkdtempSync(join(tmpdir(), "browser-check-"));
const chromium = spawn(
  browser,
  [
    "--headless=new", "--remote-debugging-pipe", "--no-sandbox", "--disable-gpu", "--no-first-run",
    "--disable-extensions", "--hide-scrollbars", `--user-data-dir=${profile}`, `--window-size=${WIDTH},${HEIGHT}`,
    "about:blank",
  ],
  { stdio: ["ignore", "ignore", "pipe", "pipe", "pipe"] },
);
let chromiumLog = "";
chromium.stderr.on("data", (d) => (chromiumLog += d));
const watchdog = setTimeout(() => fail("timed out after 120 s"), 120_000);

// The protocol: requests by id, events to listeners.
let nextId = 1;
const waiting = new Map();
const listeners = [];
let buffer = "";
chromium.stdio[4].on("data", (chunk) => {
  buffer += chunk.toString("utf8");
  let end;
  while ((end = buffer.indexOf("\0")) >= 0) {
    const message = JSON.parse(buffer.slice(0, end));
    buffer = buffer.slice(end + 1);
    if (message.id && waiting.has(message.id)) {
      const { ok, ko } = waiting.get(message.id);
      waiting.delete(message.id);
      message.error ? ko(new Error(`${message.error.message} ${message.error.data ?? ""}`)) : ok(message.result);
    } else if (message.method) {
      for (const listen of listeners) listen(message);
    }
  }
});
function send(method, params = {}, sessionId) {
  const id = nextId++;
  chromium.stdio[3].write(JSON.stringify({ id, method, params, sessionId }) + "\0");
  return new Promise((ok, ko) => waiting.set(id, { ok, ko }));
}
function fail(why) {
  console.error(`FAIL: ${why}`);
  if (chromiumLog) console.error(chromiumLog.slice(-2000));
  chromium.kill();
  try {
    rmSync(profile, { recursive: true, force: true, maxRetries: 3 });
  } catch {}
  process.exit(1);
}

// Opens `file` in a tab of its own and measures what a reader gets; `first` (the report's main
// page) also keeps its first screen and its print.
async function visit(file, first) {
  const { targetId } = await send("Target.createTarget", { url: "about:blank" });
  const { sessionId } = await send("Target.attachToTarget", { targetId, flatten: true });
  const call = (method, params) => send(method, params, sessionId);
  // What the page loads, and what goes wrong while it does.
  const errors = [];
  const requested = new Map(); // requestId -> url
  const encoded = new Map(); // requestId -> bytes as loaded
  let loaded;
  const load = new Promise((ok) => (loaded = ok));
  listeners.push((m) => {
    if (m.sessionId !== sessionId) return;
    const p = m.params;
    if (m.method === "Runtime.consoleAPICalled" && (p.type === "error" || p.type === "assert"))
      errors.push(`console.${p.type}: ${p.args.map((a) => a.value ?? a.description).join(" ")}`);
    else if (m.method === "Runtime.exceptionThrown") errors.push(`exception: ${p.exceptionDetails.text}`);
    else if (m.method === "Log.entryAdded" && p.entry.level === "error") errors.push(`${p.entry.source}: ${p.entry.text} ${p.entry.url ?? ""}`);
    else if (m.method === "Network.requestWillBeSent") requested.set(p.requestId, p.request.url);
    else if (m.method === "Network.loadingFinished") encoded.set(p.requestId, p.encodedDataLength);
    else if (m.method === "Network.loadingFailed") errors.push(`failed to load ${requested.get(p.requestId)}: ${p.errorText}`);
    else if (m.method === "Page.loadEventFired") loaded();
  });
  for (const domain of ["Page", "Runtime", "Log", "Network"]) await call(`${domain}.enable`);
  await call("Emulation.setDeviceMetricsOverride", { width: WIDTH, height: HEIGHT, deviceScaleFactor: 1, mobile: false });
  await call("Page.navigate", { url: pathToFileURL(file).href });
  await load;
  if (first) {
    const screenshot = await call("Page.captureScreenshot", { format: "png" });
    writeFileSync(join(report, "screenshot.png"), Buffer.from(screenshot.data, "base64"));
  }
  // Lazy images load as they come near the window: ask for all of them, as a reader scrolling
  // through would, and wait until each has loaded or failed.
  const evaluate = async (expression) => {
    const { result, exceptionDetails } = await call("Runtime.evaluate", { expression, awaitPromise: true, returnByValue: true });
    if (exceptionDetails) throw new Error(`${expression}: ${exceptionDetails.text}`);
    return result.value;
  };
  await evaluate(`Promise.all([...document.images].map((img) => { img.loading = "eager";
    return img.complete ? null : new Promise((done) => { img.onload = img.onerror = done; }); }))`);
  await new Promise((ok) => setTimeout(ok, 300)); // the last loadingFinished events
  const facts = await evaluate(`(() => {
    const images = [...document.images];
    const ids = new Set([...document.querySelectorAll("[id]")].map((e) => e.id));
    const headings = [...document.querySelectorAll("h1, h2, h3, h4, h5, h6")];
    const anchors = [...document.querySelectorAll('a[href^="#"]')];
    const local = [...document.querySelectorAll("a[href]")].map((a) => a.getAttribute("href"))
      .filter((h) => !h.startsWith("#") && !/^[a-z]+:/i.test(h));
    return {
      images: images.length,
      broken: images.filter((i) => !(i.complete && i.naturalWidth > 0)).map((i) => i.getAttribute("src")),
      unsized: images.filter((i) => !(i.getAttribute("width") && i.getAttribute("height"))).map((i) => i.getAttribute("src")),
      movies: images.filter((i) => /\\.gif$/i.test(i.getAttribute("src"))).length,
      scrollWidth: document.documentElement.scrollWidth,
      headings: headings.length,
      withoutId: headings.filter((h) => !h.id).map((h) => h.textContent.slice(0, 60)),
      duplicateIds: [...document.querySelectorAll("[id]")].length - ids.size,
      contents: document.querySelectorAll("nav.contents a").length,
      anchors: anchors.length,
      unresolved: anchors.map((a) => decodeURIComponent(a.hash.slice(1))).filter((id) => !ids.has(id)),
      local: [...new Set(local)],
      // Displayed equations laid out as MathML: under plain CSS "display: block" Chromium laid
      // each fraction out as a full-width block and lost the "=" between the terms.
      equations: document.querySelectorAll('math[display="block"]').length,
      fullWidthFractions: [...document.querySelectorAll('math[display="block"] mfrac')]
        .filter((f) => f.getBoundingClientRect().width >= f.closest("math").getBoundingClientRect().width - 1).length,
    };
  })()`);
  if (first) {
    // Its length: screens of SCREEN at that width, and pages printed (Chromium's own PDF, with
    // the page's @page size; a page object per page in the file).
    await call("Emulation.setDeviceMetricsOverride", { ...SCREEN, deviceScaleFactor: 1, mobile: false });
    facts.screens = (await evaluate("document.documentElement.scrollHeight")) / SCREEN.height;
    const { data: pdf } = await call("Page.printToPDF", { preferCSSPageSize: true });
    const printed = Buffer.from(pdf, "base64");
    writeFileSync(join(report, "print.pdf"), printed);
    facts.pages = (printed.toString("latin1").match(/\/Type\s*\/Page(?![s\w])/g) ?? []).length;
  }
  // Bytes: the files the page loaded (their sizes on disk, which is what a file:// page
  // transfers; Chromium's encodedDataLength is printed beside it).
  const files = new Set([...requested.values()].filter((u) => u.startsWith("file:")).map((u) => fileURLToPath(u.split("#")[0])));
  facts.files = files.size;
  facts.bytes = [...files].reduce((sum, f) => sum + (existsSync(f) ? statSync(f).size : 0), 0);
  facts.encodedBytes = [...encoded.values()].reduce((s, b) => s + b, 0);
  facts.missingLinks = facts.local.filter((h) => !existsSync(join(report, decodeURIComponent(h.split("#")[0]))));
  facts.errors = errors;
  await send("Target.closeTarget", { targetId });
  return facts;
}

async function main() {
  const started = Date.now();
  const main = await visit(page, true);
  // The appendix, where the report has one: its own page, linked from the main one.
  const appendixFile = join(report, "appendix.html");
  const appendix = existsSync(appendixFile) ? await visit(appendixFile, false) : null;
  const both = appendix ? [main, appendix] : [main];
  const all = (key) => both.flatMap((f) => f[key]);
  const sum = (key) => both.reduce((s, f) => s + f[key], 0);
  const pages = appendix ? "index.html and appendix.html" : "index.html";

  const checks = [
    [`every image and movie loads (${pages})`, all("broken").length === 0,
      `${sum("images") - all("broken").length}/${sum("images")} (${sum("movies")} movies)${all("broken").length ? ": " + all("broken").slice(0, 5).join(", ") : ""}`],
    ["every image has its width and height", all("unsized").length === 0,
      `${sum("images") - all("unsized").length}/${sum("images")}${all("unsized").length ? ": " + all("unsized").slice(0, 5).join(", ") : ""}`],
    ["no console errors", all("errors").length === 0, all("errors").length ? all("errors").slice(0, 5).join(" | ") : "0"],
    [`page width <= ${WIDTH} px`, both.every((f) => f.scrollWidth <= WIDTH), `scrollWidth ${both.map((f) => f.scrollWidth).join(", ")} px`],
    ["every heading has an id", all("withoutId").length === 0 && sum("duplicateIds") === 0,
      `${sum("headings") - all("withoutId").length}/${sum("headings")}, ${sum("duplicateIds")} duplicate ids${all("withoutId").length ? ": " + all("withoutId").join(" | ") : ""}`],
    ["every contents link resolves", main.contents > 0 && all("unresolved").length === 0,
      `${sum("anchors") - all("unresolved").length}/${sum("anchors")} #links (${main.contents} in the contents)${all("unresolved").length ? ": " + all("unresolved").slice(0, 5).join(", ") : ""}`],
    ["every local link resolves", all("missingLinks").length === 0,
      `${main.local.length + (appendix?.local.length ?? 0) - all("missingLinks").length}/${main.local.length + (appendix?.local.length ?? 0)}${all("missingLinks").length ? ": " + all("missingLinks").slice(0, 5).join(", ") : ""}`],
    ["displayed equations laid out as MathML", sum("equations") > 0 && sum("fullWidthFractions") === 0,
      `${sum("equations")} equations, ${sum("fullWidthFractions")} fractions as wide as their equation`],
    [`index.html printed in <= ${MOST_PAGES} A4 pages`, main.pages > 0 && main.pages <= MOST_PAGES, `${main.pages} pages (${join(report, "print.pdf")})`],
    [`index.html <= ${MOST_SCREENS} screens of ${SCREEN.width} x ${SCREEN.height} px`, main.screens <= MOST_SCREENS, `${main.screens.toFixed(1)} screens`],
    [`index.html loads <= ${MOST_BYTES / 1e6} MB`, main.bytes <= MOST_BYTES,
      `${(main.bytes / 1e6).toFixed(2)} MB in ${main.files} files (Chromium's encoded length ${(main.encodedBytes / 1e6).toFixed(2)} MB)${appendix ? `; appendix.html ${(appendix.bytes / 1e6).toFixed(2)} MB in ${appendix.files} files` : ""}`],
  ];
  let failed = 0;
  for (const [what, ok, value] of checks) {
    console.log(`${ok ? "ok  " : "FAIL"} ${what}: ${value}`);
    if (!ok) failed++;
  }
  console.log(`screenshot: ${join(report, "screenshot.png")} (${WIDTH}x${HEIGHT}); browser check ${((Date.now() - started) / 1000).toFixed(1)} s`);
  clearTimeout(watchdog);
  const exited = new Promise((ok) => chromium.once("exit", ok));
  await send("Browser.close").catch(() => {});
  await Promise.race([exited, new Promise((ok) => setTimeout(ok, 5000))]);
  chromium.kill();
  rmSync(profile, { recursive: true, force: true, maxRetries: 3 });
  process.exit(failed ? 1 : 0);
}

main().catch((error) => fail(error.stack ?? String(error)));
