// trackbook playground viewer: draws a precomputed tracker run on a canvas.
// One module for every playground of the book. The data (frames as JPEG data URLs, boxes,
// particles, IoU, scores) sits in a <script type="application/json"> next to the root element,
// so the page works opened from disk and offline. A frame step costs no Python.
(function () {
  "use strict";
  const GT = "#009E73", EST = "#D55E00", PART = "#0072B2", GRID = "#dddddd";

  function el(tag, attrs, text) {
    const e = document.createElement(tag);
    for (const k in (attrs || {})) e.setAttribute(k, attrs[k]);
    if (text !== undefined) e.textContent = text;
    return e;
  }

  function mount(root) {
    if (root.dataset.tbMounted) return;
    root.dataset.tbMounted = "1";
    const data = JSON.parse(document.getElementById(root.dataset.tbData).textContent);
    const state = { tracker: data.trackers[0], clip: data.clips_order[0], knob: "", value: "",
                    frame: 0, playing: false, timer: null, speed: 1 };
    const controls = el("div", { class: "tb-controls" });
    const mkSelect = (label, options, attrs) => {
      const wrap = el("label", {}, label + " ");
      const s = el("select", attrs || {});
      for (const o of options) s.appendChild(el("option", { value: o }, o));
      wrap.appendChild(s); controls.appendChild(wrap); return s;
    };
    const clipSel = mkSelect("clip", data.clips_order, { "data-choice": "clip" });
    const trackerSel = mkSelect("tracker", data.trackers, { "data-choice": "tracker" });
    const knobSels = {};
    for (const name of Object.keys(data.knobs)) {
      const s = mkSelect(name, data.knobs[name].values, { "data-knob": name });
      s.value = data.knobs[name].default;
      knobSels[name] = s;
    }
    const bar = el("div", { class: "tb-bar" });
    const play = el("button", { "data-play": "", type: "button" }, "\u25B6 play");
    const speed = el("select", { "data-speed": "" });
    for (const v of ["0.5", "1", "2", "4"]) speed.appendChild(el("option", { value: v }, v + "\u00D7"));
    speed.value = "1";
    const slider = el("input", { type: "range", min: "0", max: "1", value: "0", step: "1",
                                 "data-frame": "", "aria-label": "frame" });
    const flabel = el("span", { class: "tb-frame" }, "frame 0");
    bar.append(play, speed, slider, flabel);
    const canvas = el("canvas", { width: "720", height: "300", tabindex: "0" });
    const scores = el("div", { class: "tb-scores" });
    const note = el("div", { class: "tb-note" }, data.note);
    root.append(controls, bar, canvas, scores, note);
    const ctx = canvas.getContext("2d");
    const images = {};

    function run() {
      const key = [state.tracker, state.clip, state.knob ? state.knob + "=" + state.value : ""]
        .join("|");
      return data.runs[key] || data.runs[[state.tracker, state.clip, ""].join("|")];
    }
    function image(clip, i) {
      const k = clip + "#" + i;
      if (!images[k]) {
        const im = new Image();
        im.onload = () => { if (state.clip === clip && state.frame === i) draw(); };
        im.src = data.clips[clip].frames[i];
        images[k] = im;
      }
      return images[k];
    }
    function box(b, sx, sy, color, dash) {
      if (!b) return;
      ctx.save(); ctx.strokeStyle = color; ctx.lineWidth = 2; ctx.setLineDash(dash || []);
      ctx.strokeRect(b[0] * sx, b[1] * sy, b[2] * sx, b[3] * sy); ctx.restore();
    }
    function draw() {
      const r = run(), c = data.clips[state.clip];
      const n = r.boxes.length;
      if (state.frame >= n) state.frame = n - 1;
      slider.max = String(n - 1); slider.value = String(state.frame);
      flabel.textContent = "frame " + state.frame + " / " + (n - 1);
      const W = canvas.width, H = canvas.height, fw = Math.round(H * c.w / c.h);
      ctx.fillStyle = "#ffffff"; ctx.fillRect(0, 0, W, H);
      const im = image(state.clip, state.frame);
      if (im.complete && im.naturalWidth) ctx.drawImage(im, 0, 0, fw, H);
      const sx = fw / c.w, sy = H / c.h;
      const p = r.particles ? r.particles[state.frame] : null;
      if (p) {
        ctx.fillStyle = PART;
        for (const q of p) { ctx.globalAlpha = 0.25 + 0.75 * (q[2] || 0);
          ctx.fillRect(q[0] * sx - 1.5, q[1] * sy - 1.5, 3, 3); }
        ctx.globalAlpha = 1;
      }
      if (r.windows && r.windows[state.frame]) box(r.windows[state.frame], sx, sy, "#E69F00", [4, 3]);
      box(c.gt[state.frame], sx, sy, GT, [6, 3]);
      box(r.boxes[state.frame], sx, sy, r.ok[state.frame] ? EST : "#CC79A7");
      // the per-frame curve (IoU with ground truth, or the tracker's ok without one)
      const x0 = fw + 30, x1 = W - 10, y0 = 20, y1 = H - 30;
      ctx.strokeStyle = GRID; ctx.strokeRect(x0, y0, x1 - x0, y1 - y0);
      ctx.fillStyle = "#333"; ctx.font = "11px sans-serif";
      ctx.fillText(r.iou ? "IoU per frame" : "tracker ok per frame", x0, y0 - 6);
      ctx.fillText("1", x0 - 12, y0 + 4); ctx.fillText("0", x0 - 12, y1 + 4);
      const vals = r.iou || r.ok.map((v) => (v ? 1 : 0));
      ctx.strokeStyle = EST; ctx.lineWidth = 1.2; ctx.beginPath();
      vals.forEach((v, i) => { const X = x0 + (x1 - x0) * i / Math.max(1, n - 1);
        const Y = y1 - (y1 - y0) * (v == null ? 0 : v); i ? ctx.lineTo(X, Y) : ctx.moveTo(X, Y); });
      ctx.stroke();
      const cx = x0 + (x1 - x0) * state.frame / Math.max(1, n - 1);
      ctx.strokeStyle = "#000"; ctx.setLineDash([2, 2]); ctx.beginPath();
      ctx.moveTo(cx, y0); ctx.lineTo(cx, y1); ctx.stroke(); ctx.setLineDash([]);
      scores.textContent = r.scores;
    }
    function stop() { state.playing = false; clearInterval(state.timer); play.textContent = "\u25B6 play"; }
    function step(d) {
      const n = run().boxes.length;
      state.frame = Math.max(0, Math.min(n - 1, state.frame + d)); draw();
    }
    play.addEventListener("click", () => {
      if (state.playing) return stop();
      state.playing = true; play.textContent = "\u275A\u275A pause";
      state.timer = setInterval(() => {
        const n = run().boxes.length;
        if (state.frame >= n - 1) state.frame = -1;
        step(1);
      }, 1000 / (15 * Number(speed.value)));
    });
    speed.addEventListener("change", () => { if (state.playing) { stop(); play.click(); } });
    slider.addEventListener("input", () => { state.frame = Number(slider.value); draw(); });
    canvas.addEventListener("keydown", (e) => {
      if (e.key === "ArrowRight") { step(1); e.preventDefault(); }
      if (e.key === "ArrowLeft") { step(-1); e.preventDefault(); }
    });
    clipSel.addEventListener("change", () => { state.clip = clipSel.value; draw(); });
    trackerSel.addEventListener("change", () => { state.tracker = trackerSel.value; draw(); });
    for (const name in knobSels) {
      knobSels[name].addEventListener("change", () => {
        // the HTML holds runs for one knob at a time around the defaults: reset the others
        for (const other in knobSels) if (other !== name) knobSels[other].value = data.knobs[other].default;
        const v = knobSels[name].value;
        state.knob = v === data.knobs[name].default ? "" : name; state.value = v; draw();
      });
    }
    draw();
  }

  function mountAll() { document.querySelectorAll(".tb-playground[data-tb-data]").forEach(mount); }
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", mountAll);
  else mountAll();
  if (typeof window !== "undefined") window.tbMountPlaygrounds = mountAll;
})();
