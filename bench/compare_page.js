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
