// motionwire report: zoom, pan and details on the shared view
// (docs/report.md#script). The page reads in full without it: the SVG is
// drawn by the program, every mark and band has its title.
(function () {
  "use strict";
  var root = document.documentElement;
  root.classList.add("scripted");
  var body = document.body;
  var timedBody = body.getAttribute("data-axis") === "time";
  var startBody = Number(body.getAttribute("data-start"));
  var spanBody = Number(body.getAttribute("data-span")) || 1;
  var svgs = Array.prototype.slice.call(document.querySelectorAll("svg.tl"));
  var LEFT = 170, PLOT = 1000;
  if (svgs.length) {
    LEFT = Number(svgs[0].getAttribute("data-left"));
    PLOT = Number(svgs[0].getAttribute("data-plot"));
  }
  var NS = "http://www.w3.org/2000/svg";
  var v0 = 0, v1 = PLOT;
  var rects = [], uses = [], labels = [], paths = [];
  svgs.forEach(function (svg) {
    svg.querySelectorAll("g.plot rect").forEach(function (el) {
      rects.push({ el: el, x: +el.getAttribute("x"), w: +el.getAttribute("width"),
        min: el.hasAttribute("data-state") ? 0.5 : 2 });
    });
    svg.querySelectorAll("g.plot use").forEach(function (el) {
      uses.push({ el: el, x: +el.getAttribute("x") });
    });
    svg.querySelectorAll("g.plot text.bl").forEach(function (el) {
      labels.push({ el: el, band: el.previousElementSibling });
    });
    svg.querySelectorAll("g.plot path").forEach(function (el) { paths.push(el); });
  });

  function map(x) { return LEFT + (x - LEFT - v0) * PLOT / (v1 - v0); }

  function nice(raw) {
    var pow = Math.pow(10, Math.floor(Math.log10(raw)));
    var u = raw / pow;
    return (u < 1.5 ? 1 : u < 3.5 ? 2 : u < 7.5 ? 5 : 10) * pow;
  }

  // Each timeline and chart has its own axis (several logs read apart:
  // one per recording, docs/report.md#several); the view, a part of the
  // plot, is shared.
  function axes() {
    svgs.forEach(function (svg) {
      var g = svg.querySelector("g.axis");
      if (!g) { return; }
      var timed = svg.hasAttribute("data-axis") ? svg.getAttribute("data-axis") === "time" : timedBody;
      var start = svg.hasAttribute("data-start") ? Number(svg.getAttribute("data-start")) : startBody;
      var span = Number(svg.getAttribute("data-span")) || spanBody;
      var units = timed ? span / 1e6 : span;
      var a = v0 / PLOT * units, b = v1 / PLOT * units;
      var step = nice(Math.max((b - a) / 8, timed ? 1e-6 : 1));
      var decimals = step >= 1 ? 0 : Math.min(6, Math.ceil(-Math.log10(step)));
      var height = svg.viewBox.baseVal.height;
      g.querySelectorAll("line.grid, text.tick").forEach(function (el) { el.remove(); });
      for (var v = Math.ceil(a / step) * step; v <= b + step * 1e-9; v += step) {
        var x = LEFT + (v - a) / (b - a) * PLOT;
        var line = document.createElementNS(NS, "line");
        line.setAttribute("class", "grid");
        line.setAttribute("x1", x.toFixed(2));
        line.setAttribute("x2", x.toFixed(2));
        line.setAttribute("y1", "22");
        line.setAttribute("y2", String(height));
        var text = document.createElementNS(NS, "text");
        text.setAttribute("class", "tick");
        text.setAttribute("x", x.toFixed(2));
        text.setAttribute("y", "16");
        text.textContent = timed ? v.toFixed(decimals) : String(Math.round(start + v));
        g.appendChild(line);
        g.appendChild(text);
      }
    });
  }

  var pending = false;
  function render() {
    pending = false;
    var k = PLOT / (v1 - v0);
    rects.forEach(function (r) {
      r.el.setAttribute("x", map(r.x).toFixed(2));
      r.el.setAttribute("width", Math.max(r.w * k, r.min).toFixed(2));
    });
    uses.forEach(function (u) { u.el.setAttribute("x", map(u.x).toFixed(2)); });
    labels.forEach(function (l) {
      var band = l.band;
      l.el.setAttribute("x", (+band.getAttribute("x") + 3).toFixed(2));
      l.el.style.display = +band.getAttribute("width") < 70 ? "none" : "";
    });
    var tx = LEFT - (LEFT + v0) * k;
    paths.forEach(function (p) {
      p.setAttribute("transform", "translate(" + tx.toFixed(3) + ",0) scale(" + k.toFixed(6) + ",1)");
    });
    axes();
  }
  function later() {
    if (!pending) { pending = true; window.requestAnimationFrame(render); }
  }

  function clamp() {
    var w = Math.min(Math.max(v1 - v0, PLOT / 2000), PLOT);
    if (v0 < 0) { v0 = 0; }
    if (v0 + w > PLOT) { v0 = PLOT - w; }
    v1 = v0 + w;
  }
  function zoom(factor, at) {
    var c = at === undefined ? (v0 + v1) / 2 : at;
    var f = (c - v0) / (v1 - v0);
    var w = (v1 - v0) / factor;
    v0 = c - f * w;
    v1 = v0 + w;
    clamp();
    later();
  }
  // Where a pointer event is, in default plot units.
  function plotAt(svg, ev) {
    var box = svg.getBoundingClientRect();
    var x = (ev.clientX - box.left) * svg.viewBox.baseVal.width / box.width;
    return v0 + (x - LEFT) / PLOT * (v1 - v0);
  }

  var drag = null;
  svgs.forEach(function (svg) {
    svg.addEventListener("wheel", function (ev) {
      if (!ev.ctrlKey && !ev.metaKey) { return; }
      ev.preventDefault();
      zoom(ev.deltaY < 0 ? 1.25 : 0.8, plotAt(svg, ev));
    }, { passive: false });
    svg.addEventListener("dblclick", function (ev) { zoom(2, plotAt(svg, ev)); });
    svg.addEventListener("pointerdown", function (ev) {
      drag = { svg: svg, x: ev.clientX, v0: v0, moved: false };
    });
  });
  window.addEventListener("pointermove", function (ev) {
    if (!drag) { return; }
    var box = drag.svg.getBoundingClientRect();
    var dx = (ev.clientX - drag.x) * drag.svg.viewBox.baseVal.width / box.width;
    if (Math.abs(dx) > 2) { drag.moved = true; }
    var w = v1 - v0;
    v0 = drag.v0 - dx / PLOT * w;
    v1 = v0 + w;
    clamp();
    later();
  });
  window.addEventListener("pointerup", function () {
    if (drag && drag.moved) { drag.svg.dataset.dragged = "1"; }
    drag = null;
  });

  document.querySelectorAll("button[data-zoom]").forEach(function (b) {
    b.addEventListener("click", function () {
      var how = b.getAttribute("data-zoom");
      if (how === "in") { zoom(2); }
      else if (how === "out") { zoom(0.5); }
      else { v0 = 0; v1 = PLOT; later(); }
    });
  });

  // Details: a click on a mark or band says what it is, and marks its
  // events in the table.
  var details = document.getElementById("details");
  var selected = null;
  function select(el) {
    if (selected) { selected.classList.remove("selected"); }
    selected = el;
    el.classList.add("selected");
    var title = el.querySelector("title");
    var what = [];
    ["data-kind", "data-state", "data-line", "data-count"].forEach(function (a) {
      if (el.hasAttribute(a)) { what.push(a.slice(5) + " " + el.getAttribute(a)); }
    });
    if (details) { details.textContent = (title ? title.textContent + " — " : "") + what.join(", "); }
    var line = el.getAttribute("data-line");
    document.querySelectorAll("table.events tr.hit").forEach(function (tr) { tr.classList.remove("hit"); });
    document.querySelectorAll("table.events tr[data-line=\"" + line + "\"]").forEach(function (tr) { tr.classList.add("hit"); });
  }
  svgs.forEach(function (svg) {
    svg.addEventListener("click", function (ev) {
      if (svg.dataset.dragged) { delete svg.dataset.dragged; return; }
      var el = ev.target.closest("[data-kind]");
      if (el && el.hasAttribute("data-line")) { select(el); }
    });
  });

  // A finding or an event row: the view goes to its mark.
  function show(item) {
    var line = item.getAttribute("data-line");
    var node = item.getAttribute("data-node");
    // Logs read apart: the row of the finding's own file.
    var file = item.hasAttribute("data-file")
      ? "[data-file=\"" + CSS.escape(item.getAttribute("data-file")) + "\"]" : "";
    var iface = "[data-iface=\"" + CSS.escape(item.getAttribute("data-iface") || "") + "\"]";
    var slave = item.getAttribute("data-slave");
    var stream = item.getAttribute("data-stream");
    var row = slave !== null
      ? document.querySelector("g[data-row=\"slave\"]" + iface + "[data-slave=\"" + slave + "\"]" + file)
      : stream !== null
      ? document.querySelector("g[data-row=\"stream\"]" + iface + "[data-stream=\"" + CSS.escape(stream) + "\"]" + file)
      : node === null
      ? document.querySelector("g[data-row=\"bus\"]" + iface + file)
      : document.querySelector("g[data-row=\"node\"]" + iface + "[data-node=\"" + node + "\"]" + file);
    var scope = row || document;
    var el = scope.querySelector("[data-kind][data-line=\"" + line + "\"]:not([data-state])") ||
      scope.querySelector("[data-line=\"" + line + "\"]");
    if (!el) { return; }
    var i = rects.concat(uses).filter(function (r) { return r.el === el; })[0];
    if (i) {
      var w = Math.max((v1 - v0) / 4, PLOT / 50);
      w = Math.min(w, PLOT / 10);
      v0 = i.x - LEFT - w / 2;
      v1 = v0 + w;
      clamp();
      render();
    }
    select(el);
    var tl = document.getElementById("timeline");
    if (tl) { tl.scrollIntoView({ block: "start" }); }
  }
  document.querySelectorAll("ul.findings li[data-line], table.events tr[data-line]").forEach(function (item) {
    item.addEventListener("click", function () { show(item); });
    item.style.cursor = "pointer";
  });

  render();
  root.setAttribute("data-script", "ready");
})();
