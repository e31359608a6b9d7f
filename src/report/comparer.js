// The report's interactive parts: the comparison grid and the image comparer.
// Plain browser JavaScript with no dependencies, inlined into index.html so the
// page works from disk. Images are relative paths inside report/.
"use strict";

(function () {
  const data = JSON.parse(document.getElementById("report-data").textContent);
  const REFERENCE = "Original";
  const VIEWS = [
    ["image", "Image"],
    ["flip", "FLIP error"],
    ["relse", "Rel. squared error"],
  ];

  function el(tag, attrs, ...children) {
    const node = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs || {})) {
      if (k === "style") Object.assign(node.style, v);
      else if (k.startsWith("on")) node.addEventListener(k.slice(2), v);
      else node.setAttribute(k, v);
    }
    for (const c of children) node.append(c);
    return node;
  }

  function fmt(v) {
    if (v === null || v === undefined) return "—";
    if (v !== 0 && (Math.abs(v) < 1e-3 || Math.abs(v) >= 1e4)) return v.toExponential(2);
    return Number(v.toPrecision(3)).toString();
  }

  function colourOf(name) {
    return name === REFERENCE ? data.referenceColour : data.palette[name] || "#888";
  }

  // ---------------------------------------------------------------- the grid
  // The presentation's figure: Original and every sampler at two spp, each with
  // the high-error region magnified. Either row's spp can be changed.
  function buildGrid(host, scene, comparer) {
    const columns = [REFERENCE, ...scene.samplers.filter((s) => scene.images[s])];
    const grid = el("div", { class: "cgrid" });
    grid.style.gridTemplateColumns = `5.5em repeat(${columns.length}, minmax(84px, 1fr))`;
    const crop = scene.crop;
    const pct = (a, b) => `${(100 * a) / b}%`;

    function cellFor(name, spp) {
      const entry = name === REFERENCE ? null : (scene.images[name] || {})[spp];
      const src = name === REFERENCE ? scene.reference : entry && entry.image;
      const cell = el("div", { class: "gcell", title: `${name}${entry ? ", " + spp + " spp" : ""}` });
      cell.style.borderTopColor = colourOf(name);
      if (!src) {
        cell.append(el("div", { class: "missing" }, `no ${spp} spp`));
        return cell;
      }
      const full = el("div", { class: "gfull" }, el("img", { src, alt: `${name} ${spp} spp` }));
      const box = el("div", { class: "gbox" });
      Object.assign(box.style, {
        left: pct(crop.x, scene.width), top: pct(crop.y, scene.height),
        width: pct(crop.w, scene.width), height: pct(crop.h, scene.height),
      });
      full.append(box);
      full.style.aspectRatio = `${scene.width} / ${scene.height}`;
      const zoomImg = el("img", { src, alt: `${name} ${spp} spp, zoomed` });
      Object.assign(zoomImg.style, {
        width: pct(scene.width, crop.w), height: pct(scene.height, crop.h),
        left: pct(-crop.x, crop.w), top: pct(-crop.y, crop.h),
      });
      cell.append(full, el("div", { class: "gzoom" }, zoomImg));
      cell.append(el("div", { class: "gmetric" },
        entry ? `MSE ${fmt(entry.mse_value)}\nFLIP ${fmt(entry.flip_value)}` : "reference"));
      cell.addEventListener("click", () => {
        if (name !== REFERENCE) comparer.select(name, Number(spp));
        comparer.root.scrollIntoView({ behavior: "smooth", block: "center" });
      });
      return cell;
    }

    function addRow(initialSpp) {
      const select = el("select", { "aria-label": "samples per pixel" });
      for (const n of scene.spps) select.append(el("option", { value: n }, `${n} spp`));
      select.value = String(initialSpp);
      const head = el("div", { class: "ghead" }, select);
      grid.append(head);
      let cells = columns.map((name) => cellFor(name, String(initialSpp)));
      grid.append(...cells);
      select.addEventListener("change", () => {
        const fresh = columns.map((name) => cellFor(name, select.value));
        cells.forEach((c, i) => c.replaceWith(fresh[i]));
        cells = fresh;
      });
    }

    const names = el("div", { class: "ghead" });
    grid.append(names);
    for (const name of columns)
      grid.append(el("div", { class: "gname", style: { color: colourOf(name) } }, name));
    for (const spp of scene.gridSpps) addRow(spp);
    host.append(grid);
  }

  // ------------------------------------------------------------ the comparer
  // Exposure is applied after decoding, as an SVG filter whose lookup table maps
  // each sRGB value to sRGB(2^stops · linear): exact for unclipped pixels.
  function srgbToLinear(v) {
    return v <= 0.04045 ? v / 12.92 : Math.pow((v + 0.055) / 1.055, 2.4);
  }
  function linearToSrgb(v) {
    return v <= 0.0031308 ? 12.92 * v : 1.055 * Math.pow(v, 1 / 2.4) - 0.055;
  }
  function exposureTable(stops) {
    const gain = Math.pow(2, stops);
    const values = [];
    for (let i = 0; i < 256; i++)
      values.push(linearToSrgb(Math.min(1, srgbToLinear(i / 255) * gain)).toFixed(4));
    return values.join(" ");
  }

  const imageCache = new Map();
  function loadImage(src) {
    if (!imageCache.has(src)) {
      const img = new Image();
      const ready = new Promise((resolve, reject) => {
        img.onload = () => resolve(img);
        img.onerror = () => reject(new Error(`cannot load ${src}`));
      });
      img.src = src;
      imageCache.set(src, ready);
    }
    return imageCache.get(src);
  }

  let activeComparer = null;

  class Comparer {
    constructor(host, scene, index) {
      this.scene = scene;
      this.samplers = scene.samplers.filter((s) => scene.images[s]);
      this.state = {
        sampler: this.samplers.includes("independent") ? "independent" : this.samplers[0],
        spp: scene.gridSpps[0], view: "image", exposure: 0,
        flip: false, preview: null, scale: 1, x: 0, y: 0,
      };
      this.filterId = `pl-exposure-${index}`;
      this.build(host);
      this.fit();
      this.update();
    }

    build(host) {
      const s = this.scene;
      this.root = el("div", { class: "comparer", tabindex: "0", "data-scene": s.name });
      // Sampler chips: hover previews, click selects (as in JERI).
      this.chips = el("div", { class: "chips" });
      const refChip = el("button", { class: "chip ref", type: "button" }, "Reference");
      refChip.addEventListener("pointerenter", () => this.setFlip(true));
      refChip.addEventListener("pointerleave", () => this.setFlip(false));
      this.chips.append(refChip);
      this.samplerChips = new Map();
      this.samplers.forEach((name, i) => {
        const chip = el("button", { class: "chip", type: "button", "data-sampler": name,
          title: i < 9 ? `key ${i + 1}` : "" }, el("span", { class: "swatch",
          style: { background: colourOf(name) } }), name);
        chip.addEventListener("click", () => this.select(name, this.state.spp));
        chip.addEventListener("pointerenter", () => { this.state.preview = name; this.update(); });
        chip.addEventListener("pointerleave", () => { this.state.preview = null; this.update(); });
        this.samplerChips.set(name, chip);
        this.chips.append(chip);
      });

      this.sppButtons = new Map();
      const spps = el("div", { class: "seg" }, el("span", { class: "lbl" }, "spp"));
      for (const n of s.spps) {
        const b = el("button", { type: "button", "data-spp": n }, String(n));
        b.addEventListener("click", () => this.select(this.state.sampler, n));
        this.sppButtons.set(n, b);
        spps.append(b);
      }
      this.viewButtons = new Map();
      const views = el("div", { class: "seg" }, el("span", { class: "lbl" }, "view"));
      for (const [key, label] of VIEWS) {
        const b = el("button", { type: "button", "data-view": key }, label);
        b.addEventListener("click", () => this.setView(key));
        this.viewButtons.set(key, b);
        views.append(b);
      }
      this.exposure = el("input", { type: "range", min: "-6", max: "6", step: "0.25", value: "0",
        "aria-label": "exposure in stops" });
      this.exposure.addEventListener("input", () => this.setExposure(Number(this.exposure.value)));
      this.exposureLabel = el("span", { class: "mono" }, "+0.00");
      const reset = el("button", { type: "button" }, "0");
      reset.addEventListener("click", () => this.setExposure(0));
      const fitButton = el("button", { type: "button" }, "fit");
      fitButton.addEventListener("click", () => { this.fit(); this.draw(); });
      const exposure = el("div", { class: "seg" }, el("span", { class: "lbl" }, "exposure"),
        this.exposure, this.exposureLabel, reset, fitButton);

      this.canvas = el("canvas", { class: "view" });
      this.label = el("div", { class: "vlabel" });
      this.viewport = el("div", { class: "viewport" }, this.canvas, this.label);
      this.status = el("div", { class: "status mono" });
      this.legendLow = el("span", {});
      this.legendHigh = el("span", {});
      this.legend = el("div", { class: "legend" }, this.legendLow, el("span", { class: "bar" }),
        this.legendHigh);
      const help = el("div", { class: "help" },
        "Hold R or hover \u201cReference\u201d to flip to the reference · hover a sampler to " +
        "preview, click to select · wheel zooms, drag pans, double-click fits · keys: 1\u20139 " +
        "sampler, \u2190/\u2192 spp, I/F/E view, +/\u2212 exposure, 0 reset exposure");

      const svg = document.createElementNS("http://www.w3.org/2000/svg", "svg");
      svg.setAttribute("width", "0");
      svg.setAttribute("height", "0");
      svg.setAttribute("class", "hidden-svg");
      svg.innerHTML = `<filter id="${this.filterId}" color-interpolation-filters="sRGB">
        <feComponentTransfer><feFuncR type="table"/><feFuncG type="table"/>
        <feFuncB type="table"/></feComponentTransfer></filter>`;
      this.filterFuncs = svg.querySelectorAll("feFuncR, feFuncG, feFuncB");

      this.root.append(svg, this.chips,
        el("div", { class: "controls" }, spps, views, exposure), this.viewport,
        el("div", { class: "below" }, this.status, this.legend), help);
      host.append(this.root);
      this.attachPointer();
      new ResizeObserver(() => this.resize()).observe(this.viewport);
      this.resize();
    }

    // -- state changes
    select(sampler, spp) {
      const available = this.scene.images[sampler] || {};
      if (!available[spp]) {
        // Keep the spp if the sampler has it, else its nearest.
        const options = Object.keys(available).map(Number);
        spp = options.reduce((a, b) => (Math.abs(b - spp) < Math.abs(a - spp) ? b : a), options[0]);
      }
      Object.assign(this.state, { sampler, spp, preview: null });
      this.update();
    }
    setView(view) { this.state.view = view; this.update(); }
    setFlip(on) { this.state.flip = on; this.update(); }
    setExposure(stops) {
      this.state.exposure = Math.max(-6, Math.min(6, stops));
      this.exposure.value = String(this.state.exposure);
      const table = exposureTable(this.state.exposure);
      this.filterFuncs.forEach((f) => f.setAttribute("tableValues", table));
      this.update();
    }

    // What is on screen: the reference when flipped, else the chosen image.
    shown() {
      const st = this.state;
      if (st.flip) return { src: this.scene.reference, name: REFERENCE, entry: null, view: "image" };
      const name = st.preview || st.sampler;
      const perSpp = this.scene.images[name] || {};
      const entry = perSpp[st.spp] || perSpp[Object.keys(perSpp)[0]];
      const src = (entry && entry[st.view]) || (entry && entry.image);
      return { src, name, entry, view: entry && entry[st.view] ? st.view : "image" };
    }

    update() {
      const st = this.state;
      const shown = this.shown();
      for (const [name, chip] of this.samplerChips) chip.classList.toggle("on", name === st.sampler);
      this.chips.querySelector(".ref").classList.toggle("on", st.flip);
      for (const [n, b] of this.sppButtons) {
        b.classList.toggle("on", n === st.spp);
        b.disabled = !(this.scene.images[st.sampler] || {})[n];
      }
      for (const [v, b] of this.viewButtons) {
        b.classList.toggle("on", v === st.view);
        const entry = (this.scene.images[st.sampler] || {})[st.spp];
        b.disabled = v !== "image" && !(entry && entry[v]);
      }
      this.exposureLabel.textContent = (st.exposure >= 0 ? "+" : "") + st.exposure.toFixed(2);
      // Error maps are colour maps: exposure would change their meaning.
      const exposed = shown.view === "image" && st.exposure !== 0;
      this.canvas.style.filter = exposed ? `url(#${this.filterId})` : "none";
      // Both maps are magma: FLIP linear in [0, 1]; the relative squared error
      // on a log scale from 1e-4 to 10 (docs/study-output.md).
      const scale = { flip: ["0", "1 (FLIP)"], relse: ["10\u207b\u2074", "10 (rel. sq. error, log)"] };
      this.legend.style.visibility = scale[shown.view] ? "visible" : "hidden";
      if (scale[shown.view]) {
        this.legendLow.textContent = scale[shown.view][0];
        this.legendHigh.textContent = scale[shown.view][1];
      }
      const e = shown.entry;
      this.label.textContent = shown.name === REFERENCE ? "Reference"
        : `${shown.name} · ${st.spp} spp` +
          (shown.view !== "image" ? ` · ${VIEWS.find((v) => v[0] === shown.view)[1]}` : "");
      this.label.style.borderColor = colourOf(shown.name);
      this.statusText = shown.name === REFERENCE ? "reference"
        : `MSE ${fmt(e && e.mse_value)} · relMSE ${fmt(e && e.relmse_value)} · ` +
          `FLIP ${fmt(e && e.flip_value)} · render ${fmt(e && e.seconds_value)} s (seed 0)`;
      Object.assign(this.root.dataset, { sampler: st.sampler, spp: String(st.spp),
        view: st.view, exposure: String(st.exposure), flipped: String(st.flip),
        shown: shown.src || "" });
      this.current = shown.src;
      this.showStatus();
      if (shown.src) {
        loadImage(shown.src).then((img) => {
          if (this.current === shown.src) { this.image = img; this.draw(); }
        }, (err) => { this.status.textContent = err.message; });
      }
      this.preload();
    }

    preload() {
      // The neighbours the user will flip to next, so flipping never flickers.
      loadImage(this.scene.reference).catch(() => {});
      const perSpp = this.scene.images[this.state.sampler] || {};
      for (const entry of Object.values(perSpp)) loadImage(entry.image).catch(() => {});
    }

    showStatus(pixel) {
      const zoom = `zoom ${Math.round(this.state.scale * 100)}%`;
      this.status.textContent = `${this.statusText} · ${pixel || ""}${pixel ? " · " : ""}${zoom}`;
    }

    // -- view geometry: image pixel (u,v) is drawn at (x + u·scale, y + v·scale)
    resize() {
      const w = Math.max(200, this.viewport.clientWidth);
      const h = Math.round(Math.min(window.innerHeight * 0.7,
        w * (this.scene.height / this.scene.width), 720));
      const dpr = window.devicePixelRatio || 1;
      this.canvas.style.width = `${w}px`;
      this.canvas.style.height = `${h}px`;
      this.canvas.width = Math.round(w * dpr);
      this.canvas.height = Math.round(h * dpr);
      if (!this.userMoved) this.fit();
      this.draw();
    }

    fit() {
      const w = this.canvas.clientWidth || 400, h = this.canvas.clientHeight || 400;
      const fill = Math.min(w / this.scene.width, h / this.scene.height);
      // Whole-number magnification keeps pixels the same size as each other.
      const scale = fill >= 1 ? Math.floor(fill) : fill;
      Object.assign(this.state, { scale,
        x: (w - this.scene.width * scale) / 2, y: (h - this.scene.height * scale) / 2 });
      this.userMoved = false;
    }

    draw() {
      const ctx = this.canvas.getContext("2d");
      const dpr = this.canvas.width / (this.canvas.clientWidth || 1);
      ctx.setTransform(1, 0, 0, 1, 0, 0);
      // Transparent around the image, so exposure leaves the backdrop alone.
      ctx.clearRect(0, 0, this.canvas.width, this.canvas.height);
      if (!this.image) return;
      const st = this.state;
      ctx.imageSmoothingEnabled = false;  // nearest neighbour: see the real pixels
      ctx.setTransform(st.scale * dpr, 0, 0, st.scale * dpr, st.x * dpr, st.y * dpr);
      ctx.drawImage(this.image, 0, 0);
      // For tests and tools: what is on the canvas, at which zoom.
      Object.assign(this.root.dataset, { drawn: this.image.getAttribute("src"),
        scale: st.scale.toFixed(4) });
      this.showStatus();
    }

    zoomAt(px, py, factor) {
      const st = this.state;
      const scale = Math.max(0.05, Math.min(64, st.scale * factor));
      st.x = px - ((px - st.x) * scale) / st.scale;
      st.y = py - ((py - st.y) * scale) / st.scale;
      st.scale = scale;
      this.userMoved = true;
      this.draw();
    }

    attachPointer() {
      const c = this.canvas;
      let drag = null;
      c.addEventListener("wheel", (ev) => {
        ev.preventDefault();
        const r = c.getBoundingClientRect();
        this.zoomAt(ev.clientX - r.left, ev.clientY - r.top, Math.pow(1.0015, -ev.deltaY));
      }, { passive: false });
      c.addEventListener("pointerdown", (ev) => {
        drag = { x: ev.clientX, y: ev.clientY };
        c.setPointerCapture(ev.pointerId);
        this.root.focus({ preventScroll: true });
      });
      c.addEventListener("pointermove", (ev) => {
        const r = c.getBoundingClientRect();
        const u = Math.floor((ev.clientX - r.left - this.state.x) / this.state.scale);
        const v = Math.floor((ev.clientY - r.top - this.state.y) / this.state.scale);
        const inside = u >= 0 && v >= 0 && u < this.scene.width && v < this.scene.height;
        if (drag) {
          this.state.x += ev.clientX - drag.x;
          this.state.y += ev.clientY - drag.y;
          drag = { x: ev.clientX, y: ev.clientY };
          this.userMoved = true;
          this.draw();
        }
        this.showStatus(inside ? `pixel ${u}, ${v}` : "");
      });
      const end = () => { drag = null; };
      c.addEventListener("pointerup", end);
      c.addEventListener("pointercancel", end);
      c.addEventListener("dblclick", () => { this.fit(); this.draw(); });
      this.root.addEventListener("pointerenter", () => { activeComparer = this; });
      this.root.addEventListener("focusin", () => { activeComparer = this; });
    }

    key(ev, down) {
      const k = ev.key.toLowerCase();
      if (k === "r") { if (ev.repeat) return true; this.setFlip(down); return true; }
      if (!down) return false;
      const i = this.samplers.indexOf(this.state.sampler);
      const spps = this.scene.spps;
      const j = spps.indexOf(this.state.spp);
      if (/^[1-9]$/.test(k) && Number(k) <= this.samplers.length) {
        this.select(this.samplers[Number(k) - 1], this.state.spp);
      } else if (k === "arrowright" && j < spps.length - 1) {
        this.select(this.state.sampler, spps[j + 1]);
      } else if (k === "arrowleft" && j > 0) {
        this.select(this.state.sampler, spps[j - 1]);
      } else if (k === "arrowdown" || k === "arrowup") {
        const next = (i + (k === "arrowdown" ? 1 : this.samplers.length - 1)) % this.samplers.length;
        this.select(this.samplers[next], this.state.spp);
      } else if (k === "i" || k === "f" || k === "e") {
        this.setView({ i: "image", f: "flip", e: "relse" }[k]);
      } else if (k === "+" || k === "=") {
        this.setExposure(this.state.exposure + 0.5);
      } else if (k === "-" || k === "_") {
        this.setExposure(this.state.exposure - 0.5);
      } else if (k === "0") {
        this.setExposure(0);
      } else {
        return false;
      }
      return true;
    }
  }

  function typing(target) {
    return target && (target.tagName === "SELECT" || target.tagName === "INPUT" ||
      target.tagName === "TEXTAREA");
  }
  document.addEventListener("keydown", (ev) => {
    if (activeComparer && !typing(ev.target) && !ev.ctrlKey && !ev.metaKey && !ev.altKey &&
        activeComparer.key(ev, true)) ev.preventDefault();
  });
  document.addEventListener("keyup", (ev) => {
    if (activeComparer && activeComparer.key(ev, false)) ev.preventDefault();
  });
  window.addEventListener("blur", () => { if (activeComparer) activeComparer.setFlip(false); });

  window.pathlabComparers = [];
  data.scenes.forEach((scene, index) => {
    const section = document.querySelector(`section.scene[data-scene="${CSS.escape(scene.name)}"]`);
    if (!section) return;
    const comparer = new Comparer(section.querySelector(".comparer-host"), scene, index);
    buildGrid(section.querySelector(".grid-host"), scene, comparer);
    window.pathlabComparers.push(comparer);
  });
  if (window.pathlabComparers.length) activeComparer = window.pathlabComparers[0];
})();
