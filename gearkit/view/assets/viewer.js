/* gearkit viewer: the 2D mesh animated, a transmission error trace, a 3D view of the solids
 * (WebGL, orbit controls; a canvas fallback), a map panel (blocking contours) and the findings.
 * Self-contained: no library, no network. The page inlines this file and a JSON object
 * (window.GEARKIT_DATA) written by gearkit.view. */
(function () {
  "use strict";
  var D = window.GEARKIT_DATA;
  var state = { frame: 0, playing: true, speed: 1, last: 0, acc: 0 };
  var nFrames = D.anim ? D.anim.frames : 1;

  function $(id) { return document.getElementById(id); }
  function el(tag, cls, text) {
    var e = document.createElement(tag);
    if (cls) e.className = cls;
    if (text !== undefined) e.textContent = text;
    return e;
  }
  function b64(s, Type) {
    var bin = atob(s), n = bin.length, buf = new ArrayBuffer(n), u8 = new Uint8Array(buf);
    for (var i = 0; i < n; i++) u8[i] = bin.charCodeAt(i);
    return new Type(buf);
  }
  function fitCanvas(c) {
    var r = c.getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
    var w = Math.max(1, Math.round(r.width * dpr)), h = Math.max(1, Math.round(r.height * dpr));
    if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
    return dpr;
  }

  /* ---------------- text panels ---------------- */
  function tables() {
    $("title").textContent = D.title;
    $("subtitle").textContent = D.subtitle || "";
    var sum = $("summary");
    (D.summary || []).forEach(function (row) {
      var tr = el("tr");
      tr.appendChild(el("th", null, row[0]));
      tr.appendChild(el("td", null, row[1]));
      sum.appendChild(tr);
    });
    var f = $("findings"), worst = "ok";
    (D.findings || []).forEach(function (x) {
      var tr = el("tr", "st-" + x.status);
      tr.appendChild(el("td", "status", x.status));
      tr.appendChild(el("td", "fid", x.id));
      tr.appendChild(el("td", null, x.message));
      f.appendChild(tr);
      if (x.status === "fail" || (x.status === "warn" && worst === "ok")) worst = x.status;
    });
    var v = $("verdict");
    v.textContent = worst === "ok" ? "all checks pass" : worst === "warn" ? "passes with warnings" : "a check FAILS";
    v.className = "verdict st-" + worst;
  }

  /* ---------------- 2D mesh ---------------- */
  var view2 = null;
  function bounds2() {
    if (D.anim.bounds) return D.anim.bounds.slice();
    var lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
    D.anim.bodies.forEach(function (b) {
      var p = b.poses[0];
      b.loops.forEach(function (L) {
        var c = Math.cos(p[0]), s = Math.sin(p[0]);
        for (var i = 0; i < L.length; i += 2) {
          var x = c * L[i] - s * L[i + 1] + p[1], y = s * L[i] + c * L[i + 1] + p[2];
          lo[0] = Math.min(lo[0], x); lo[1] = Math.min(lo[1], y);
          hi[0] = Math.max(hi[0], x); hi[1] = Math.max(hi[1], y);
        }
      });
    });
    return [lo[0], lo[1], hi[0], hi[1]];
  }
  function setup2d() {
    var c = $("mesh2d"), b = bounds2();
    view2 = { cx: (b[0] + b[2]) / 2, cy: (b[1] + b[3]) / 2, span: Math.max(b[2] - b[0], b[3] - b[1]) * 1.08, home: null };
    view2.home = { cx: view2.cx, cy: view2.cy, span: view2.span };
    var drag = null;
    c.addEventListener("wheel", function (e) {
      e.preventDefault();
      view2.span *= Math.exp(0.0015 * e.deltaY);
    }, { passive: false });
    c.addEventListener("mousedown", function (e) { drag = [e.clientX, e.clientY]; });
    window.addEventListener("mouseup", function () { drag = null; });
    window.addEventListener("mousemove", function (e) {
      if (!drag) return;
      var r = c.getBoundingClientRect(), k = view2.span / Math.min(r.width, r.height);
      view2.cx -= (e.clientX - drag[0]) * k; view2.cy += (e.clientY - drag[1]) * k;
      drag = [e.clientX, e.clientY];
    });
    c.addEventListener("dblclick", function () {
      var f = D.anim.focus;
      if (f && Math.abs(view2.span - view2.home.span) < 1e-9) { view2.cx = f[0]; view2.cy = f[1]; view2.span = f[2]; }
      else { view2.cx = view2.home.cx; view2.cy = view2.home.cy; view2.span = view2.home.span; }
    });
  }
  function draw2d() {
    var c = $("mesh2d"), dpr = fitCanvas(c), g = c.getContext("2d");
    var W = c.width, H = c.height, k = Math.min(W, H) / view2.span;
    g.setTransform(1, 0, 0, 1, 0, 0);
    g.fillStyle = "#fbfbfd"; g.fillRect(0, 0, W, H);
    g.setTransform(k, 0, 0, -k, W / 2 - k * view2.cx, H / 2 + k * view2.cy);
    var px = 1 / k, f = state.frame, A = D.anim;
    A.bodies.forEach(function (b) {
      var p = b.poses[Math.min(f, b.poses.length - 1)];
      g.save();
      g.translate(p[1], p[2]); g.rotate(p[0]);
      g.beginPath();
      b.loops.forEach(function (L) {
        g.moveTo(L[0], L[1]);
        for (var i = 2; i < L.length; i += 2) g.lineTo(L[i], L[i + 1]);
        g.closePath();
      });
      g.fillStyle = b.fill || "rgba(120,140,170,0.35)"; g.fill("evenodd");
      g.lineWidth = 1.2 * dpr * px; g.strokeStyle = b.color || "#234"; g.stroke();
      if (b.mark) {  // a radial line that shows the body turning
        g.beginPath(); g.moveTo(0, 0); g.lineTo(b.mark[0], b.mark[1]);
        g.lineWidth = 1.5 * dpr * px; g.strokeStyle = b.color || "#234"; g.stroke();
        g.beginPath(); g.arc(0, 0, 3 * dpr * px, 0, 2 * Math.PI); g.fillStyle = b.color || "#234"; g.fill();
      }
      g.restore();
    });
    if (A.path && A.path.length) {
      g.beginPath();
      for (var i = 0; i < A.path.length; i += 2) {
        g.moveTo(A.path[i] + 1.6 * dpr * px, A.path[i + 1]);
        g.arc(A.path[i], A.path[i + 1], 1.6 * dpr * px, 0, 2 * Math.PI);
      }
      g.fillStyle = "rgba(40,120,60,0.55)"; g.fill();
    }
    var pts = (A.contacts && A.contacts.length) ? A.contacts[f % A.contacts.length] : [];
    g.beginPath();
    for (var j = 0; j < pts.length; j += 2) {
      g.moveTo(pts[j] + 5 * dpr * px, pts[j + 1]);
      g.arc(pts[j], pts[j + 1], 5 * dpr * px, 0, 2 * Math.PI);
    }
    g.fillStyle = "#d2232a"; g.fill();
    g.setTransform(1, 0, 0, 1, 0, 0);
    g.fillStyle = "#333"; g.font = (12 * dpr) + "px sans-serif";
    g.fillText((A.caption || "") + "  frame " + (f + 1) + "/" + nFrames + (pts.length ? ", " + pts.length / 2 + " in contact" : ""),
      8 * dpr, H - 8 * dpr);
  }

  /* ---------------- trace ---------------- */
  function drawTrace() {
    var T = D.anim.trace, c = $("trace");
    if (!T) { c.style.display = "none"; return; }
    var dpr = fitCanvas(c), g = c.getContext("2d"), W = c.width, H = c.height;
    var m = { l: 62 * dpr, r: 12 * dpr, t: 22 * dpr, b: 30 * dpr };
    g.font = (11 * dpr) + "px sans-serif";
    g.setTransform(1, 0, 0, 1, 0, 0);
    g.fillStyle = "#fff"; g.fillRect(0, 0, W, H);
    var x0 = T.x[0], x1 = T.x[T.x.length - 1];
    var y0 = Math.min.apply(null, T.y), y1 = Math.max.apply(null, T.y);
    if (y1 - y0 < 1e-12) { y0 -= 1; y1 += 1; }
    var pad = 0.08 * (y1 - y0); y0 -= pad; y1 += pad;
    function X(v) { return m.l + (v - x0) / (x1 - x0) * (W - m.l - m.r); }
    function Y(v) { return H - m.b - (v - y0) / (y1 - y0) * (H - m.t - m.b); }
    g.strokeStyle = "#bbb"; g.lineWidth = dpr; g.strokeRect(m.l, m.t, W - m.l - m.r, H - m.t - m.b);
    g.fillStyle = "#333"; g.font = (11 * dpr) + "px sans-serif";
    for (var q = 0; q <= 4; q++) {
      var v = y0 + (y1 - y0) * q / 4;
      g.fillText(v.toPrecision(3), 4 * dpr, Y(v) + 4 * dpr);
    }
    g.fillText(T.label, m.l, 15 * dpr);
    g.fillText(T.xlabel || "", W - m.r - g.measureText(T.xlabel || "").width, H - 8 * dpr);
    g.beginPath();
    for (var i = 0; i < T.x.length; i++) { if (i) g.lineTo(X(T.x[i]), Y(T.y[i])); else g.moveTo(X(T.x[i]), Y(T.y[i])); }
    g.strokeStyle = "#1f5fa8"; g.lineWidth = 1.5 * dpr; g.stroke();
    if (T.y2) {  // a second series (pairs in contact) as a step line on its own axis, right
      var lo2 = Math.min.apply(null, T.y2) - 0.5, hi2 = Math.max.apply(null, T.y2) + 0.5;
      var Y2 = function (v) { return H - m.b - (v - lo2) / (hi2 - lo2) * (H - m.t - m.b); };
      g.beginPath();
      for (var j = 0; j < T.x.length; j++) {
        if (j) g.lineTo(X(T.x[j]), Y2(T.y2[j - 1]));
        g.lineTo(X(T.x[j]), Y2(T.y2[j]));
        if (!j) g.moveTo(X(T.x[j]), Y2(T.y2[j]));
      }
      g.strokeStyle = "rgba(40,120,60,0.8)"; g.lineWidth = dpr; g.stroke();
      g.fillStyle = "rgb(40,120,60)";
      var lab = T.label2 + ": " + T.y2[state.frame % T.x.length];
      g.fillText(lab, W - m.r - g.measureText(lab).width, 15 * dpr);
    }
    var idx = state.frame % T.x.length;
    g.beginPath(); g.moveTo(X(T.x[idx]), m.t); g.lineTo(X(T.x[idx]), H - m.b);
    g.strokeStyle = "#d2232a"; g.lineWidth = dpr; g.stroke();
    g.beginPath(); g.arc(X(T.x[idx]), Y(T.y[idx]), 4 * dpr, 0, 2 * Math.PI); g.fillStyle = "#d2232a"; g.fill();
  }

  /* ---------------- map (blocking contour) ---------------- */
  function drawMap() {
    var M = D.map, c = $("map");
    if (!M) return;
    var dpr = fitCanvas(c), g = c.getContext("2d"), W = c.width, H = c.height;
    var m = { l: 46 * dpr, r: 10 * dpr, t: 10 * dpr, b: 34 * dpr }, w = M.window;
    var sx = (W - m.l - m.r) / (w[1] - w[0]), sy = (H - m.t - m.b) / (w[3] - w[2]);
    function X(v) { return m.l + (v - w[0]) * sx; }
    function Y(v) { return H - m.b - (v - w[2]) * sy; }
    g.fillStyle = "#fff"; g.fillRect(0, 0, W, H);
    M.region.forEach(function (P) {
      g.beginPath();
      for (var i = 0; i < P.length; i += 2) { if (i) g.lineTo(X(P[i]), Y(P[i + 1])); else g.moveTo(X(P[i]), Y(P[i + 1])); }
      g.closePath(); g.fillStyle = "rgba(90,170,110,0.25)"; g.fill();
    });
    M.lines.forEach(function (ln) {
      g.beginPath();
      ln.parts.forEach(function (P) {
        for (var i = 0; i < P.length; i += 2) { if (i) g.lineTo(X(P[i]), Y(P[i + 1])); else g.moveTo(X(P[i]), Y(P[i + 1])); }
      });
      g.strokeStyle = ln.color; g.lineWidth = (ln.dashed ? 1 : 1.8) * dpr;
      g.setLineDash(ln.dashed ? [5 * dpr, 4 * dpr] : []); g.stroke();
    });
    g.setLineDash([]);
    g.strokeStyle = "#999"; g.lineWidth = dpr; g.strokeRect(m.l, m.t, W - m.l - m.r, H - m.t - m.b);
    g.fillStyle = "#333"; g.font = (11 * dpr) + "px sans-serif";
    for (var q = 0; q <= 4; q++) {
      var vx = w[0] + (w[1] - w[0]) * q / 4, vy = w[2] + (w[3] - w[2]) * q / 4;
      /* centred on its tick, kept right of the x2 labels and on the canvas */
      var tx = vx.toFixed(2), tw = g.measureText(tx).width;
      g.fillText(tx, Math.min(Math.max(X(vx) - tw / 2, m.l - 8 * dpr), W - tw), H - m.b + 14 * dpr);
      g.fillText(vy.toFixed(2), 4 * dpr, Y(vy) + 4 * dpr);
    }
    g.fillText("x1", W - m.r - 16 * dpr, H - 6 * dpr); g.fillText("x2", m.l + 5 * dpr, m.t + 13 * dpr);
    (M.points || []).forEach(function (p) {
      g.beginPath(); g.arc(X(p.x1), Y(p.x2), 5 * dpr, 0, 2 * Math.PI);
      g.fillStyle = p.color; g.fill(); g.fillStyle = "#111";
      g.fillText(p.label, X(p.x1) + 7 * dpr, Y(p.x2) - 6 * dpr);
    });
    var leg = $("legend");
    if (!leg.childNodes.length) M.lines.forEach(function (ln) {
      var s = el("span", "key"); s.style.borderColor = ln.color; s.textContent = ln.code + " " + ln.name; leg.appendChild(s);
    });
  }

  /* ---------------- 3D ---------------- */
  var cam = { yaw: -0.6, pitch: 0.9, dist: 1, target: [0, 0, 0], radius: 1 };
  var gl3 = null;
  function mat4mul(a, b) {
    var o = new Float32Array(16);
    for (var i = 0; i < 4; i++) for (var j = 0; j < 4; j++) {
      var s = 0;
      for (var k = 0; k < 4; k++) s += a[k * 4 + j] * b[i * 4 + k];
      o[i * 4 + j] = s;
    }
    return o;
  }
  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function unit(a) { var l = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / l, a[1] / l, a[2] / l]; }
  function basis() {  // camera axes: side, up, forward (z up, pitch from +z)
    var sp = Math.sin(cam.pitch), cp = Math.cos(cam.pitch), t = cam.target;
    var eye = [t[0] + cam.dist * sp * Math.sin(cam.yaw), t[1] - cam.dist * sp * Math.cos(cam.yaw), t[2] + cam.dist * cp];
    var f = unit(sub(t, eye)), s = unit(cross(f, [0, 0, 1])), u = cross(s, f);
    return { eye: eye, f: f, s: s, u: u };
  }
  function viewMatrix() {
    var b = basis(), s = b.s, u = b.u, f = b.f, e = b.eye;
    return new Float32Array([s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0,
      -dot(s, e), -dot(u, e), dot(f, e), 1]);
  }
  function projMatrix(aspect) {
    var f = 1 / Math.tan(0.35), n = cam.dist * 0.05 + 1e-3, fa = cam.dist + 4 * cam.radius;
    return new Float32Array([f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (fa + n) / (n - fa), -1, 0, 0, 2 * fa * n / (n - fa), 0]);
  }
  function poseMatrix(part) {
    if (part.body === undefined || !D.anim) return new Float32Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
    var b = D.anim.bodies[part.body], p = b.poses[Math.min(state.frame, b.poses.length - 1)];
    var c = Math.cos(p[0]), s = Math.sin(p[0]);
    return new Float32Array([c, s, 0, 0, -s, c, 0, 0, 0, 0, 1, 0, p[1], p[2], 0, 1]);
  }
  function setup3d() {
    var parts = D.parts3d || [], lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    parts.forEach(function (p) {
      var v = b64(p.positions, Float32Array), f = b64(p.indices, Uint32Array), M = poseMatrix(p);
      var pos = new Float32Array(f.length * 3), nor = new Float32Array(f.length * 3);
      for (var t = 0; t < f.length; t += 3) {
        var a = f[t] * 3, b = f[t + 1] * 3, c = f[t + 2] * 3;
        var ux = v[b] - v[a], uy = v[b + 1] - v[a + 1], uz = v[b + 2] - v[a + 2];
        var wx = v[c] - v[a], wy = v[c + 1] - v[a + 1], wz = v[c + 2] - v[a + 2];
        var nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx, l = Math.hypot(nx, ny, nz) || 1;
        for (var k = 0; k < 3; k++) {
          var i = f[t + k] * 3, o = (t + k) * 3;
          pos[o] = v[i]; pos[o + 1] = v[i + 1]; pos[o + 2] = v[i + 2];
          nor[o] = nx / l; nor[o + 1] = ny / l; nor[o + 2] = nz / l;
        }
      }
      for (var q = 0; q < v.length; q += 3) {
        var x = M[0] * v[q] + M[4] * v[q + 1] + M[12], y = M[1] * v[q] + M[5] * v[q + 1] + M[13], z = v[q + 2];
        lo = [Math.min(lo[0], x), Math.min(lo[1], y), Math.min(lo[2], z)];
        hi = [Math.max(hi[0], x), Math.max(hi[1], y), Math.max(hi[2], z)];
      }
      p.pos = pos; p.nor = nor; p.count = f.length;
    });
    if (!parts.length) return;
    cam.target = [(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2];
    cam.radius = 0.5 * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    cam.dist = cam.radius / Math.sin(0.35) * 0.9;
    var c = $("solid3d"), drag = null, button = 0;
    c.addEventListener("contextmenu", function (e) { e.preventDefault(); });
    c.addEventListener("mousedown", function (e) { drag = [e.clientX, e.clientY]; button = e.shiftKey ? 2 : e.button; });
    window.addEventListener("mouseup", function () { drag = null; });
    window.addEventListener("mousemove", function (e) {
      if (!drag) return;
      var dx = e.clientX - drag[0], dy = e.clientY - drag[1];
      drag = [e.clientX, e.clientY];
      if (button === 2) {
        var k = cam.dist / c.getBoundingClientRect().height, B = basis();
        for (var i = 0; i < 3; i++) cam.target[i] += k * (-dx * B.s[i] + dy * B.u[i]);
      } else {
        cam.yaw -= dx * 0.008;
        cam.pitch = Math.max(0.05, Math.min(Math.PI - 0.05, cam.pitch - dy * 0.008));
      }
    });
    c.addEventListener("wheel", function (e) { e.preventDefault(); cam.dist *= Math.exp(0.0015 * e.deltaY); },
      { passive: false });
    var g = c.getContext("webgl", { antialias: true, preserveDrawingBuffer: true });
    if (!g) { $("glnote").textContent = "WebGL is not available: a simplified drawing is shown."; return; }
    function shader(type, src) {
      var s = g.createShader(type); g.shaderSource(s, src); g.compileShader(s);
      if (!g.getShaderParameter(s, g.COMPILE_STATUS)) throw new Error(g.getShaderInfoLog(s));
      return s;
    }
    var prog = g.createProgram();
    g.attachShader(prog, shader(g.VERTEX_SHADER,
      "attribute vec3 p; attribute vec3 n; uniform mat4 mv; uniform mat4 pr; varying vec3 vn;" +
      "void main(){ vn = (mv * vec4(n, 0.0)).xyz; gl_Position = pr * mv * vec4(p, 1.0); }"));
    g.attachShader(prog, shader(g.FRAGMENT_SHADER,
      "precision mediump float; varying vec3 vn; uniform vec3 col;" +
      "void main(){ vec3 m = normalize(vn); vec3 L = normalize(vec3(0.3, 0.5, 0.8)); float d = abs(dot(m, L));" +
      "float r = pow(max(dot(reflect(-L, m), vec3(0.0, 0.0, 1.0)), 0.0), 24.0);" +
      "gl_FragColor = vec4(col * (0.32 + 0.68 * d) + vec3(0.25) * r, 1.0); }"));
    g.linkProgram(prog);
    if (!g.getProgramParameter(prog, g.LINK_STATUS)) throw new Error(g.getProgramInfoLog(prog));
    parts.forEach(function (p) {
      p.bp = g.createBuffer(); g.bindBuffer(g.ARRAY_BUFFER, p.bp); g.bufferData(g.ARRAY_BUFFER, p.pos, g.STATIC_DRAW);
      p.bn = g.createBuffer(); g.bindBuffer(g.ARRAY_BUFFER, p.bn); g.bufferData(g.ARRAY_BUFFER, p.nor, g.STATIC_DRAW);
    });
    gl3 = { g: g, prog: prog, p: g.getAttribLocation(prog, "p"), n: g.getAttribLocation(prog, "n"),
      mv: g.getUniformLocation(prog, "mv"), pr: g.getUniformLocation(prog, "pr"), col: g.getUniformLocation(prog, "col") };
  }
  function hex(c) { return [parseInt(c.substr(1, 2), 16) / 255, parseInt(c.substr(3, 2), 16) / 255, parseInt(c.substr(5, 2), 16) / 255]; }
  function draw3d() {
    var c = $("solid3d"), parts = D.parts3d || [];
    if (!parts.length) return;
    fitCanvas(c);
    var V = viewMatrix(), P = projMatrix(c.width / c.height);
    if (!gl3) return drawFallback(c, V, P);
    var g = gl3.g;
    g.viewport(0, 0, c.width, c.height);
    g.clearColor(0.96, 0.97, 0.98, 1); g.clear(g.COLOR_BUFFER_BIT | g.DEPTH_BUFFER_BIT);
    g.enable(g.DEPTH_TEST); g.useProgram(gl3.prog);
    g.uniformMatrix4fv(gl3.pr, false, P);
    parts.forEach(function (p) {
      g.uniformMatrix4fv(gl3.mv, false, mat4mul(V, poseMatrix(p)));
      g.uniform3fv(gl3.col, hex(p.color || "#8899bb"));
      g.bindBuffer(g.ARRAY_BUFFER, p.bp); g.enableVertexAttribArray(gl3.p); g.vertexAttribPointer(gl3.p, 3, g.FLOAT, false, 0, 0);
      g.bindBuffer(g.ARRAY_BUFFER, p.bn); g.enableVertexAttribArray(gl3.n); g.vertexAttribPointer(gl3.n, 3, g.FLOAT, false, 0, 0);
      g.drawArrays(g.TRIANGLES, 0, p.count);
    });
  }
  function drawFallback(c, V, P) {  // painter's algorithm on a 2D canvas (every 4th triangle is enough to show the shape)
    var g = c.getContext("2d"), W = c.width, H = c.height, tris = [];
    g.fillStyle = "#f5f7fa"; g.fillRect(0, 0, W, H);
    (D.parts3d || []).forEach(function (p) {
      var M = mat4mul(P, mat4mul(V, poseMatrix(p))), col = hex(p.color || "#8899bb");
      for (var t = 0; t < p.count; t += 12) {
        var q = [], z = 0;
        for (var k = 0; k < 3; k++) {
          var o = (t + k) * 3, x = p.pos[o], y = p.pos[o + 1], zz = p.pos[o + 2];
          var w = M[3] * x + M[7] * y + M[11] * zz + M[15];
          q.push((M[0] * x + M[4] * y + M[8] * zz + M[12]) / w, (M[1] * x + M[5] * y + M[9] * zz + M[13]) / w);
          z += w;
        }
        tris.push([z, q, col, Math.abs(p.nor[t * 3 + 2])]);
      }
    });
    tris.sort(function (a, b) { return b[0] - a[0]; });
    tris.forEach(function (t) {
      var q = t[1], s = 0.4 + 0.6 * t[3];
      g.beginPath(); g.moveTo((q[0] + 1) * W / 2, (1 - q[1]) * H / 2);
      g.lineTo((q[2] + 1) * W / 2, (1 - q[3]) * H / 2); g.lineTo((q[4] + 1) * W / 2, (1 - q[5]) * H / 2);
      g.fillStyle = "rgb(" + [0, 1, 2].map(function (i) { return Math.round(255 * t[2][i] * s); }).join(",") + ")";
      g.fill();
    });
  }

  /* ---------------- loop ---------------- */
  function controls() {
    var b = $("play");
    b.addEventListener("click", function () { state.playing = !state.playing; b.textContent = state.playing ? "pause" : "play"; });
    $("speed").addEventListener("input", function (e) { state.speed = parseFloat(e.target.value); });
    $("step").addEventListener("click", function () { state.frame = (state.frame + 1) % nFrames; });
  }
  function tick(t) {
    if (state.last) {
      state.acc += (t - state.last) / 1000 * (D.anim ? D.anim.fps : 30) * state.speed;
      if (state.playing && state.acc >= 1) { state.frame = (state.frame + Math.floor(state.acc)) % nFrames; }
      if (state.acc >= 1) state.acc -= Math.floor(state.acc);
    }
    state.last = t;
    if (D.anim) { draw2d(); drawTrace(); }
    drawMap();
    draw3d();
    document.body.setAttribute("data-frame", String(state.frame));
    window.requestAnimationFrame(tick);
  }
  tables();
  if (D.anim) { setup2d(); controls(); } else { $("animpanel").style.display = "none"; }
  if (!D.map) $("mappanel").style.display = "none"; else document.querySelector("main").className = "three";
  setup3d();
  window.requestAnimationFrame(tick);
})();
