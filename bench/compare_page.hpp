#pragma once
// The page that glint-compare writes: plain HTML, CSS and JavaScript in one file, with no
// network access of any kind; the images are PNG files beside it and the data is the JSON that
// glint-compare puts in place of the marker /*GLINT_DATA*/ (a <script type="application/json">
// element, so the page's code reads it with JSON.parse and never evaluates it).
//
// The page's state, for a person and for tests/viewer/viewer_test.bash alike: <body> carries
// data-images (how many images the page preloads), then data-state="done" with data-loaded and
// data-failed once every image has loaded or failed; each row of the variant table carries
// data-variant (data-entry="reference" for the reference's row).

#include <string_view>

namespace glint_compare {

inline constexpr std::string_view kDataMarker = "/*GLINT_DATA*/";

inline constexpr std::string_view kPageTemplate = R"glint_page(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>glint-compare</title>
<style>
  :root {
    color-scheme: dark;
    --bg: #15171b; --panel: #1d2026; --line: #30343c; --text: #e4e6ea; --muted: #99a0aa;
    --a: #5aa2ff; --b: #ffb454; --bad: #ff6b6b;
  }
  * { box-sizing: border-box; }
  html, body { height: 100%; }
  body {
    margin: 0; display: flex; flex-direction: column; background: var(--bg); color: var(--text);
    font: 14px/1.45 system-ui, -apple-system, "Segoe UI", sans-serif;
  }
  header {
    display: flex; flex-wrap: wrap; align-items: baseline; gap: 6px 18px;
    padding: 8px 14px; border-bottom: 1px solid var(--line);
  }
  h1 { font-size: 16px; margin: 0; font-weight: 600; }
  .muted { color: var(--muted); }
  select, button {
    font: inherit; color: inherit; background: var(--panel); border: 1px solid var(--line);
    border-radius: 4px; padding: 2px 8px;
  }
  button { cursor: pointer; }
  #problems { padding: 6px 14px; background: #3a1d1f; color: var(--bad); }
  main { flex: 1; display: flex; min-height: 0; }
  #viewer { flex: 1; display: flex; flex-direction: column; min-width: 0; }
  #view {
    flex: 1; position: relative; overflow: hidden; cursor: grab; outline: none;
    background: #0c0d10;
  }
  #view.dragging { cursor: grabbing; }
  #image {
    position: absolute; left: 0; top: 0; transform-origin: 0 0; max-width: none;
    image-rendering: pixelated; user-select: none; -webkit-user-drag: none;
  }
  #badge {
    position: absolute; left: 10px; top: 10px; padding: 2px 10px; border-radius: 4px;
    background: rgba(0, 0, 0, 0.65); font-weight: 600; pointer-events: none;
  }
  #badge.a { border-left: 4px solid var(--a); }
  #badge.b { border-left: 4px solid var(--b); }
  #status {
    display: flex; flex-wrap: wrap; gap: 4px 18px; padding: 6px 14px;
    border-top: 1px solid var(--line); font-variant-numeric: tabular-nums;
  }
  #legend { display: flex; align-items: center; gap: 10px; padding: 0 14px 8px; }
  #legend[hidden] { display: none; }
  #legend .bar { width: 260px; height: 12px; border-radius: 2px; }
  #legend .ticks { position: relative; width: 260px; height: 1.3em; font-size: 12px; }
  #legend .ticks span { position: absolute; top: 0; transform: translateX(-50%); }
  #legend .scale { display: flex; flex-direction: column; gap: 2px; padding: 0 12px; }
  aside {
    width: min(580px, 46vw); overflow: auto; padding: 10px 12px;
    border-left: 1px solid var(--line); background: var(--panel);
  }
  table { border-collapse: collapse; width: 100%; font-variant-numeric: tabular-nums; }
  th, td { padding: 3px 5px; text-align: right; white-space: nowrap; }
  th { font-weight: 600; color: var(--muted); border-bottom: 1px solid var(--line); }
  th.name, td.name { text-align: left; }
  td.name small { display: block; color: var(--muted); white-space: normal; font-size: 12px; }
  td.mark { width: 3.4em; padding-right: 0; text-align: left; }
  tbody tr { cursor: pointer; border-bottom: 1px solid var(--line); }
  tbody tr:hover { background: #262a32; }
  tbody tr.shown { background: #25334a; }
  tr.failed td.name { color: var(--bad); }
  .tag {
    display: inline-block; min-width: 1.4em; margin-right: 2px; border-radius: 3px;
    text-align: center; font-size: 12px; font-weight: 700; color: #111;
  }
  .tag.a { background: var(--a); }
  .tag.b { background: var(--b); }
  .better { color: #7ddc8c; }
  .worse { color: #f29b8f; }
  kbd {
    display: inline-block; min-width: 1.6em; padding: 0 4px; border: 1px solid var(--line);
    border-radius: 3px; background: var(--bg); text-align: center; font: 12px monospace;
  }
  #help { margin-top: 14px; color: var(--muted); }
  #help dl { display: grid; grid-template-columns: max-content 1fr; gap: 2px 10px; margin: 0; }
  #help dd { margin: 0; }
</style>
</head>
<body data-state="loading">
<header>
  <h1 id="title">glint-compare</h1>
  <label>Scene <select id="scene"></select></label>
  <span id="note" class="muted"></span>
</header>
<div id="problems" hidden></div>
<noscript>
  <p>This page needs JavaScript (it runs locally; nothing is fetched from a network).</p>
</noscript>
<main>
  <section id="viewer">
    <div id="view" tabindex="0">
      <img id="image" alt="" draggable="false"><span id="badge"></span>
    </div>
    <div id="status">
      <span id="showing"></span>
      <span id="mode"></span>
      <span id="zoom"></span>
      <span id="pixel" class="muted">pixel -</span>
    </div>
    <div id="legend" hidden>
      <div class="scale">
        <div class="bar" id="legend-bar"></div>
        <div class="ticks" id="legend-ticks"></div>
      </div>
      <span class="muted" id="legend-caption"></span>
    </div>
  </section>
  <aside>
    <table>
      <thead>
        <tr>
          <th></th>
          <th class="name">variant</th>
          <th title="samples per pixel">spp</th>
          <th title="CPU seconds of the render">CPU s</th>
          <th title="CPU time as a ratio to the baseline's">&times;</th>
          <th title="root mean squared error of the linear radiance against the reference">RMSE</th>
          <th title="RMSE as a ratio to the baseline's">&times;</th>
          <th title="mean relative squared error: the mean of the error map">relMSE</th>
        </tr>
      </thead>
      <tbody id="rows"></tbody>
    </table>
    <p class="muted" id="table-note"></p>
    <section id="help">
      <dl>
        <dt><kbd>&larr;</kbd> <kbd>&rarr;</kbd> or <kbd>1</kbd>-<kbd>9</kbd>, <kbd>r</kbd></dt>
        <dd>previous / next image, the n-th variant, the reference (as A); or click a row</dd>
        <dt><kbd>b</kbd> or shift-click</dt><dd>pin the shown image (or the row) as B</dd>
        <dt><kbd>space</kbd> or <kbd>f</kbd></dt><dd>flip between A and B</dd>
        <dt><kbd>e</kbd></dt><dd>error map of the shown variant on / off</dd>
        <dt><kbd>+</kbd> <kbd>-</kbd> or wheel</dt><dd>zoom (to single pixels); drag to pan</dd>
        <dt><kbd>0</kbd> or double-click</dt><dd>fit the image to the view</dd>
        <dt><kbd>[</kbd> <kbd>]</kbd></dt><dd>previous / next scene</dd>
      </dl>
    </section>
  </aside>
</main>
<script id="glint-data" type="application/json">/*GLINT_DATA*/</script>
<script>
"use strict";
(function () {
  const data = JSON.parse(document.getElementById("glint-data").textContent);
  const byId = (id) => document.getElementById(id);
  const view = byId("view");
  const image = byId("image");
  const maxScale = 64;  // screen pixels per image pixel at the closest zoom

  // Entry 0 of a scene is its reference, then the variants in the manifest's order.
  const scenes = data.scenes.map((scene) => ({
    ...scene,
    entries: [{ ...scene.reference, name: "reference", isReference: true }, ...scene.variants],
  }));
  const state = { scene: 0, a: 0, b: 0, showB: false, error: false,
                  scale: 1, x: 0, y: 0, fitted: true };
  const failedImages = new Set();

  const scene = () => scenes[state.scene];
  const shownIndex = () => (state.showB ? state.b : state.a);
  const shown = () => scene().entries[shownIndex()];
  const baseline = () => scene().entries.find((e) => e.name === scene().baseline);

  function format(value, digits) {
    return value === null || value === undefined ? "-" : Number(value).toPrecision(digits);
  }
  function ratioCell(value, base, lowerIsBetter) {
    const td = document.createElement("td");
    if (value === null || value === undefined || !base || !(base > 0)) {
      td.textContent = "-";
      return td;
    }
    const ratio = value / base;
    td.textContent = ratio.toFixed(2) + "\u00d7";
    if (Math.abs(ratio - 1) > 0.05) {
      td.className = (ratio < 1) === lowerIsBetter ? "better" : "worse";
    }
    return td;
  }
  function cell(text, className) {
    const td = document.createElement("td");
    td.textContent = text;
    if (className) td.className = className;
    return td;
  }

  // ---- the table of variants ----------------------------------------------------------------
  function renderTable() {
    const rows = byId("rows");
    rows.replaceChildren();
    const base = baseline();
    scene().entries.forEach((entry, index) => {
      const tr = document.createElement("tr");
      if (entry.isReference) tr.dataset.entry = "reference";
      else tr.dataset.variant = entry.name;
      const mark = cell("", "mark");
      for (const [slot, label] of [["a", "A"], ["b", "B"]]) {
        if (state[slot] !== index) continue;
        const tag = document.createElement("span");
        tag.className = "tag " + slot;
        tag.textContent = label;
        mark.append(tag);
      }
      tr.append(mark);
      const name = cell("", "name");
      const key = entry.isReference ? "r" : index <= 9 ? String(index) : "";
      if (key) {
        const kbd = document.createElement("kbd");
        kbd.textContent = key;
        name.append(kbd, " ");
      }
      name.append(entry.name + (entry.name === scene().baseline ? " (baseline)" : ""));
      if (entry.description) {
        const small = document.createElement("small");
        small.textContent = entry.description;
        name.append(small);
      }
      tr.append(name, cell(entry.spp ?? "-"), cell(format(entry.cpu, 3)));
      if (entry.isReference) {
        tr.append(cell("-"), cell("-"), cell("-"), cell("-"));
      } else {
        const rmse = cell(format(entry.rmse, 3));
        rmse.title = "relative RMSE (RMSE / mean of the reference): " +
                     format(entry.relativeRmse, 3);
        tr.append(ratioCell(entry.cpu, base && base.cpu, true), rmse,
                  ratioCell(entry.rmse, base && base.rmse, true), cell(format(entry.relMse, 3)));
      }
      if (failedImages.has(entry.image) || failedImages.has(entry.errorImage)) {
        tr.classList.add("failed");
        tr.title = "an image of this row did not load";
      }
      if (index === shownIndex()) tr.classList.add("shown");
      tr.addEventListener("click", (event) => {
        if (event.shiftKey) pinB(index);
        else select(index);
      });
      rows.append(tr);
    });
    byId("table-note").textContent = scene().baseline
      ? "Ratios are to " + scene().baseline + "; below 1 is faster or more accurate."
      : "";
  }

  // ---- what is shown ------------------------------------------------------------------------
  function update() {
    const entry = shown();
    const showError = state.error && !entry.isReference;
    const source = showError ? entry.errorImage : entry.image;
    if (image.getAttribute("src") !== source) image.src = source;
    image.alt = entry.name + (showError ? " error map" : "");
    const slot = state.showB ? "b" : "a";
    const badge = byId("badge");
    badge.className = slot;
    badge.textContent = slot.toUpperCase() + ": " + entry.name + (showError ? " (error)" : "");
    let text = (state.showB ? "B" : "A") + ": " + entry.name;
    if (entry.spp) text += ", " + entry.spp + " spp";
    if (entry.cpu !== null && entry.cpu !== undefined) {
      text += ", " + format(entry.cpu, 3) + " s CPU";
    }
    if (!entry.isReference) {
      text += ", RMSE " + format(entry.rmse, 3) +
              " (relative " + format(entry.relativeRmse, 3) + ")";
    }
    byId("showing").textContent = text;
    byId("mode").textContent = showError
      ? "error map (relative squared error)"
      : state.error
        ? "the reference has no error map"
        : "image (" + data.toneMapping + ")";
    byId("legend").hidden = !showError;
    if (showError) renderLegend();
    renderTable();
    const hash = "#" + encodeURIComponent(scene().name) + "/" + encodeURIComponent(entry.name) +
                 (state.error ? "/error" : "");
    if (location.hash !== hash) {
      try {
        history.replaceState(null, "", hash);
      } catch (error) {
        // Some browsers refuse history changes on file:// pages; the link is a convenience.
      }
    }
  }

  function renderLegend() {
    const [low, high] = scene().errorDecades;
    byId("legend-bar").style.background = "linear-gradient(to right, " + data.ramp.join(", ") + ")";
    const ticks = byId("legend-ticks");
    ticks.replaceChildren();
    const superscripts = "\u207b\u2070\u00b9\u00b2\u00b3\u2074\u2075\u2076\u2077\u2078\u2079";
    const superscript = (n) =>
      String(n).replace(/./g, (c) => superscripts["-0123456789".indexOf(c)]);
    for (let d = low; d <= high; ++d) {
      const span = document.createElement("span");
      span.textContent = "10" + superscript(d);
      span.style.left = (100 * (d - low) / (high - low)) + "%";
      ticks.append(span);
    }
    byId("legend-caption").textContent =
      "(x - r)\u00b2 / (r\u00b2 + " + data.errorEpsilon + "), mean over RGB; log scale, clamped";
  }

  function select(index) {
    state.a = index;
    state.showB = false;
    update();
  }
  function pinB(index) {
    state.b = index;
    update();
  }
  function flip() {
    if (state.a === state.b) {
      byId("mode").textContent = "A and B are the same image: press b on another to pin it as B";
      return;
    }
    state.showB = !state.showB;
    update();
  }
  function selectScene(index) {
    state.scene = (index + scenes.length) % scenes.length;
    byId("scene").value = String(state.scene);
    const base = scene().entries.findIndex((e) => e.name === scene().baseline);
    state.a = base > 0 ? base : Math.min(1, scene().entries.length - 1);
    state.b = 0;
    state.showB = false;
    image.style.width = scene().width + "px";
    image.style.height = scene().height + "px";
    fit();
    update();
  }

  // ---- zoom and pan -------------------------------------------------------------------------
  function apply() {
    image.style.transform =
      "translate(" + state.x + "px, " + state.y + "px) scale(" + state.scale + ")";
    byId("zoom").textContent = "zoom " + (state.scale >= 10 ? state.scale.toFixed(0)
                                                            : state.scale.toFixed(2)) + "\u00d7";
  }
  function fit() {
    const box = view.getBoundingClientRect();
    const s = scene();
    state.scale = Math.max(Math.min(box.width / s.width, box.height / s.height, maxScale), 1e-3);
    state.x = (box.width - s.width * state.scale) / 2;
    state.y = (box.height - s.height * state.scale) / 2;
    state.fitted = true;
    apply();
  }
  function zoomAt(factor, cx, cy) {
    const minScale = Math.min(1, fitScale() / 2);
    const next = Math.min(Math.max(state.scale * factor, minScale), maxScale);
    // Keep the image point under (cx, cy) where it is.
    state.x = cx - (cx - state.x) * (next / state.scale);
    state.y = cy - (cy - state.y) * (next / state.scale);
    state.scale = next;
    state.fitted = false;
    apply();
  }
  function fitScale() {
    const box = view.getBoundingClientRect();
    return Math.min(box.width / scene().width, box.height / scene().height);
  }
  function zoomCentre(factor) {
    const box = view.getBoundingClientRect();
    zoomAt(factor, box.width / 2, box.height / 2);
  }

  view.addEventListener("wheel", (event) => {
    event.preventDefault();
    const box = view.getBoundingClientRect();
    const step = event.deltaMode === 1 ? 0.05 : 0.002;  // lines or pixels
    zoomAt(Math.exp(-event.deltaY * step), event.clientX - box.left, event.clientY - box.top);
  }, { passive: false });
  let drag = null;
  view.addEventListener("pointerdown", (event) => {
    drag = { x: event.clientX, y: event.clientY };
    view.setPointerCapture(event.pointerId);
    view.classList.add("dragging");
    view.focus();
  });
  view.addEventListener("pointermove", (event) => {
    if (drag) {
      state.x += event.clientX - drag.x;
      state.y += event.clientY - drag.y;
      drag = { x: event.clientX, y: event.clientY };
      state.fitted = false;
      apply();
    }
    const box = view.getBoundingClientRect();
    const px = Math.floor((event.clientX - box.left - state.x) / state.scale);
    const py = Math.floor((event.clientY - box.top - state.y) / state.scale);
    const inside = px >= 0 && py >= 0 && px < scene().width && py < scene().height;
    byId("pixel").textContent = inside ? "pixel " + px + ", " + py : "pixel -";
  });
  const endDrag = () => {
    drag = null;
    view.classList.remove("dragging");
  };
  view.addEventListener("pointerup", endDrag);
  view.addEventListener("pointercancel", endDrag);
  view.addEventListener("pointerleave", () => { byId("pixel").textContent = "pixel -"; });
  view.addEventListener("dblclick", fit);
  window.addEventListener("resize", () => { if (state.fitted) fit(); });

  // ---- keys ---------------------------------------------------------------------------------
  document.addEventListener("keydown", (event) => {
    if (event.ctrlKey || event.metaKey || event.altKey) return;
    if (event.target instanceof HTMLSelectElement) return;
    const count = scene().entries.length;
    const key = event.key;
    if (key === "ArrowRight" || key === "ArrowDown") select((state.a + 1) % count);
    else if (key === "ArrowLeft" || key === "ArrowUp") select((state.a + count - 1) % count);
    else if (/^[1-9]$/.test(key)) { if (Number(key) < count) select(Number(key)); }
    else if (key === "r") select(0);
    else if (key === "b") pinB(shownIndex());
    else if (key === " " || key === "f") flip();
    else if (key === "e") { state.error = !state.error; update(); }
    else if (key === "+" || key === "=") zoomCentre(Math.SQRT2);
    else if (key === "-" || key === "_") zoomCentre(Math.SQRT1_2);
    else if (key === "0") fit();
    else if (key === "[" || key === "PageUp") selectScene(state.scene - 1);
    else if (key === "]" || key === "PageDown") selectScene(state.scene + 1);
    else return;
    event.preventDefault();
  });

  // ---- start --------------------------------------------------------------------------------
  document.title = data.title;
  byId("title").textContent = data.title;
  byId("note").textContent = data.note;
  const sceneSelect = byId("scene");
  scenes.forEach((s, index) => {
    const option = document.createElement("option");
    option.value = String(index);
    option.textContent = s.name;
    option.dataset.scene = s.name;
    sceneSelect.append(option);
  });
  sceneSelect.addEventListener("change", () => {
    selectScene(Number(sceneSelect.value));
    sceneSelect.blur();  // so that the arrow keys go back to the images
  });

  // Every image is loaded once at the start: flipping is then instant, and the page can say
  // whether all of them are there.
  const sources = [];
  for (const s of scenes) {
    for (const entry of s.entries) {
      sources.push(entry.image);
      if (entry.errorImage) sources.push(entry.errorImage);
    }
  }
  document.body.dataset.images = String(sources.length);
  let loaded = 0;
  const settle = () => {
    if (loaded + failedImages.size < sources.length) return;
    document.body.dataset.loaded = String(loaded);
    document.body.dataset.failed = String(failedImages.size);
    document.body.dataset.state = "done";
    if (failedImages.size > 0) {
      const problems = byId("problems");
      problems.textContent = "Could not load " + failedImages.size + " of " + sources.length +
                             " images: " + [...failedImages].join(", ");
      problems.hidden = false;
    }
    renderTable();
  };
  const preloaded = sources.map((source) => {
    const img = new Image();
    img.onload = () => { ++loaded; settle(); };
    img.onerror = () => { failedImages.add(source); settle(); };
    img.src = source;
    return img;
  });
  window.glintPreloaded = preloaded;  // kept alive, so the browser keeps them decoded
  settle();

  // A link may name a scene, an image and the error view: #SCENE, #SCENE/VARIANT or
  // #SCENE/VARIANT/error (the page keeps its address up to date, so it can be shared).
  const decode = (part) => {
    try {
      return decodeURIComponent(part);
    } catch (error) {
      return "";  // a mistyped link shows the first scene, not a broken page
    }
  };
  const [hashScene, hashEntry, hashView] = location.hash.slice(1).split("/").map(decode);
  state.error = hashView === "error";
  selectScene(Math.max(0, scenes.findIndex((s) => s.name === hashScene)));
  const entryIndex = scene().entries.findIndex((e) => e.name === hashEntry);
  if (entryIndex >= 0) select(entryIndex);
})();
</script>
</body>
</html>
)glint_page";

}  // namespace glint_compare
