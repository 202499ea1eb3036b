// The labeller's page: holds the labels being edited, asks the server for all cable geometry.
// A frame's record is {s: [d, alpha, w, beta] or null, k: "key" | "interpolated" | "none" | null}.
"use strict";

const root = document.getElementById("labeller");
const view = document.getElementById("view");
const image = document.getElementById("frame");
const slider = document.getElementById("slider");
const strip = document.getElementById("strip");
const inputs = ["d", "alpha", "w", "beta"].map((id) => document.getElementById(id));
const ANGLES = new Set([1, 3]);  // alpha and beta are typed in degrees, stored in radians
const COLOURS = { key: "#00a000", interpolated: "#8fd88f", none: "#d04040", null: "#999" };

let sequence = null;
let frames = [];
let current = 0;
let base = "";
let dirty = false;
let shown = null;
let drag = null;
let pending = 1;
let ticket = 0;
const undoSteps = [];
const drawings = new Map();

function busy(delta) {
  pending += delta;
  root.dataset.pending = String(pending);
}

function tracked(action) {
  // The page is busy (data-pending > 0) from an action's start to its last redraw.
  return async (...args) => {
    busy(1);
    try {
      await action(...args);
    } finally {
      busy(-1);
    }
  };
}

async function call(path, body) {
  busy(1);
  try {
    const options = body === undefined ? {} : {
      method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
    };
    const response = await fetch(path, options);
    const data = await response.json();
    if (!response.ok) throw new Error(data.error || response.statusText);
    return data;
  } finally {
    busy(-1);
  }
}

function message(text) {
  document.getElementById("message").textContent = text;
}

function draftKey() {
  return "trackbench-label:" + sequence.output;
}

function persist() {
  try {
    localStorage.setItem(draftKey(), JSON.stringify({ base, frames, current, dirty }));
  } catch (error) {
    message("cannot keep a draft in this browser: " + error.message);
  }
}

function restoreDraft() {
  const text = localStorage.getItem(draftKey());
  if (!text) return false;
  const draft = JSON.parse(text);
  if (draft.base !== sequence.revision || draft.frames.length !== sequence.images.length) {
    localStorage.removeItem(draftKey());
    message("the file changed since the last draft; the draft was dropped");
    return false;
  }
  ({ frames, current, dirty } = draft);
  return true;
}

async function drawingOf(state) {
  const key = JSON.stringify(state);
  if (!drawings.has(key)) drawings.set(key, await call("api/borders-of", { state }));
  return drawings.get(key);
}

function suggestion(index) {
  for (const step of [-1, 1]) {
    for (let i = index + step; i >= 0 && i < frames.length; i += step) {
      if (frames[i].s) return frames[i].s;
    }
  }
  return [0, 0, sequence.width / 4, 0];
}

function setLine(name, segment) {
  const line = document.getElementById("line-" + name);
  [["x1", 0, 0], ["y1", 0, 1], ["x2", 1, 0], ["y2", 1, 1]].forEach(([attribute, end, axis]) => {
    line.setAttribute(attribute, segment[end][axis]);
  });
  view.querySelectorAll(`.handle[data-border="${name}"]`).forEach((handle) => {
    const point = segment[Number(handle.dataset.end)];
    handle.setAttribute("cx", point[0]);
    handle.setAttribute("cy", point[1]);
  });
}

function showDrawing(drawing, style) {
  const borders = document.getElementById("borders");
  borders.classList.remove("hidden");
  borders.classList.toggle("suggestion-handles", style === "suggestion");
  borders.querySelectorAll(".border").forEach((line) => {
    line.setAttribute("class", "border " + style);
  });
  setLine("left", drawing.left);
  setLine("right", drawing.right);
  drawing.state.forEach((value, i) => {
    inputs[i].value = (ANGLES.has(i) ? value * 180 / Math.PI : value).toFixed(3);
  });
}

function drawStrip() {
  const context = strip.getContext("2d");
  strip.width = frames.length;
  frames.forEach((record, i) => {
    context.fillStyle = i === current ? "#000" : COLOURS[record.k];
    context.fillRect(i, 0, 1, strip.height);
  });
}

async function render() {
  const record = frames[current];
  const names = { key: "key frame", interpolated: "interpolated", none: "no cable visible", null: "unlabelled" };
  slider.value = current;
  document.getElementById("position").textContent =
    `frame ${current + 1} / ${frames.length}: ${sequence.images[current]}`;
  document.getElementById("kind").textContent = names[record.k];
  const saved = document.getElementById("saved");
  saved.textContent = dirty ? "unsaved changes" : "saved";
  saved.classList.toggle("dirty", dirty);
  image.setAttribute("href", `frames/${current}`);
  if (current + 1 < frames.length) new Image().src = `frames/${current + 1}`;
  drawStrip();
  document.getElementById("no-cable").classList.toggle("hidden", record.k !== "none");
  const mine = ++ticket;
  if (record.k === "none") {
    shown = null;
    document.getElementById("borders").classList.add("hidden");
    inputs.forEach((input) => { input.value = ""; });
    return;
  }
  const style = { key: "", interpolated: "interpolated", null: "suggestion" }[record.k];
  try {
    const drawing = await drawingOf(record.s || suggestion(current));
    if (mine !== ticket) return;
    shown = drawing;
    showDrawing(drawing, style);
  } catch (error) {
    message("cannot draw this state: " + error.message);
  }
}

function change(edits, target = current) {
  undoSteps.push({ before: edits.map(([i]) => [i, frames[i]]), current });
  if (undoSteps.length > 500) undoSteps.shift();
  edits.forEach(([i, record]) => { frames[i] = record; });
  current = target;
  dirty = true;
  persist();
  return render();
}

function undo() {
  const step = undoSteps.pop();
  if (!step) return message("nothing to undo");
  step.before.forEach(([i, record]) => { frames[i] = record; });
  current = step.current;
  dirty = true;
  persist();
  return render();
}

function go(index) {
  current = Math.max(0, Math.min(frames.length - 1, index));
  persist();
  return render();
}

function copyToNext() {
  const record = frames[current];
  if (current + 1 >= frames.length) return message("this is the last frame");
  if (record.k === null) return message("nothing to copy: this frame is unlabelled");
  return change([[current + 1, { s: record.s, k: record.k === "none" ? "none" : "key" }]], current + 1);
}

function keep() {
  if (!shown) return message("no lines to keep");
  return change([[current, { s: shown.state, k: "key" }]]);
}

// Linear in d, alpha, w and beta between consecutive key frames; a "no cable" frame breaks the pair.
// alpha comes from the server in (-90, 90] deg, so a cable turning through the horizontal needs its own key frames.
function interpolate() {
  const edits = [];
  let last = null;
  frames.forEach((record, i) => {
    if (record.k === "none") last = null;
    if (record.k !== "key") return;
    if (last !== null) {
      const from = frames[last].s;
      for (let j = last + 1; j < i; j++) {
        const t = (j - last) / (i - last);
        edits.push([j, { s: from.map((value, q) => value + t * (record.s[q] - value)), k: "interpolated" }]);
      }
    }
    last = i;
  });
  if (!edits.length) return message("no frames between two key frames to interpolate");
  message(`interpolated ${edits.length} frames`);
  return change(edits);
}

function nextUnlabelled() {
  const order = [...frames.keys()].map((i) => (current + 1 + i) % frames.length);
  const found = order.find((i) => frames[i].k === null);
  if (found === undefined) return message("every frame is labelled");
  return go(found);
}

function toggleNone() {
  const none = frames[current].k === "none";
  return change([[current, { s: null, k: none ? null : "none" }]]);
}

async function save() {
  const states = frames.map((record) => (record.k === "none" ? null : record.s));
  try {
    const result = await call("api/save", { states });
    base = result.revision;
    dirty = false;
    persist();
    message("saved " + result.output);
    await render();
  } catch (error) {
    message("not saved: " + error.message);
  }
}

async function typed() {
  const values = inputs.map((input, i) => Number(input.value) * (ANGLES.has(i) ? Math.PI / 180 : 1));
  if (values.some((value) => !Number.isFinite(value)) || inputs.some((input) => input.value === "")) {
    return message("d, alpha, w and beta must all be numbers");
  }
  try {
    const drawing = await drawingOf(values);
    await change([[current, { s: drawing.state, k: "key" }]]);
  } catch (error) {
    message("cannot use these values: " + error.message);
  }
}

function imagePoint(event) {
  const point = new DOMPoint(event.clientX, event.clientY).matrixTransform(view.getScreenCTM().inverse());
  return [point.x, point.y];
}

function draggedSegments(event) {
  const segments = { left: shown.left.map((p) => [...p]), right: shown.right.map((p) => [...p]) };
  segments[drag.border][drag.end] = imagePoint(event);
  return segments;
}

view.addEventListener("pointerdown", (event) => {
  const handle = event.target.closest(".handle");
  if (!handle || !shown) return;
  drag = { border: handle.dataset.border, end: Number(handle.dataset.end) };
  view.setPointerCapture(event.pointerId);
  event.preventDefault();
});

view.addEventListener("pointermove", (event) => {
  if (!drag) return;
  setLine(drag.border, draggedSegments(event)[drag.border]);
});

view.addEventListener("pointerup", tracked(async (event) => {
  if (!drag) return;
  const segments = draggedSegments(event);
  drag = null;
  try {
    const drawing = await call("api/state-of", segments);
    drawings.set(JSON.stringify(drawing.state), drawing);
    await change([[current, { s: drawing.state, k: "key" }]]);
  } catch (error) {
    message("cannot use these borders: " + error.message);
    await render();
  }
}));

strip.addEventListener("click", tracked((event) => {
  const box = strip.getBoundingClientRect();
  return go(Math.floor((event.clientX - box.left) / box.width * frames.length));
}));

slider.addEventListener("input", tracked(() => go(Number(slider.value))));
inputs.forEach((input) => input.addEventListener("change", tracked(typed)));

const ACTIONS = {
  ArrowRight: (event) => go(current + (event.shiftKey ? 10 : 1)),
  ArrowLeft: (event) => go(current - (event.shiftKey ? 10 : 1)),
  Home: () => go(0),
  End: () => go(frames.length - 1),
  c: copyToNext,
  k: keep,
  i: interpolate,
  n: nextUnlabelled,
  x: toggleNone,
  z: undo,
  s: save,
};

const BUTTONS = {
  previous: () => go(current - 1), next: () => go(current + 1), copy: copyToNext, keep, interpolate,
  unlabelled: nextUnlabelled, none: toggleNone, undo, save,
};
Object.entries(BUTTONS).forEach(([id, action]) => document.getElementById(id).addEventListener("click", tracked(action)));

document.addEventListener("keydown", (event) => {
  if (event.target.type === "number") {
    // Enter or Escape leaves a spin box (Enter applies its value), so that the shortcuts work again.
    if (event.key === "Enter" || event.key === "Escape") event.target.blur();
    return;
  }
  if (event.altKey) return;
  const key = event.key.length === 1 ? event.key.toLowerCase() : event.key;
  if ((event.ctrlKey || event.metaKey) && key !== "z" && key !== "s") return;
  const action = ACTIONS[key];
  if (!action) return;
  event.preventDefault();
  tracked(action)(event);
});

function layout() {
  const { width, height } = sequence;
  const margin = 0.1 * Math.max(width, height);
  const room = Math.max(200, window.innerWidth - 420);
  const scale = Math.min(room / (width + 2 * margin), (0.75 * window.innerHeight) / (height + 2 * margin));
  view.setAttribute("viewBox", `${-0.5 - margin} ${-0.5 - margin} ${width + 2 * margin} ${height + 2 * margin}`);
  view.setAttribute("width", (width + 2 * margin) * scale);
  view.setAttribute("height", (height + 2 * margin) * scale);
  Object.entries({ x: -0.5, y: -0.5, width, height }).forEach(([name, value]) => image.setAttribute(name, value));
  view.querySelectorAll(".handle").forEach((handle) => handle.setAttribute("r", 6 / scale));
  view.querySelectorAll(".border").forEach((line) => line.setAttribute("stroke-width", 2 / scale));
  const text = document.getElementById("no-cable");
  text.setAttribute("x", 0);
  text.setAttribute("y", 14 / scale);
  text.setAttribute("font-size", 14 / scale);
}

async function start() {
  try {
    sequence = await call("api/sequence");
  } catch (error) {
    message("cannot load the sequence: " + error.message);
    return;
  }
  document.getElementById("name").textContent = sequence.name;
  document.title = "trackbench label: " + sequence.name;
  base = sequence.revision;
  if (!restoreDraft()) frames = sequence.states.map((state) => ({ s: state, k: state ? "key" : null }));
  slider.max = frames.length - 1;
  layout();
  window.addEventListener("resize", layout);
  await render();
  busy(-1);
}

start();
