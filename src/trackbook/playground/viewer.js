// trackbook playground viewer: one ES module for the Jupyter widget (anywidget) and the
// static HTML book. It draws on a canvas the frame, ground truth, estimate, the tracker's
// state, the IoU-per-frame curve with a cursor, the tracker's confidence per frame (frames
// judged lost shaded), a correlation filter's response map as an inset, and the scores line. Frames arrive once as
// JPEG; everything else is drawn here, so a frame step costs no Python and no network.
// Contract: root element .tb-playground, knob inputs [data-knob], frame input [data-frame],
// play button [data-play].

const SPEEDS = [["slow", 5], ["normal", 12], ["fast", 25]];

function el(tag, attrs, parent) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === "text") e.textContent = v;
    else if (k === "class") e.className = v;
    else e.setAttribute(k, v);
  }
  if (parent) parent.appendChild(e);
  return e;
}

function fmt(v) {
  if (Array.isArray(v)) return v.map(fmt).join(", ");
  if (typeof v === "number") return Number.isInteger(v) ? String(v) : String(+v.toPrecision(3));
  return String(v);
}

function same(a, b) { return JSON.stringify(a) === JSON.stringify(b); }

function bytesOf(b64) {
  const bin = atob(b64);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  return bytes;
}

// particles: base64 little-endian int16 triples (2x, 2y, weight*1000), pcount per frame;
// response maps: base64 uint8 cells (lo + q / 255 (hi - lo)), rshape [rows, cols] per frame
function decodeState(run) {
  const st = (run && run.state) || {};
  const out = { particles: null };
  if (st.pcount && st.particles) {
    const a = new Int16Array(bytesOf(st.particles).buffer);
    const per = [];
    let o = 0;
    for (const c of st.pcount) { per.push(a.subarray(o, o + 3 * c)); o += 3 * c; }
    out.particles = per;
  }
  for (const k of ["search_window", "ellipse", "candidates", "rays", "response_box", "confidence"])
    out[k] = st[k] || null;
  out.response = null;
  if (st.rshape && st.response !== undefined) {
    const a = bytesOf(st.response);
    const per = [];
    let o = 0;
    st.rshape.forEach((sh, k) => {
      if (!sh) { per.push(null); return; }
      const n = sh[0] * sh[1];
      per.push({ rows: sh[0], cols: sh[1], q: a.subarray(o, o + n), range: st.rrange[k] });
      o += n;
    });
    out.response = per;
  }
  return out;
}

// a perceptually ordered colour map (viridis, from its published stops) for the response
const VIRIDIS = [[68, 1, 84], [72, 40, 120], [62, 74, 137], [49, 104, 142], [38, 130, 142],
  [31, 158, 137], [53, 183, 121], [109, 205, 89], [180, 222, 44], [253, 231, 37]];
const LUT = (() => {
  const t = new Uint8ClampedArray(256 * 3), n = VIRIDIS.length - 1;
  for (let q = 0; q < 256; q++) {
    const f = q / 255 * n, i = Math.min(n - 1, Math.floor(f)), u = f - i;
    for (let c = 0; c < 3; c++) t[3 * q + c] = VIRIDIS[i][c] * (1 - u) + VIRIDIS[i + 1][c] * u;
  }
  return t;
})();

const RAY_DIRS = [[1, 0], [1, -1], [0, -1], [-1, -1], [-1, 0], [-1, 1], [0, 1], [1, 1]];

class Viewer {
  constructor(root, host) {
    this.root = root;
    this.host = host;
    // element -> colour, from Python (trackbook.style.VIEWER) with the config
    this.colors = host.config().colors || {};
    this.frame = 0;
    this.playing = false;
    this.images = [];
    this.clipKey = null;
    this.drag = null;
    root.classList.add("tb-playground");
    root.setAttribute("tabindex", "0");
    const top = el("div", { class: "tb-row tb-choices" }, root);
    this.clipSel = el("select", { "data-control": "clip", "aria-label": "clip" }, top);
    this.trackerSel = el("select", { "data-control": "tracker", "aria-label": "tracker" }, top);
    this.status = el("span", { class: "tb-status" }, top);
    this.knobBox = el("div", { class: "tb-knobs" }, root);
    this.note = el("div", { class: "tb-note" }, root);
    this.canvas = el("canvas", { class: "tb-canvas" }, root);
    this.ctx = this.canvas.getContext("2d");
    this.legendBox = el("div", { class: "tb-legend" }, root);
    const tr = el("div", { class: "tb-row tb-transport" }, root);
    this.playBtn = el("button", { "data-play": "", type: "button", text: "\u25b6 play" }, tr);
    this.slider = el("input", { type: "range", "data-frame": "", min: 0, max: 0, step: 1,
                                value: 0, "aria-label": "frame" }, tr);
    this.frameLabel = el("span", { class: "tb-frame-label" }, tr);
    this.speedSel = el("select", { "data-speed": "", "aria-label": "speed" }, tr);
    for (const [name, fps] of SPEEDS) el("option", { value: fps, text: name }, this.speedSel);
    this.speedSel.value = "12";
    this.scores = el("div", { class: "tb-scores" }, root);
    this.spread = el("div", { class: "tb-spread" }, root);
    if (typeof ResizeObserver !== "undefined") {
      // the column's width decides the layout: side by side, or the curve under the frame
      this.resizer = new ResizeObserver(() => {
        if (this.clipInfo && this.root.clientWidth !== this.laidOut) { this.layout(); this.draw(); }
      });
      this.resizer.observe(root);
    }
    this.slider.addEventListener("input", () => this.seek(+this.slider.value));
    this.playBtn.addEventListener("click", () => this.togglePlay());
    root.addEventListener("keydown", (ev) => {
      if (ev.target.tagName === "INPUT" && ev.target !== this.slider) return;
      if (ev.key === "ArrowRight") { this.seek(this.frame + 1); ev.preventDefault(); }
      else if (ev.key === "ArrowLeft") { this.seek(this.frame - 1); ev.preventDefault(); }
      else if (ev.key === " " && ev.target === root) { this.togglePlay(); ev.preventDefault(); }
    });
    this.clipSel.addEventListener("change", () => host.setClip(this.clipSel.value));
    this.trackerSel.addEventListener("change", () => host.setTracker(this.trackerSel.value));
    this.canvas.addEventListener("mousedown", (ev) => this.dragStart(ev));
    this.canvas.addEventListener("mousemove", (ev) => this.dragMove(ev));
    window.addEventListener("mouseup", (ev) => this.dragEnd(ev));
    const cfg = host.config();
    for (const c of cfg.clips) el("option", { value: c.key, text: c.name }, this.clipSel);
    for (const t of cfg.trackers) el("option", { value: t, text: t }, this.trackerSel);
    this.clipSel.disabled = cfg.clips.length < 2;
    this.trackerSel.disabled = cfg.trackers.length < 2;
  }

  // ---- data arriving -----------------------------------------------------------------
  update() {
    const h = this.host;
    this.clipSel.value = h.clipKey();
    this.trackerSel.value = h.tracker();
    const clip = h.clip();
    if (clip && this.clipKey !== h.clipKey()) this.loadClip(clip, h.clipKey());
    let run = h.run();
    this.loading = !run && !!(h.loading && h.loading());
    if (!run && this.loading && this.lastFull && this.lastFull.clip === (clip && clip.name)) {
      run = this.lastFull;         // the previous run, greyed, until this one arrives
      this.stale = true;
    } else this.stale = false;
    if (run && !this.stale && run.boxes && !(run.n_done < run.n_total)) this.lastFull = run;
    if (run !== this.run) { this.run = run; this.state = decodeState(run); }
    // the confidence curve and the response inset take room only when the run has them
    const st = this.state || {};
    const panels = [!!(st.confidence && !(run && run.curve)), !!st.response].join();
    if (panels !== this.panelSig) { this.panelSig = panels; this.layout(); }
    this.buildKnobs();
    const n = this.nFrames();
    this.slider.max = Math.max(0, n - 1);
    if (this.frame > n - 1) this.frame = Math.max(0, n - 1);
    this.slider.value = this.frame;
    const r = this.run || {};
    const clipHasGt = clip && clip.gt;
    if (r.animation) this.scores.textContent = r.scores || "";
    else if (r.waiting) this.scores.textContent =
      "No ground truth: drag the target's box on frame 0, the tracker starts from it.";
    else if (r.error) this.scores.textContent = "This setting was refused: " + r.error;
    else if (!clipHasGt) this.scores.textContent = (r.tracker || "") +
      " on your clip: no ground truth, so no scores; the curve is the tracker's ok flag.";
    else this.scores.textContent = r.scores || "";
    const partial = r.n_done !== undefined && r.n_done < r.n_total;
    if (partial) this.scores.textContent = `running\u2026 ${r.n_done}/${r.n_total} \u00b7 ` + this.scores.textContent;
    if (this.stale) this.scores.textContent = "loading this run\u2026 (the previous one shown, greyed)";
    else if (!run && this.loading) this.scores.textContent = "loading the run\u2026";
    this.spread.textContent = !this.stale && r.seeds ? spreadText(r.seeds) : "";
    this.note.textContent = h.note();
    this.status.textContent = h.status();
    this.legend();
    this.draw();
  }

  loadClip(clip, key) {
    this.clipKey = key;
    this.clipInfo = clip;
    this.frameIndex = clip.index || null;  // animations: step -> image (steps share frames)
    const imgs = [];
    this.images = imgs;
    const add = (b64, at) => {
      const im = new Image();
      im.onload = () => { if (this.images === imgs) this.draw(); };
      im.src = "data:image/jpeg;base64," + b64;
      imgs[at] = im;
    };
    this.addFrames = (frames, start) => frames.forEach((b64, j) => add(b64, start + j));
    this.chunkAsked = {};
    if (clip.frames) this.addFrames(clip.frames, 0);
    else this.needFrame(0);
    this.layout();
  }

  // frames arrive in files of clip.per frames, asked for when the cursor comes near them
  needFrame(i) {
    const clip = this.clipInfo;
    if (!clip || clip.frames || !clip.chunks || !this.host.loadFile) return;
    const c = Math.floor(i / clip.per);
    if (c < 0 || c >= clip.chunks.length || this.chunkAsked[c]) return;
    this.chunkAsked[c] = true;
    const imgs = this.images;
    this.host.loadFile(clip.chunks[c], (d) => {
      if (this.images !== imgs) return;
      if (d) this.addFrames(d.frames, d.start);
      else this.chunkAsked[c] = false;
      this.draw();
    });
  }

  layout() {
    const clip = this.clipInfo;
    if (!clip) return;
    const cs = getComputedStyle(this.root);
    const pad = (parseFloat(cs.paddingLeft) || 0) + (parseFloat(cs.paddingRight) || 0);
    this.laidOut = this.root.clientWidth;
    const avail = Math.max(200, (this.root.clientWidth || 640) - pad);
    const side = avail >= 560;     // the IoU curve beside the frame, or under it
    this.cw = side ? Math.round(Math.max(220, Math.min(320, avail * 0.36))) : avail;
    const fwMax = side ? avail - 16 - this.cw : avail;
    this.scale = Math.min(2, 480 / clip.w, fwMax / clip.w);
    this.fw = Math.round(clip.w * this.scale);
    this.fh = Math.round(clip.h * this.scale);
    this.cx0 = side ? this.fw + 16 : 0;
    this.cy0 = side ? 0 : this.fh + 8;
    const [hasConf, hasResp] = (this.panelSig || "false,false").split(",").map((x) => x === "true");
    // the response inset: a square, under the curves beside the frame, or beside the
    // confidence curve under it (a phone's column holds ~370 px)
    const inset = hasResp ? (side ? Math.min(this.cw - 44, 110) : Math.min(110, Math.round(avail * 0.3))) : 0;
    let H;
    this.panels = {};
    if (side) {
      const need = 110 + (hasConf ? 100 : 0) + (hasResp ? inset + 36 : 0);
      const colH = Math.max(this.fh, need);
      const curves = colH - (hasResp ? inset + 36 : 0);
      const hi = hasConf ? Math.round(curves * 0.55) : curves;
      this.panels.iou = { x: this.cx0, y: 0, w: this.cw, h: hi };
      if (hasConf) this.panels.conf = { x: this.cx0, y: hi, w: this.cw, h: curves - hi };
      if (hasResp) this.panels.resp = { x: this.cx0 + 34, y: curves + 18, w: inset, h: inset };
      H = colH;
    } else {
      this.panels.iou = { x: 0, y: this.cy0, w: avail, h: 150 };
      let y = this.cy0 + 150;
      if (hasConf || hasResp) {
        const rowH = Math.max(120, inset + 36);
        if (hasConf) this.panels.conf = { x: 0, y, w: avail - (hasResp ? inset + 12 : 0), h: rowH };
        if (hasResp) this.panels.resp = { x: avail - inset, y: y + 18, w: inset, h: inset };
        y += rowH;
      }
      H = y;
    }
    this.ch = this.panels.iou.h;
    const W = side ? this.cx0 + this.cw : avail;
    // where each panel sits (CSS px of the canvas), for whoever checks the drawing
    this.root.setAttribute("data-tb-panels", JSON.stringify(this.panels));
    this.W = W; this.H = H;
    const dpr = window.devicePixelRatio || 1;
    this.canvas.width = Math.round(W * dpr);
    this.canvas.height = Math.round(H * dpr);
    this.canvas.style.width = W + "px";
    this.canvas.style.height = H + "px";
    this.ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  }

  nFrames() {
    const r = this.run;
    if (r && r.n_total) return r.n_total;
    if (r && r.boxes) return r.boxes.length;
    if (!this.clipInfo) return 1;
    return this.clipInfo.n || (this.clipInfo.frames ? this.clipInfo.frames.length : 1);
  }

  buildKnobs() {
    const specs = this.host.knobs();
    const sig = JSON.stringify([this.host.tracker(), this.host.clipKey(), specs.map((k) => k.name),
                                this.host.live]);
    if (sig !== this.knobSig) {
      this.knobSig = sig;
      this.knobBox.textContent = "";
      this.inputs = {};
      for (const k of specs) this.inputs[k.name] = this.makeKnob(k);
    }
    for (const k of specs) this.showKnob(k, this.inputs[k.name]);
  }

  makeKnob(k) {
    const h = this.host;
    const lab = el("label", { class: "tb-knob", title: k.doc || "" }, this.knobBox);
    el("span", { class: "tb-knob-name", text: k.name }, lab);
    let input;
    if (!h.live) {
      input = el("input", { type: "range", "data-knob": k.name, min: 0,
                            max: k.samples.length - 1, step: 1 }, lab);
      if (!h.sampled(k)) { input.disabled = true; lab.title = "Jupyter only: " + (k.doc || ""); }
      input.addEventListener("input", () => h.setKnob(k.name, k.samples[+input.value]));
    } else if (k.kind === "choice") {
      input = el("select", { "data-knob": k.name }, lab);
      for (const c of k.choices) el("option", { value: c, text: c }, input);
      input.addEventListener("change", () => h.setKnob(k.name, input.value));
    } else if (k.kind === "bool") {
      input = el("input", { type: "checkbox", "data-knob": k.name }, lab);
      input.addEventListener("change", () => h.setKnob(k.name, input.checked));
    } else if (k.kind === "int" || k.kind === "float") {
      input = el("input", { type: "range", "data-knob": k.name, min: k.lo, max: k.hi,
                            step: k.step }, lab);
      input.addEventListener("change", () =>
        h.setKnob(k.name, k.kind === "int" ? Math.round(+input.value) : +input.value));
      input.addEventListener("input", () => { lab.lastChild.textContent = fmt(+input.value); });
    } else {
      input = el("input", { type: "text", "data-knob": k.name, size: 9 }, lab);
      input.addEventListener("change", () => {
        const parts = input.value.split(",").map((s) => +s.trim());
        h.setKnob(k.name, k.kind === "pair" ? parts : input.value);
      });
    }
    el("span", { class: "tb-knob-value" }, lab);
    return input;
  }

  showKnob(k, input) {
    const v = this.host.value(k.name);
    const lab = input.parentNode;
    if (!this.host.live) {
      let i = k.samples.findIndex((s) => same(s, v));
      if (i < 0) i = 0;
      input.value = i;
    } else if (k.kind === "bool") input.checked = !!v;
    else if (k.kind === "pair" || k.kind === "text") input.value = fmt(v);
    else input.value = v;
    lab.lastChild.textContent = fmt(v);
  }

  // ---- frames --------------------------------------------------------------------------
  seek(i) {
    const n = this.nFrames();
    this.frame = Math.max(0, Math.min(n - 1, i | 0));
    this.slider.value = this.frame;
    const per = this.clipInfo && this.clipInfo.per;
    const at = (k) => (this.frameIndex ? this.frameIndex[Math.min(k, this.frameIndex.length - 1)] : k);
    this.needFrame(at(this.frame));
    if (per && at(this.frame) % per >= per - 10) this.needFrame(at(this.frame) + 10);
    this.draw();
  }

  togglePlay() {
    this.playing = !this.playing;
    this.playBtn.textContent = this.playing ? "\u275a\u275a pause" : "\u25b6 play";
    if (!this.playing) return;
    if (this.frame >= this.nFrames() - 1) this.seek(0);
    let last = performance.now();
    const tick = (now) => {
      if (!this.playing || !this.root.isConnected) { this.playing = false; return; }
      const dt = 1000 / +this.speedSel.value;
      if (now - last >= dt) {
        last = now;
        if (this.frame >= this.nFrames() - 1) { this.togglePlay(); return; }
        this.seek(this.frame + 1);
      }
      requestAnimationFrame(tick);
    };
    requestAnimationFrame(tick);
  }

  // ---- drawing -------------------------------------------------------------------------
  box(b, color, width, dash) {
    if (!b) return;
    const c = this.ctx, s = this.scale;
    c.save();
    c.strokeStyle = color; c.lineWidth = width; c.setLineDash(dash || []);
    c.strokeRect(b[0] * s, b[1] * s, b[2] * s, b[3] * s);
    c.restore();
  }

  draw() {
    const c = this.ctx, s = this.scale, i = this.frame;
    if (!this.clipInfo) return;
    c.fillStyle = "#fff";
    c.fillRect(0, 0, this.W, this.H);
    const ii = this.frameIndex ? this.frameIndex[i] : i;   // animations: step -> image
    const im = this.images[ii];
    if (im && im.complete && im.naturalWidth) c.drawImage(im, 0, 0, this.fw, this.fh);
    else {
      c.fillStyle = "#222"; c.fillRect(0, 0, this.fw, this.fh);
      c.fillStyle = "#ddd"; c.font = "13px sans-serif";
      c.fillText("loading frames\u2026", 12, 22);
      this.needFrame(ii);
    }
    c.save();
    c.beginPath(); c.rect(0, 0, this.fw, this.fh); c.clip();   // nothing spills off the frame
    const gt = this.clipInfo.gt;
    if (gt && gt[i]) this.box(gt[i], this.colors.gt, 2);
    const extra = this.run && this.run.extra_boxes;   // animations: e.g. the measurement
    if (extra) for (const e of extra) if (e.boxes[i]) this.box(e.boxes[i], e.color, 2, e.dash);
    const r = this.run, st = this.state || {};
    const done = r && r.boxes ? (r.n_done !== undefined ? r.n_done : r.boxes.length) : 0;
    if (r && r.boxes && i >= done && this.lastFull && this.lastFull !== r &&
        this.lastFull.clip === r.clip && this.lastFull.boxes[i]) {         // a run still coming: the previous run's box, greyed
      this.box(this.lastFull.boxes[i], "rgba(128,128,128,0.8)", 2, [6, 4]);
    }
    if (this.stale) c.globalAlpha = 0.45;
    if (r && r.boxes && i < done) {
      if (st.search_window && st.search_window[i]) this.box(st.search_window[i], this.colors.window, 1.5, [5, 4]);
      if (st.response_box && st.response_box[i]) this.box(st.response_box[i], this.colors.response, 1, [2, 3]);
      if (st.candidates && st.candidates[i]) for (const b of st.candidates[i]) this.box(b, this.colors.cand, 1);
      if (st.particles && st.particles[i]) {
        const p = st.particles[i];
        c.fillStyle = this.colors.particle;
        for (let j = 0; j < p.length; j += 3) {
          const rad = 1.5 + 4 * Math.sqrt(Math.max(0, p[j + 2]) / 1000);
          c.globalAlpha = 0.35 + 0.5 * p[j + 2] / 1000;
          c.beginPath(); c.arc(p[j] / 2 * s, p[j + 1] / 2 * s, rad, 0, 2 * Math.PI); c.fill();
        }
        c.globalAlpha = 1;
      }
      if (st.ellipse && st.ellipse[i]) {
        const e = st.ellipse[i];
        c.save(); c.strokeStyle = this.colors.ellipse; c.lineWidth = 2;
        c.beginPath(); c.ellipse(e[0] * s, e[1] * s, Math.abs(e[2]) * s, Math.abs(e[3]) * s, 0, 0, 2 * Math.PI);
        c.stroke(); c.restore();
      }
      if (st.rays && st.rays[i]) {
        const q = st.rays[i];
        c.save(); c.strokeStyle = this.colors.ray; c.lineWidth = 1.5;
        for (let j = 0; j < 8 && j + 2 < q.length; j++) {
          const [dx, dy] = RAY_DIRS[j], n = Math.hypot(dx, dy);
          c.beginPath(); c.moveTo(q[0] * s, q[1] * s);
          c.lineTo((q[0] + dx / n * q[j + 2]) * s, (q[1] + dy / n * q[j + 2]) * s); c.stroke();
        }
        c.restore();
      }
      if (r.boxes[i]) this.box(r.boxes[i], this.colors.est, 2.5);
    }
    c.globalAlpha = 1;
    if (this.drag && this.drag.b) this.box(this.drag.b, this.colors.est, 2, [4, 3]);
    c.restore();
    this.curve();
    const iou = r && r.iou ? r.iou[i] : null;
    const conf = this.state && this.state.confidence && r && i < done ? this.state.confidence[i] : null;
    this.frameLabel.textContent = `frame ${i} / ${Math.max(0, this.nFrames() - 1)}` +
      (iou !== null && iou !== undefined ? ` \u00b7 IoU ${iou.toFixed(2)}` : "") +
      (conf !== null && conf !== undefined ? ` \u00b7 confidence ${fmt(conf)}` : "") +
      (r && r.ok ? (r.ok[i] ? "" : " \u00b7 lost") : "") +
      (r && r.captions && r.captions[i] ? " \u00b7 " + r.captions[i] : "");
  }

  // the legend sits under the canvas, never over the frame
  legend() {
    const items = [[(this.run && this.run.est_label) || "estimate", this.colors.est]];
    if (this.clipInfo && this.clipInfo.gt) items.unshift(["ground truth", this.colors.gt]);
    for (const e of (this.run && this.run.extra_boxes) || []) items.push([e.label, e.color]);
    if (this.run && this.run.seeds && !this.run.seeds.deterministic)
      items.push(["IoU range over the seeds", this.colors.curve, 0.25]);
    if (this.panels && this.panels.conf) {
      items.push(["confidence", this.colors.conf]);
      items.push(["frames judged lost", this.colors.lost, 0.25]);
    }
    if (this.panels && this.panels.resp) items.push(["response map's area", this.colors.response]);
    const sig = JSON.stringify(items);
    if (sig === this.legendSig) return;
    this.legendSig = sig;
    this.legendBox.textContent = "";
    for (const [name, col, alpha] of items) {
      const it = el("span", { class: "tb-legend-item" }, this.legendBox);
      const sw = el("span", { class: "tb-swatch" }, it);
      sw.style.background = col;
      if (alpha) sw.style.opacity = alpha;
      el("span", { text: name }, it);
    }
  }

  curve() {
    const P = this.panels || {};
    this.iouCurve(P.iou || { x: this.cx0, y: this.cy0, w: this.cw, h: this.ch });
    if (P.conf) this.confCurve(P.conf);
    if (P.resp) this.inset(P.resp);
  }

  // frames judged lost (ok = 0) as shaded columns of a plot
  lostBands(X, y0, h) {
    const r = this.run, c = this.ctx;
    if (!r || !r.ok) return;
    const n = this.nFrames(), dx = n > 1 ? (X(1) - X(0)) : 0;
    c.save(); c.fillStyle = this.colors.lost; c.globalAlpha = 0.25;
    r.ok.forEach((v, k) => { if (!v) c.fillRect(X(k) - dx / 2, y0, Math.max(1, dx), h); });
    c.restore();
  }

  // the tracker's own confidence per frame (its scale is the tracker's: PSR, likelihood, ...)
  confCurve(p) {
    const c = this.ctx, x0 = p.x + 34, y0 = p.y + 12, w = p.w - 44, h = p.h - 40;
    const ys = this.state.confidence, n = this.nFrames();
    const fin = ys.filter((v) => v !== null && v !== undefined && isFinite(v));
    let lo = Math.min(0, ...fin), hi = Math.max(...fin, lo + 1e-9);
    if (!(hi > lo)) hi = lo + 1;
    const X = (k) => x0 + (n > 1 ? k / (n - 1) : 0) * w, Y = (v) => y0 + h - (v - lo) / (hi - lo) * h;
    this.lostBands(X, y0, h);
    c.strokeStyle = "#000"; c.lineWidth = 1; c.strokeRect(x0, y0, w, h);
    c.fillStyle = "#000"; c.font = "11px sans-serif";
    c.save(); c.translate(p.x + 8, y0 + h / 2); c.rotate(-Math.PI / 2);
    c.textAlign = "center"; c.fillText("confidence", 0, 0); c.restore();
    c.textAlign = "right";      // the scale's ends, in the tracker's own units
    c.fillText(fmt(hi), x0 - 2, y0 - 2); c.fillText(fmt(lo), x0 - 2, y0 + h);
    c.textAlign = "left";
    c.fillText("frame", x0 + w / 2 - 14, y0 + h + 24);
    if (this.stale) c.globalAlpha = 0.35;
    c.strokeStyle = this.colors.conf; c.lineWidth = 1.5; c.beginPath();
    let pen = false;
    ys.forEach((v, k) => {
      if (v === null || v === undefined || !isFinite(v)) { pen = false; return; }
      if (pen) c.lineTo(X(k), Y(v)); else c.moveTo(X(k), Y(v));
      pen = true;
    });
    c.stroke();
    c.globalAlpha = 1;
    c.strokeStyle = "#000"; c.lineWidth = 1; c.setLineDash([2, 2]);
    c.beginPath(); c.moveTo(X(this.frame), y0); c.lineTo(X(this.frame), y0 + h); c.stroke();
    c.setLineDash([]);
  }

  // the current frame's response map over its area (the dotted box on the frame): the middle
  // cell is "no move" (crossed), the brightest is where the search put the target
  inset(p) {
    const c = this.ctx, i = this.frame, r = this.run;
    const done = r && r.boxes ? (r.n_done !== undefined ? r.n_done : r.boxes.length) : 0;
    const m = i < done && this.state.response ? this.state.response[i] : null;
    c.fillStyle = "#000"; c.font = "11px sans-serif"; c.textAlign = "left";
    c.fillText(m ? "response, this frame" : "response (none on this frame)", p.x, p.y - 5);
    c.strokeStyle = "#000"; c.lineWidth = 1; c.strokeRect(p.x - 0.5, p.y - 0.5, p.w + 1, p.h + 1);
    if (!m) { c.fillStyle = "#eee"; c.fillRect(p.x, p.y, p.w, p.h); return; }
    if (!this.cellCanvas) this.cellCanvas = document.createElement("canvas");
    const cc = this.cellCanvas;
    cc.width = m.cols; cc.height = m.rows;
    const g = cc.getContext("2d"), img = g.createImageData(m.cols, m.rows);
    let best = 0;
    for (let k = 0; k < m.q.length; k++) {
      const q = m.q[k];
      if (q > m.q[best]) best = k;
      img.data[4 * k] = LUT[3 * q]; img.data[4 * k + 1] = LUT[3 * q + 1];
      img.data[4 * k + 2] = LUT[3 * q + 2]; img.data[4 * k + 3] = 255;
    }
    g.putImageData(img, 0, 0);
    c.save();
    if (this.stale) c.globalAlpha = 0.45;
    c.imageSmoothingEnabled = false;       // cells stay cells
    c.drawImage(cc, p.x, p.y, p.w, p.h);
    c.restore();
    const sx = p.w / m.cols, sy = p.h / m.rows;
    const mx = p.x + (Math.floor(m.cols / 2) + 0.5) * sx, my = p.y + (Math.floor(m.rows / 2) + 0.5) * sy;
    c.strokeStyle = "#fff"; c.lineWidth = 1;
    c.beginPath(); c.moveTo(mx - 4, my); c.lineTo(mx + 4, my); c.moveTo(mx, my - 4); c.lineTo(mx, my + 4); c.stroke();
    const bx = p.x + (best % m.cols + 0.5) * sx, by = p.y + (Math.floor(best / m.cols) + 0.5) * sy;
    c.strokeStyle = this.colors.est; c.lineWidth = 1.5;
    c.beginPath(); c.arc(bx, by, Math.max(3, Math.min(sx, sy)), 0, 2 * Math.PI); c.stroke();
    c.fillStyle = "#000";
    if (m.range) c.fillText(`${fmt(m.range[0])} \u2026 ${fmt(m.range[1])}`, p.x, p.y + p.h + 13);
  }

  iouCurve(p) {
    const c = this.ctx, x0 = p.x + 34, y0 = p.y + 12, w = p.w - 44, h = p.h - 40;
    const r = this.run, n = this.nFrames();
    c.strokeStyle = "#000"; c.lineWidth = 1; c.strokeRect(x0, y0, w, h);
    c.fillStyle = "#000"; c.font = "11px sans-serif";
    const custom = r && r.curve;          // animations: any per-step series, 0..1
    const useIou = !custom && r && r.iou;
    c.save(); c.translate(p.x + 10, y0 + h / 2); c.rotate(-Math.PI / 2);
    c.textAlign = "center";
    c.fillText(custom ? custom.label : useIou ? "IoU with ground truth" : "tracker ok", 0, 0);
    c.restore();
    c.fillText(custom && custom.x ? custom.x : "frame", x0 + w / 2 - 14, y0 + h + 24);
    c.fillText("0", x0 - 3, y0 + h + 12); c.fillText(String(n - 1), x0 + w - 12, y0 + h + 12);
    c.fillText("1", x0 - 10, y0 + 8); c.fillText("0", x0 - 10, y0 + h);
    const X = (k) => x0 + (n > 1 ? k / (n - 1) : 0) * w, Y = (v) => y0 + h - v * h;
    c.strokeStyle = this.colors.grid; c.setLineDash([4, 3]);
    c.beginPath(); c.moveTo(x0, Y(0.5)); c.lineTo(x0 + w, Y(0.5)); c.stroke(); c.setLineDash([]);
    const ys = custom ? custom.values : useIou ? r.iou : (r && r.ok ? r.ok : null);
    const sd = useIou && r.seeds && !this.stale ? r.seeds : null;
    if (sd && sd.iou_lo && !sd.deterministic) {     // the band: least to greatest IoU over seeds
      c.save(); c.fillStyle = this.colors.curve; c.globalAlpha = 0.22;
      let open = false;
      const flush = (k0, k1) => {
        c.beginPath();
        for (let k = k0; k <= k1; k++) c.lineTo(X(k), Y(sd.iou_hi[k]));
        for (let k = k1; k >= k0; k--) c.lineTo(X(k), Y(sd.iou_lo[k]));
        c.closePath(); c.fill();
      };
      let k0 = 0;
      for (let k = 0; k <= sd.iou_lo.length; k++) {
        const okk = k < sd.iou_lo.length && sd.iou_lo[k] !== null && sd.iou_hi[k] !== null;
        if (okk && !open) { open = true; k0 = k; }
        if (!okk && open) { open = false; flush(k0, k - 1); }
      }
      c.restore();
    }
    if (this.stale) c.globalAlpha = 0.35;
    if (ys) {
      c.strokeStyle = this.colors.curve; c.lineWidth = 1.5; c.beginPath();
      let pen = false;
      ys.forEach((v, k) => {
        if (v === null || v === undefined) { pen = false; return; }
        if (pen) c.lineTo(X(k), Y(v)); else c.moveTo(X(k), Y(v));
        pen = true;
      });
      c.stroke();
    }
    c.globalAlpha = 1;
    c.strokeStyle = "#000"; c.lineWidth = 1; c.setLineDash([2, 2]);
    c.beginPath(); c.moveTo(X(this.frame), y0); c.lineTo(X(this.frame), y0 + h); c.stroke();
    c.setLineDash([]);
  }

  // ---- your own video: drag the target's box on frame 0 (Jupyter) ----------------------
  canDrag() { return this.host.live && this.clipInfo && !this.clipInfo.gt && this.frame === 0; }

  pos(ev) {
    const r = this.canvas.getBoundingClientRect();
    return [(ev.clientX - r.left) / this.scale, (ev.clientY - r.top) / this.scale];
  }

  dragStart(ev) {
    if (!this.canDrag()) return;
    const [x, y] = this.pos(ev);
    if (x > this.clipInfo.w) return;
    this.drag = { x, y, b: null };
  }

  dragMove(ev) {
    if (!this.drag) return;
    const [x, y] = this.pos(ev);
    const cx = Math.max(0, Math.min(this.clipInfo.w, x)), cy = Math.max(0, Math.min(this.clipInfo.h, y));
    this.drag.b = [Math.min(cx, this.drag.x), Math.min(cy, this.drag.y),
                   Math.abs(cx - this.drag.x), Math.abs(cy - this.drag.y)];
    this.draw();
  }

  dragEnd() {
    if (!this.drag) return;
    const b = this.drag.b;
    this.drag = null;
    if (b && b[2] >= 4 && b[3] >= 4) this.host.setBox(b.map((v) => Math.round(v * 10) / 10));
    this.draw();
  }
}

// ---- the static HTML book: runs precomputed at build time -------------------------------
// A page carries only the configuration; each run and each chunk of frames is a file
// tbpg-<hash>.js beside the book's pages that calls window.tbPlaygroundRegister(name, data).
// A <script> tag loads it when the reader picks it: that works from file:// and over http.

function spreadText(sd) {
  const a = (sd.auc || []).filter((x) => x !== null && x === x);
  if (!a.length) return "";
  if (sd.deterministic) return `AUC ${a[0].toFixed(2)} (same boxes for every seed)`;
  const mean = a.reduce((p, q) => p + q, 0) / a.length;
  return `AUC ${mean.toFixed(2)} (${Math.min(...a).toFixed(2)}\u2013${Math.max(...a).toFixed(2)} ` +
    `over ${a.length} seeds; boxes and state shown: seed ${sd.seeds[0]})`;
}

function files() {
  const g = typeof window !== "undefined" ? window : {};
  if (!g.__tbPlaygroundFiles) {
    const reg = { data: {}, wait: {}, failed: {} };
    g.__tbPlaygroundFiles = reg;
    g.tbPlaygroundRegister = (name, d) => {
      const r = g.__tbPlaygroundFiles;
      r.data[name] = d;
      const w = r.wait[name] || [];
      delete r.wait[name];
      for (const f of w) f(d);
    };
  }
  return g.__tbPlaygroundFiles;
}

function baseOf(root) {
  const b = root.getAttribute("data-tb-base") || "";
  if (b && !b.startsWith("@@")) return b;
  // not through the book's Sphinx extension: beside the page's _static scripts, if any
  const s = document.querySelector('script[src*="_static/"]');
  return s ? s.getAttribute("src").replace(/_static\/.*$/, "_static/playground/") : "";
}

function loadFile(base, name, cb) {
  const reg = files();
  if (name in reg.data) { cb(reg.data[name]); return; }
  if (reg.wait[name]) { reg.wait[name].push(cb); return; }
  reg.wait[name] = [cb];
  delete reg.failed[name];
  const s = document.createElement("script");
  s.src = base + name;
  s.async = true;
  s.onerror = () => {
    reg.failed[name] = true;
    const w = reg.wait[name] || [];
    delete reg.wait[name];
    for (const f of w) f(null);
  };
  document.head.appendChild(s);
}

function staticHost(data, root) {
  const cfg = data.config;
  const onDemand = !!data.files;
  const table = data.files || data.runs || {};
  const base = onDemand && root ? baseOf(root) : "";
  let clipKey = data.initial.clip, tracker = data.initial.tracker, values = {};
  let viewer = null;
  const knobs = () => cfg.knobs[tracker] || [];
  const defaults = () => Object.fromEntries(knobs().map((k) => [k.name, k.default]));
  values = defaults();
  let key = `${clipKey}|${tracker}|`;
  const ask = () => {
    if (onDemand && table[key]) loadFile(base, table[key], () => { if (viewer) viewer.update(); });
  };
  const host = {
    live: false,
    config: () => cfg,
    clipKey: () => clipKey,
    tracker: () => tracker,
    clip: () => data.clips[clipKey],
    run: () => {
      if (!onDemand) return table[key] || null;
      const d = table[key] ? files().data[table[key]] : null;
      return d || null;
    },
    loading: () => onDemand && !!table[key] && !(table[key] in files().data) &&
      !files().failed[table[key]],
    loadFile: onDemand ? (name, cb) => loadFile(base, name, cb) : null,
    knobs,
    value: (name) => values[name],
    sampled: (k) => k.samples.some((v, i) => !same(v, k.default) &&
                                   `${clipKey}|${tracker}|${k.name}#${i}` in table),
    note: () => data.note !== undefined ? data.note : "This page holds runs over the whole clip " +
      "for a few values of each knob (the book's default, the paper's value where it prints " +
      "one, and two others), one knob at a time (the others return to their defaults), each " +
      "over several seeds; in Jupyter the playground re-runs the tracker for any value." +
      (host.run() && host.run().seeds && host.run().seeds.deterministic ? ` ${tracker} ` +
       "gave the same boxes for two seeds here, so each of its runs is computed once." : "") +
      (knobs().some((k) => !host.sampled(k)) ? " Greyed knobs: Jupyter only." : ""),
    status: () => {
      if (!table[key]) return "(no precomputed run for this choice)";
      if (onDemand && files().failed[table[key]]) return "\u26a0 could not load " + table[key];
      return host.loading() ? "loading\u2026" : "";
    },
    setClip(c) { clipKey = c; values = defaults(); key = `${clipKey}|${tracker}|`; ask(); viewer.update(); },
    setTracker(t) { tracker = t; values = defaults(); key = `${clipKey}|${tracker}|`; ask(); viewer.update(); },
    setKnob(name, v) {
      values = defaults();
      const k = knobs().find((q) => q.name === name);
      const i = k.samples.findIndex((s) => same(s, v));
      values[name] = v;
      key = same(v, k.default) ? `${clipKey}|${tracker}|` : `${clipKey}|${tracker}|${name}#${i}`;
      ask();
      viewer.update();
    },
    setBox() {},
  };
  ask();
  return { host, attach: (v) => { viewer = v; } };
}

function mountStatic(root) {
  const script = root.querySelector("script.tb-data");
  if (!script) return;
  const data = JSON.parse(script.textContent);
  const { host, attach } = staticHost(data, root);
  const v = new Viewer(root, host);
  attach(v);
  v.update();
}

function mountAll() {
  document.querySelectorAll(".tb-playground[data-tb-static]:not([data-tb-ready])").forEach((r) => {
    r.setAttribute("data-tb-ready", "1");
    mountStatic(r);
  });
}

if (typeof document !== "undefined") {
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", mountAll);
  else mountAll();
}

// ---- Jupyter (anywidget): the kernel re-runs on a knob change ------------------------------
function render({ model, el: root }) {
  const fixed = model.get("static_data");
  if (fixed && fixed.runs) {              // an animation: everything precomputed, no kernel
    const { host, attach } = staticHost(fixed, null);
    const v = new Viewer(root, host);
    attach(v);
    v.update();
    return () => { v.playing = false; };
  }
  const cfg = () => model.get("config");
  const host = {
    live: true,
    config: cfg,
    clipKey: () => model.get("clip"),
    tracker: () => model.get("tracker"),
    clip: () => model.get("clip_data"),
    run: () => model.get("run_data"),
    knobs: () => cfg().knobs[model.get("tracker")] || [],
    value: (name) => model.get("values")[name],
    sampled: () => true,
    note: () => "",
    status: () => (model.get("busy") ? "running\u2026" : model.get("error") ? "\u26a0 " + model.get("error") : ""),
    setClip(c) { model.set("clip", c); model.save_changes(); },
    setTracker(t) { model.set("tracker", t); model.save_changes(); },
    setKnob(name, v) {
      model.set("values", { ...model.get("values"), [name]: v });
      model.set("frame", v_.frame);  // the kernel re-runs up to the frame on screen first
      model.save_changes();
      v_.status.textContent = "running\u2026";
    },
    setBox(b) { model.set("init_box", b); model.save_changes(); v_.status.textContent = "running\u2026"; },
  };
  const v_ = new Viewer(root, host);
  const up = () => v_.update();
  for (const ev of ["change:run_data", "change:clip_data", "change:busy", "change:error"]) model.on(ev, up);
  v_.update();
  return () => { v_.playing = false; for (const ev of ["change:run_data", "change:clip_data", "change:busy", "change:error"]) model.off(ev, up); };
}

export { Viewer, decodeState, mountAll, spreadText };
export default { render };
