// End-to-end test of `pathlab report` in headless Chromium: opens index.html
// from disk and uses it as a person would.
//   node report.test.mjs REPORT/index.html ARTIFACT_DIR
// Uses Debian's /usr/bin/chromium (or $PATHLAB_CHROMIUM); never downloads one.
import assert from "node:assert/strict";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import { chromium } from "playwright-core";

const [indexHtml, artifactDir] = process.argv.slice(2);
if (!indexHtml || !artifactDir) {
  console.error("usage: node report.test.mjs REPORT/index.html ARTIFACT_DIR");
  process.exit(2);
}
fs.mkdirSync(artifactDir, { recursive: true });

const checks = [];
async function check(name, fn) {
  try {
    await fn();
    checks.push([name, null]);
    console.log(`ok   ${name}`);
  } catch (err) {
    checks.push([name, err]);
    console.log(`FAIL ${name}\n     ${String(err.message).split("\n").join("\n     ")}`);
  }
}

const profile = fs.mkdtempSync(path.join(os.tmpdir(), "pathlab-chromium-"));
const context = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.PATHLAB_CHROMIUM || "/usr/bin/chromium",
  headless: true,
  args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  viewport: { width: 1280, height: 900 },
});
const problems = [];
const page = context.pages()[0] || (await context.newPage());
page.on("console", (msg) => {
  if (msg.type() === "error" || msg.type() === "warning") problems.push(`console ${msg.type()}: ${msg.text()}`);
});
page.on("pageerror", (err) => problems.push(`page error: ${err.message}`));
page.on("requestfailed", (req) => problems.push(`request failed: ${req.url()}`));
// Self-contained means no request leaves the disk.
await page.route("**/*", (route) => {
  const url = route.request().url();
  if (url.startsWith("file:") || url.startsWith("data:")) return route.continue();
  problems.push(`network request: ${url}`);
  return route.abort();
});

const url = "file://" + path.resolve(indexHtml);
const comparer = page.locator(".comparer").first();
const canvas = comparer.locator("canvas");

// Waits until the comparer has drawn what it says it shows; returns its pixels.
async function settled() {
  await page.waitForFunction(() => {
    const c = document.querySelector(".comparer");
    return c && c.dataset.shown && c.dataset.drawn === c.dataset.shown;
  }, null, { timeout: 10000 });
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  return canvas.screenshot();
}
const state = () => comparer.evaluate((c) => ({ ...c.dataset }));

try {
  await page.goto(url, { waitUntil: "load" });

  await check("every image has loaded", async () => {
    const images = await page.$$eval("img", (imgs) =>
      imgs.map((i) => ({ src: i.getAttribute("src"), ok: i.complete && i.naturalWidth > 0 })));
    assert.ok(images.length > 10, `only ${images.length} images on the page`);
    const broken = images.filter((i) => !i.ok).map((i) => i.src);
    assert.deepEqual(broken, [], "images that did not load");
  });

  await check("every plot is drawn", async () => {
    const scenes = await page.locator("section.scene").count();
    assert.ok(scenes >= 1, "no scene section");
    const plots = await page.$$eval(".plot img", (imgs) => imgs.map((i) => i.naturalWidth));
    assert.equal(plots.length, 4 * scenes, "four plots per scene");
    assert.ok(plots.every((w) => w > 100), `plot widths ${plots}`);
    // The error spectra at 1 and 4 spp (the study has no 16), one figure per scene.
    const spectra = await page.$$eval(".spectra img", (imgs) => imgs.map((i) => i.naturalWidth));
    assert.equal(spectra.length, scenes, "one error-spectrum figure per scene");
    assert.ok(spectra.every((w) => w > 100), `spectrum figure widths ${spectra}`);
    const rows = await page.locator("table.results tbody tr").count();
    assert.ok(rows >= 2, "the summary table has a row per sampler");
    assert.ok((await page.locator("table.results td.winner").count()) >= 1, "a winner is highlighted");
  });

  await check("an external renderer is shown beside pathlab's samplers, flagged biased", async () => {
    const names = await page.$$eval("table.results tbody th", (ths) => ths.map((t) => t.textContent));
    assert.ok(names.includes("direct:independent") && names.includes("direct:sobol-owen"),
      `summary rows: ${names}`);
    assert.ok(names.includes("independent"), `summary rows: ${names}`);
    // Direct light only is far too dark; with two seeds the interval is wide
    // at the lowest spp, so the verdict names the spp where it is decided.
    const biased = await page.$$eval("table.results td.biased", (tds) =>
      tds.map((t) => ({ row: t.parentElement.querySelector("th").textContent, text: t.textContent })));
    assert.ok(biased.length >= 1, "no biased cell");
    assert.ok(biased.every((b) => b.row.startsWith("direct:") && /^biased at .* spp/.test(b.text)),
      `biased cells: ${JSON.stringify(biased)}`);
    const colour = await page.locator("table.results td.biased").first()
      .evaluate((td) => getComputedStyle(td).color);
    assert.equal(colour, "rgb(192, 0, 0)");
    assert.match(await page.locator("ul.findings").first().textContent(), /Biased: direct:/);
    const chips = await page.$$eval(".comparer .chip[data-sampler]", (cs) => cs.map((c) => c.dataset.sampler));
    assert.ok(chips.includes("direct:independent"), `comparer samplers: ${chips}`);
  });

  await check("the comparer draws an image", async () => {
    await settled();
    const s = await state();
    assert.ok(s.drawn && s.drawn.endsWith(".png"), `drawn: ${s.drawn}`);
  });

  await check("switching the sampler changes the shown image", async () => {
    const before = await settled();
    const s0 = await state();
    const other = comparer.locator(`.chip[data-sampler]:not([data-sampler="${s0.sampler}"])`).first();
    await other.click();
    await page.mouse.move(0, 0);  // leave the chip: hovering previews
    const after = await settled();
    const s1 = await state();
    assert.notEqual(s1.sampler, s0.sampler);
    assert.notEqual(s1.shown, s0.shown);
    assert.ok(!before.equals(after), "the canvas looks the same");
  });

  await check("switching spp changes the shown image", async () => {
    const before = await settled();
    const s0 = await state();
    const other = comparer.locator(`.seg button[data-spp]:not([data-spp="${s0.spp}"]):not([disabled])`).last();
    await other.click();
    const after = await settled();
    const s1 = await state();
    assert.notEqual(s1.spp, s0.spp);
    assert.notEqual(s1.shown, s0.shown);
    assert.ok(!before.equals(after), "the canvas looks the same");
  });

  await check("hovering Reference flips to the reference and back", async () => {
    const before = await settled();
    const s0 = await state();
    await comparer.locator(".chip.ref").hover();
    const flipped = await settled();
    const s1 = await state();
    assert.equal(s1.flipped, "true");
    assert.match(s1.shown, /reference\.png$/);
    assert.ok(!before.equals(flipped), "the reference looks like the test image");
    await page.mouse.move(0, 0);
    await settled();
    assert.equal((await state()).shown, s0.shown);
  });

  await check("holding R flips to the reference", async () => {
    await canvas.click();
    await page.keyboard.down("r");
    await settled();
    assert.match((await state()).shown, /reference\.png$/);
    await page.keyboard.up("r");
    await settled();
    assert.doesNotMatch((await state()).shown, /reference\.png$/);
  });

  await check("the FLIP and relative-error toggles change the image", async () => {
    const image = await settled();
    await comparer.locator('button[data-view="flip"]').click();
    const flip = await settled();
    assert.match((await state()).shown, /-flip\.png$/);
    await comparer.locator('button[data-view="relse"]').click();
    const relse = await settled();
    assert.match((await state()).shown, /-relse\.png$/);
    assert.ok(!image.equals(flip) && !flip.equals(relse) && !image.equals(relse));
    await comparer.locator('button[data-view="image"]').click();
    await settled();
  });

  await check("the exposure control changes the display", async () => {
    const before = await settled();
    await comparer.locator('input[type="range"]').evaluate((input) => {
      input.value = "2";
      input.dispatchEvent(new Event("input", { bubbles: true }));
    });
    const brighter = await settled();
    assert.equal((await state()).exposure, "2");
    assert.ok(!before.equals(brighter), "exposure +2 looks the same");
    await canvas.click();
    await page.keyboard.press("0");
    assert.equal((await state()).exposure, "0");
  });

  await check("wheel zooms and drag pans", async () => {
    const box = await canvas.boundingBox();
    const cx = box.x + box.width / 2, cy = box.y + box.height / 2;
    const scale0 = Number((await state()).scale);
    await page.mouse.move(cx, cy);
    await page.mouse.wheel(0, -400);
    await settled();
    const scale1 = Number((await state()).scale);
    assert.ok(scale1 > scale0 * 1.5, `zoom ${scale0} -> ${scale1}`);
    const before = await settled();
    await page.mouse.move(cx, cy);
    await page.mouse.down();
    await page.mouse.move(cx + 80, cy + 40, { steps: 4 });
    await page.mouse.up();
    const after = await settled();
    assert.ok(!before.equals(after), "dragging did not move the image");
    await canvas.dblclick();
  });

  await check("the grid's spp selector swaps its images", async () => {
    const select = page.locator(".cgrid select").first();
    const options = await select.locator("option").evaluateAll((o) => o.map((x) => x.value));
    const current = await select.inputValue();
    const next = options.find((v) => v !== current);
    await select.selectOption(next);
    await page.waitForFunction(() => [...document.querySelectorAll(".cgrid img")]
      .every((i) => i.complete && i.naturalWidth > 0));
    const srcs = await page.$$eval(".cgrid img", (imgs) => imgs.map((i) => i.getAttribute("src")));
    assert.ok(srcs.some((s) => s.includes(`/spp${next}.png`)), `no spp${next} image in the grid`);
  });

  await check("no console errors and no network requests", async () => {
    assert.deepEqual(problems, []);
  });

  // Artefacts for a person to look at.
  await page.mouse.move(0, 0);
  await comparer.scrollIntoViewIfNeeded();
  await page.screenshot({ path: path.join(artifactDir, "report.png"), fullPage: true });
  await comparer.screenshot({ path: path.join(artifactDir, "report-comparer.png") });
} finally {
  await context.close();
  fs.rmSync(profile, { recursive: true, force: true });
}

const failed = checks.filter(([, err]) => err).length;
console.log(`${checks.length - failed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
