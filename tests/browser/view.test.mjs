// End-to-end test of `pathlab view` in headless Chromium: the page loads, the
// image updates as passes land, the A/B split and the error plot are drawn, a
// sampler switched through the page restarts accumulation, and nothing logs
// an error.
//   node view.test.mjs URL ARTIFACT_DIR
// Uses Debian's /usr/bin/chromium (or $PATHLAB_CHROMIUM); never downloads one.
import assert from "node:assert/strict";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import { chromium } from "playwright-core";

const [url, artifactDir] = process.argv.slice(2);
if (!url || !artifactDir) {
  console.error("usage: node view.test.mjs URL ARTIFACT_DIR");
  process.exit(2);
}
fs.mkdirSync(artifactDir, { recursive: true });

const profile = fs.mkdtempSync(path.join(os.tmpdir(), "pathlab-chromium-"));
const context = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.PATHLAB_CHROMIUM || "/usr/bin/chromium",
  headless: true,
  args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  viewport: { width: 1100, height: 700 },
});
const problems = [];
const page = context.pages()[0] || (await context.newPage());
page.on("console", (msg) => {
  if (msg.type() === "error" || msg.type() === "warning") problems.push(`console ${msg.type()}: ${msg.text()}`);
});
page.on("pageerror", (err) => problems.push(`page error: ${err.message}`));
// Everything comes from the server itself.
await page.route("**/*", (route) => {
  if (route.request().url().startsWith(url)) return route.continue();
  problems.push(`request elsewhere: ${route.request().url()}`);
  return route.abort();
});

let failed = false;
async function check(name, fn) {
  try {
    await fn();
    console.log(`ok   ${name}`);
  } catch (err) {
    failed = true;
    console.log(`FAIL ${name}\n     ${String(err.message).split("\n").join("\n     ")}`);
  }
}
const status = () => page.evaluate(() => window.pathlabView.status);
const updates = () => page.evaluate(() => window.pathlabView.updates);

await page.goto(url);
await check("the page loads and shows the status", async () => {
  await page.waitForFunction(() => window.pathlabView && window.pathlabView.status, null, { timeout: 20000 });
  assert.match(await page.locator("#stats").textContent(), /spp/);
});
await check("the image updates at least three times", async () => {
  await page.waitForFunction(() => window.pathlabView.updates >= 3, null, { timeout: 30000 });
  await page.screenshot({ path: path.join(artifactDir, "view-ab.png") });
});
await check("the A/B split is drawn: the two halves differ", async () => {
  const halves = await page.evaluate(() => {
    const c = document.getElementById("canvas");
    const s = window.pathlabView;
    const ctx = c.getContext("2d");
    const dpr = window.devicePixelRatio || 1;
    const y = Math.round((s.panY + s.images.a.height * s.zoom * 0.5) * dpr);
    const split = (s.panX + s.split * s.images.a.width * s.zoom) * dpr;
    // One readback (several make Chromium warn): a row across the split line.
    const x0 = Math.round(split - 60);
    const row = Array.from(ctx.getImageData(x0, y, 120, 1).data);
    const cut = Math.round(split) - x0;
    return { left: row.slice(0, 4 * (cut - 2)), right: row.slice(4 * (cut + 2)), names: s.status.compare };
  });
  assert.equal(halves.names, "sobol-owen");
  assert.ok(halves.left.some((v, i) => i % 4 !== 3 && v > 0), "the left half is drawn");
  assert.ok(halves.right.some((v, i) => i % 4 !== 3 && v > 0), "the right half is drawn");
});
await check("the error plot appears and grows", async () => {
  await page.locator("#error_panel").waitFor({ state: "visible", timeout: 20000 });
  await page.waitForFunction(() => window.pathlabView.errorPoints >= 3, null, { timeout: 30000 });
  await page.screenshot({ path: path.join(artifactDir, "view-error.png") });
});
await check("the points panel draws the pixel's points and their spectrum", async () => {
  const box = await page.locator("#canvas").boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.waitForFunction(() => window.pathlabView.pointsDrawn >= 1, null, { timeout: 20000 });
  const drawn = await page.evaluate(() => {
    const lit = (id) => {
      const c = document.getElementById(id);
      const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < d.length; i += 4) n += d[i] + d[i + 1] + d[i + 2] > 120;
      return n;
    };
    return { points: lit("points_plot"), spectrum: lit("points_spectrum"),
      caption: document.getElementById("points_caption").textContent };
  });
  assert.ok(drawn.points > 20, `points drawn: ${drawn.points} bright pixels`);
  assert.ok(drawn.spectrum > 100, `spectrum drawn: ${drawn.spectrum} bright pixels`);
  assert.match(drawn.caption, /independent at \(\d+,\d+\), dims 0, 1: \d+ points/);
  await page.locator("#points_panel").screenshot({ path: path.join(artifactDir, "view-points.png") });
});
await check("the FLIP error map replaces the image when chosen", async () => {
  const before = await updates();
  await page.selectOption("#map", "flip");
  await page.waitForFunction((n) => window.pathlabView.updates > n && window.pathlabView.shown.endsWith("/flip"),
    before, { timeout: 20000 });
  await page.screenshot({ path: path.join(artifactDir, "view-flip-map.png") });
  await page.selectOption("#map", "image");
});
await check("switching the sampler through the page restarts accumulation", async () => {
  const before = await status();
  await page.waitForFunction((spp) => window.pathlabView.status.spp > spp, before.spp, { timeout: 30000 });
  await page.selectOption("#sampler", "halton");
  await page.waitForFunction((g) => {
    const s = window.pathlabView.status;
    return s.generation > g && s.sampler === "halton";
  }, before.generation, { timeout: 20000 });
  const after = await status();
  assert.ok(after.generation > before.generation);
  const shownBefore = await updates();
  await page.waitForFunction((n) => window.pathlabView.updates > n, shownBefore, { timeout: 20000 });
});
await check("display settings do not restart", async () => {
  const before = await status();
  await page.selectOption("#tone_map", "aces");
  await page.waitForFunction(() => window.pathlabView.status.tone_map === "aces", null, { timeout: 10000 });
  assert.equal((await status()).generation, before.generation);
});
await check("zoom magnifies by whole pixels", async () => {
  const z0 = await page.evaluate(() => window.pathlabView.zoom);
  const box = await page.locator("#canvas").boundingBox();
  await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
  await page.mouse.wheel(0, -100);
  await page.waitForFunction((z) => window.pathlabView.zoom === 2 * z, z0, { timeout: 5000 });
  await page.screenshot({ path: path.join(artifactDir, "view-zoomed.png") });
});
await check("equal time through the page: A and B show counts of their own", async () => {
  const before = await status();
  await page.selectOption("#equal", "time");
  await page.waitForFunction((g) => {
    const s = window.pathlabView.status;
    return s.generation > g && s.equal === "time" && s.spp >= 1 && s.spp_b >= 1;
  }, before.generation, { timeout: 30000 });
  await page.waitForFunction(() => /\(\d+ spp\) vs .* \(\d+ spp\)/.test(
    document.getElementById("stats").textContent), null, { timeout: 10000 });
  await page.screenshot({ path: path.join(artifactDir, "view-equal-time.png") });
});
await check("no console errors", async () => {
  assert.deepEqual(problems, []);
});
await page.evaluate(() => fetch("/api/stop", { method: "POST", body: "{}" }));
await context.close();
fs.rmSync(profile, { recursive: true, force: true });
process.exit(failed ? 1 : 0);
