// spiralbevel report: a small WebGL viewer of the meshing pair (no dependencies, no network).
// Data: a JSON element with id "pair-data" (spiralbevel.io.report_mesh.view_payload): per member one tooth (base64
// float32 positions, int8 normals, uint16/uint32 indices), its tooth count, a 3x3 placement into the pair frame and
// the rolling ratio. Each tooth is drawn z times about the member axis. Drag: orbit; wheel: zoom; shift-drag: pan.
(function () {
  "use strict";
  var canvas = document.getElementById("pair-canvas");
  var status = document.getElementById("pair-status");
  var dataElement = document.getElementById("pair-data");
  if (!canvas || !dataElement) { return; }
  function say(text) { if (status) { status.textContent = text; } }
  var data = JSON.parse(dataElement.textContent);
  var gl = canvas.getContext("webgl", {antialias: true, preserveDrawingBuffer: true});
  if (!gl) { say("This browser has no WebGL: the 3-D view is not available (the rest of the report is)."); return; }

  function decode(b64, Type) {
    var s = atob(b64), bytes = new Uint8Array(s.length);
    for (var i = 0; i < s.length; i++) { bytes[i] = s.charCodeAt(i); }
    return new Type(bytes.buffer);
  }

  var vsSource = [
    "attribute vec3 position; attribute vec3 normal;",
    "uniform mat4 model; uniform mat4 view; uniform mat4 projection;",
    "varying vec3 vNormal;",
    "void main() { vNormal = mat3(view * model) * normal;",
    "  gl_Position = projection * view * model * vec4(position, 1.0); }"].join("\n");
  var fsSource = [
    "precision mediump float; uniform vec3 colour; varying vec3 vNormal;",
    "void main() { vec3 n = normalize(vNormal); if (!gl_FrontFacing) { n = -n; }",
    "  float d = max(dot(n, normalize(vec3(0.3, 0.5, 1.0))), 0.0);",
    "  float s = pow(max(dot(n, normalize(vec3(0.3, 0.5, 2.0))), 0.0), 40.0);",
    "  gl_FragColor = vec4(colour * (0.28 + 0.72 * d) + vec3(0.25 * s), 1.0); }"].join("\n");

  function shader(type, source) {
    var sh = gl.createShader(type);
    gl.shaderSource(sh, source); gl.compileShader(sh);
    if (!gl.getShaderParameter(sh, gl.COMPILE_STATUS)) { throw new Error(gl.getShaderInfoLog(sh)); }
    return sh;
  }
  var program = gl.createProgram();
  gl.attachShader(program, shader(gl.VERTEX_SHADER, vsSource));
  gl.attachShader(program, shader(gl.FRAGMENT_SHADER, fsSource));
  gl.linkProgram(program);
  gl.useProgram(program);
  var loc = {
    position: gl.getAttribLocation(program, "position"), normal: gl.getAttribLocation(program, "normal"),
    model: gl.getUniformLocation(program, "model"), view: gl.getUniformLocation(program, "view"),
    projection: gl.getUniformLocation(program, "projection"), colour: gl.getUniformLocation(program, "colour")
  };
  var uintIndices = gl.getExtension("OES_element_index_uint");
  var colours = {pinion: [0.23, 0.47, 0.78], gear: [0.80, 0.42, 0.22]};

  // 4x4 matrices, column-major (WebGL order)
  function mul(a, b) {
    var r = new Float32Array(16);
    for (var c = 0; c < 4; c++) { for (var i = 0; i < 4; i++) {
      var s = 0; for (var k = 0; k < 4; k++) { s += a[k * 4 + i] * b[c * 4 + k]; } r[c * 4 + i] = s; } }
    return r;
  }
  function fromRows3(m) {  // row-major 3x3 -> column-major 4x4
    return new Float32Array([m[0], m[3], m[6], 0, m[1], m[4], m[7], 0, m[2], m[5], m[8], 0, 0, 0, 0, 1]);
  }
  function rotZ(a) { var c = Math.cos(a), s = Math.sin(a);
    return new Float32Array([c, s, 0, 0, -s, c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]); }
  function rotX(a) { var c = Math.cos(a), s = Math.sin(a);
    return new Float32Array([1, 0, 0, 0, 0, c, s, 0, 0, -s, c, 0, 0, 0, 0, 1]); }
  function translate(x, y, z) { return new Float32Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, x, y, z, 1]); }
  function perspective(fovy, aspect, near, far) {
    var f = 1 / Math.tan(fovy / 2), nf = 1 / (near - far);
    return new Float32Array([f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0]);
  }

  var members = [], lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  data.members.forEach(function (m) {
    var positions = decode(m.positions, Float32Array), normals = decode(m.normals, Int8Array);
    var indices = m.index_bits === 32 ? decode(m.indices, Uint32Array) : decode(m.indices, Uint16Array);
    if (m.index_bits === 32 && !uintIndices) { say("This browser cannot draw meshes of this size."); return; }
    var place = fromRows3(m.placement), rmax = 0, zmin = Infinity, zmax = -Infinity;
    for (var i = 0; i < positions.length; i += 3) {
      rmax = Math.max(rmax, Math.hypot(positions[i], positions[i + 1]));
      zmin = Math.min(zmin, positions[i + 2]); zmax = Math.max(zmax, positions[i + 2]);
    }
    // bounding box of the whole member in the pair frame: the circle of radius rmax at z = zmin and zmax
    for (var t = 0; t < 64; t++) {
      var a = 2 * Math.PI * t / 64;
      [zmin, zmax].forEach(function (z) {
        var p = [rmax * Math.cos(a), rmax * Math.sin(a), z];
        for (var j = 0; j < 3; j++) {
          var q = place[j] * p[0] + place[4 + j] * p[1] + place[8 + j] * p[2];
          lo[j] = Math.min(lo[j], q); hi[j] = Math.max(hi[j], q);
        }
      });
    }
    var buffers = {position: gl.createBuffer(), normal: gl.createBuffer(), index: gl.createBuffer()};
    gl.bindBuffer(gl.ARRAY_BUFFER, buffers.position); gl.bufferData(gl.ARRAY_BUFFER, positions, gl.STATIC_DRAW);
    gl.bindBuffer(gl.ARRAY_BUFFER, buffers.normal); gl.bufferData(gl.ARRAY_BUFFER, normals, gl.STATIC_DRAW);
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, buffers.index);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, indices, gl.STATIC_DRAW);
    members.push({name: m.name, teeth: m.teeth, ratio: m.ratio, place: place, buffers: buffers, count: indices.length,
                  type: m.index_bits === 32 ? gl.UNSIGNED_INT : gl.UNSIGNED_SHORT, visible: true});
  });
  var centre = [0, 1, 2].map(function (j) { return 0.5 * (lo[j] + hi[j]); });
  var size = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  // home: from the side of the gear's back face, both members and the mesh zone in sight
  var home = {yaw: -0.9, pitch: -1.0, distance: 2.0 * size, pan: [0, 0]};
  var cam = JSON.parse(JSON.stringify(home));
  var roll = 0, animate = false, last = null;

  function draw() {
    var w = canvas.clientWidth, h = canvas.clientHeight, dpr = window.devicePixelRatio || 1;
    if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
      canvas.width = Math.round(w * dpr); canvas.height = Math.round(h * dpr);
    }
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(0.97, 0.97, 0.98, 1); gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    var view = mul(translate(cam.pan[0], cam.pan[1], -cam.distance),
                   mul(rotX(cam.pitch), mul(rotZ(cam.yaw), translate(-centre[0], -centre[1], -centre[2]))));
    gl.uniformMatrix4fv(loc.view, false, view);
    gl.uniformMatrix4fv(loc.projection, false, perspective(0.6, canvas.width / Math.max(canvas.height, 1),
                                                           size * 0.05, size * 10));
    members.forEach(function (m) {
      if (!m.visible) { return; }
      gl.uniform3fv(loc.colour, colours[m.name] || [0.6, 0.6, 0.6]);
      gl.bindBuffer(gl.ARRAY_BUFFER, m.buffers.position);
      gl.enableVertexAttribArray(loc.position); gl.vertexAttribPointer(loc.position, 3, gl.FLOAT, false, 0, 0);
      gl.bindBuffer(gl.ARRAY_BUFFER, m.buffers.normal);
      gl.enableVertexAttribArray(loc.normal); gl.vertexAttribPointer(loc.normal, 3, gl.BYTE, true, 0, 0);
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, m.buffers.index);
      for (var k = 0; k < m.teeth; k++) {
        gl.uniformMatrix4fv(loc.model, false, mul(m.place, rotZ(2 * Math.PI * k / m.teeth + roll * m.ratio)));
        gl.drawElements(gl.TRIANGLES, m.count, m.type, 0);
      }
    });
  }
  function frame(t) {
    if (animate) {
      if (last !== null) { roll += 0.25 * (t - last) / 1000; }
      last = t; draw(); window.requestAnimationFrame(frame);
    } else { last = null; }
  }

  var drag = null;
  canvas.addEventListener("pointerdown", function (e) {
    drag = {x: e.clientX, y: e.clientY, pan: e.shiftKey}; canvas.setPointerCapture(e.pointerId); });
  canvas.addEventListener("pointerup", function () { drag = null; });
  canvas.addEventListener("pointermove", function (e) {
    if (!drag) { return; }
    var dx = e.clientX - drag.x, dy = e.clientY - drag.y; drag.x = e.clientX; drag.y = e.clientY;
    if (drag.pan) {
      var k = cam.distance / canvas.clientHeight; cam.pan[0] += dx * k; cam.pan[1] -= dy * k;
    } else { cam.yaw += dx * 0.01; cam.pitch += dy * 0.01; }
    draw();
  });
  canvas.addEventListener("wheel", function (e) {
    e.preventDefault(); cam.distance *= Math.exp(e.deltaY * 0.001); draw(); }, {passive: false});
  function button(id, fn) { var b = document.getElementById(id); if (b) { b.addEventListener("click", fn); } }
  var home_centre = centre.slice();
  button("pair-reset", function () {
    cam = JSON.parse(JSON.stringify(home)); centre = home_centre.slice(); roll = 0; draw(); });
  button("pair-roll", function () { animate = !animate; if (animate) { window.requestAnimationFrame(frame); } });
  members.forEach(function (m) {
    button("pair-toggle-" + m.name, function () { m.visible = !m.visible; draw(); });
  });
  window.addEventListener("resize", draw);
  // for scripted use (tests, screenshots): set the camera (optionally the point looked at, pair frame, mm) or the
  // roll angle (pinion, rad) and redraw
  window.spiralbevelView = {
    set: function (yaw, pitch, distanceFactor, rollAngle, target) {
      cam.yaw = yaw; cam.pitch = pitch; cam.distance = distanceFactor * size; roll = rollAngle || 0;
      if (target) { centre = target.slice(); }
      draw();
    }
  };
  draw();
  var triangles = data.members.reduce(function (s, m) { return s + m.triangles * m.teeth; }, 0);
  say("Pinion (blue) and gear (orange), pair frame, " + triangles + " triangles. Drag to orbit, wheel to zoom, " +
      "shift-drag to pan; 'Roll' turns the pair at its ratio.");
  canvas.setAttribute("data-rendered", "1");
})();
