// deepcheck viewer: draws the JSON scene written by viewer/html_view.h with three.js.
//
// Data (all lengths in metres, world frame z up; base64 strings hold little-endian arrays):
//   bodies[]: name, layer, visible, track (-1: fixed at pose), pose [x y z qx qy qz qw],
//             shapes[] (box/sphere/cylinder/mesh in the body frame), pieces (wireframe: vertices
//             f32 xyz, edges u32 pairs, firsts u32 first vertex of each piece, spheres f32 xyzr);
//   frames:   count, tracks, poses f32 (count x tracks x 7; x = NaN hides the track), waypoint
//             ("1"/"0" per frame), value f64 (plotted), labels[], contact {has, distance f64,
//             points f32 (pointA, pointB, normal per frame), names [A, B per frame]},
//             bodyContact {has, distance f64, points f32}: the same pair measured as whole bodies
//             (each the union of its pieces), where the pair overlaps.
// URL hash: #t=N | #t=end selects the frame; "probe" adds pixel statistics of the first image
// (data-pixel-variance, data-pixel-hash on <html>) and the arrows shown (data-arrows: "contact",
// "body depth", comma-separated, with data-body-depth the body arrow's length) for the browser test; "timing" shows up to 60
// frames and sets data-frame-ms (for the benchmark); "antialias" multisamples even in software
// WebGL (for screenshots). When the first image is
// drawn <html> gets data-ready="1" and data-load-ms (time since navigation start).
(function () {
  'use strict';

  const data = JSON.parse(document.getElementById('deepcheck-data').textContent);
  const frames = data.frames;

  function bytes(b64) {
    const s = atob(b64);
    const out = new Uint8Array(s.length);
    for (let i = 0; i < s.length; ++i) out[i] = s.charCodeAt(i);
    return out.buffer;
  }
  const f32 = (b64) => new Float32Array(bytes(b64));
  const f64 = (b64) => new Float64Array(bytes(b64));
  const u32 = (b64) => new Uint32Array(bytes(b64));

  const poses = f32(frames.poses);
  const values = f64(frames.value);
  const contactDistance = f64(frames.contact.distance);
  const contactPoints = f32(frames.contact.points);
  const bodyContactDistance = f64(frames.bodyContact.distance);
  const bodyContactPoints = f32(frames.bodyContact.points);

  const LAYER_COLOURS = { robot: 0xd9a45b, attached: 0x6bb36b, scene: 0x8fa3b8, obstacle: 0xb86f5e, 'shape A': 0x4a90d9,
    'shape B': 0xe0a030, answer: 0x3fae49, mesh: 0xb5b5b5 };
  const SHAPE_OPACITY = { scene: 0.55, obstacle: 0.7, answer: 0.35 };
  const colourOf = (layer) => (layer in LAYER_COLOURS ? LAYER_COLOURS[layer] : 0xa0a0a0);

  // --- three.js scene -------------------------------------------------------------------------
  const container = document.getElementById('view');
  // Multisampling costs 4x in software WebGL (SwiftShader, llvmpipe: headless browsers, virtual
  // machines) and nearly nothing on a GPU.
  function softwareWebGl() {
    const gl = document.createElement('canvas').getContext('webgl');
    const info = gl && gl.getExtension('WEBGL_debug_renderer_info');
    return /swiftshader|llvmpipe|software/i.test(info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : '');
  }
  const antialias = /antialias/.test(window.location.hash) || !softwareWebGl();
  const renderer = new THREE.WebGLRenderer({ antialias: antialias, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xf4f5f7);
  container.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(45, 1, 0.01, 1000);
  camera.up.set(0, 0, 1);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x667788, 0.75));
  const sun = new THREE.DirectionalLight(0xffffff, 0.55);
  camera.add(sun);
  sun.position.set(1, 2, 3);
  scene.add(camera);

  function setPose(object, p, offset) {
    object.position.set(p[offset], p[offset + 1], p[offset + 2]);
    object.quaternion.set(p[offset + 3], p[offset + 4], p[offset + 5], p[offset + 6]);
  }

  function primitiveGeometry(shape) {
    if (shape.type === 'box') return new THREE.BoxBufferGeometry(shape.size[0], shape.size[1], shape.size[2]);
    if (shape.type === 'sphere') return new THREE.SphereBufferGeometry(shape.radius, 32, 16);
    if (shape.type === 'cylinder') {
      // three.js cylinders run along y, URDF ones along z.
      const g = new THREE.CylinderBufferGeometry(shape.radius, shape.radius, shape.length, 32);
      g.rotateX(Math.PI / 2);
      return g;
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(f32(shape.vertices), 3));
    g.setIndex(new THREE.BufferAttribute(u32(shape.triangles), 1));
    g.computeVertexNormals();
    return g;
  }

  function shapesObject(body) {
    const group = new THREE.Group();
    // Scenes and answers see-through: the robot inside a shelf stays visible.
    const opacity = SHAPE_OPACITY[body.layer] || 1;
    const material = new THREE.MeshStandardMaterial({ color: colourOf(body.layer), roughness: 0.75,
      metalness: 0.05, flatShading: true, side: THREE.DoubleSide, transparent: opacity < 1, opacity: opacity,
      depthWrite: opacity === 1 });
    for (const shape of body.shapes) {
      const mesh = new THREE.Mesh(primitiveGeometry(shape), material);
      setPose(mesh, shape.pose, 0);
      group.add(mesh);
    }
    return group;
  }

  function piecesObject(pieces) {
    const group = new THREE.Group();
    const vertices = f32(pieces.vertices);
    const firsts = u32(pieces.firsts);
    const colours = new Float32Array(vertices.length);
    const colour = new THREE.Color();
    for (let p = 0; p < firsts.length; ++p) {
      colour.setHSL((p * 0.618034) % 1, 0.75, 0.4);  // golden-ratio hues: neighbours differ
      const end = p + 1 < firsts.length ? firsts[p + 1] : vertices.length / 3;
      for (let v = firsts[p]; v < end; ++v) colour.toArray(colours, 3 * v);
    }
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(vertices, 3));
    g.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    g.setIndex(new THREE.BufferAttribute(u32(pieces.edges), 1));
    const material = new THREE.LineBasicMaterial({ vertexColors: THREE.VertexColors, transparent: true,
      opacity: 0.6, depthTest: false });
    const lines = new THREE.LineSegments(g, material);
    lines.renderOrder = 1;  // drawn over the shaded shapes they wrap
    group.add(lines);
    const spheres = f32(pieces.spheres);
    for (let i = 0; i < spheres.length; i += 4) {
      const wire = new THREE.LineSegments(new THREE.WireframeGeometry(new THREE.SphereBufferGeometry(spheres[i + 3], 12, 8)),
        new THREE.LineBasicMaterial({ color: 0x8844aa, transparent: true, opacity: 0.6, depthTest: false }));
      wire.position.set(spheres[i], spheres[i + 1], spheres[i + 2]);
      wire.renderOrder = 1;
      group.add(wire);
    }
    return group;
  }

  // --- bodies and layers -------------------------------------------------------------------------
  const layerVisible = {};  // "<layer> shapes" / "<layer> pieces" / "contact" / "body depth" / "grid" -> bool
  const bodies = data.bodies.map((b) => {
    const object = new THREE.Group();
    object.name = b.name;
    const shapes = shapesObject(b);
    const pieces = piecesObject(b.pieces);
    object.add(shapes, pieces);
    setPose(object, b.pose, 0);
    scene.add(object);
    layerVisible[b.layer + ' shapes'] = true;
    if (b.pieces.count > 0) layerVisible[b.layer + ' pieces'] = true;
    return { data: b, object: object, shapes: shapes, pieces: pieces, on: b.visible, hiddenNow: false };
  });
  layerVisible.contact = true;
  layerVisible['body depth'] = true;
  layerVisible.grid = true;

  function applyVisibility() {
    for (const b of bodies) {
      b.object.visible = b.on && !b.hiddenNow;
      b.shapes.visible = layerVisible[b.data.layer + ' shapes'];
      b.pieces.visible = !!layerVisible[b.data.layer + ' pieces'];
    }
    contact.group.visible = layerVisible.contact && contact.present;
    bodyContact.group.visible = layerVisible['body depth'] && bodyContact.present;
    grid.visible = layerVisible.grid;
  }

  // --- contact: witness points and the signed-distance arrow -------------------------------------
  scene.updateMatrixWorld(true);
  const bounds = new THREE.Box3();
  for (const b of bodies) bounds.expandByObject(b.object);
  if (bounds.isEmpty()) bounds.set(new THREE.Vector3(-1, -1, -1), new THREE.Vector3(1, 1, 1));
  const size = Math.max(bounds.getSize(new THREE.Vector3()).length(), 0.05);
  const center = bounds.getCenter(new THREE.Vector3());

  const grid = new THREE.GridHelper(Math.ceil(size * 2), Math.ceil(size * 2) * 10, 0xb0b4bb, 0xdde0e4);
  grid.rotateX(Math.PI / 2);  // the xy plane (z up)
  scene.add(grid);

  /// An arrow of solid meshes (lines are one pixel wide): a shaft and a cone along +y, scaled by place().
  function makeArrow(colour) {
    const material = new THREE.MeshBasicMaterial({ color: colour, depthTest: false, transparent: true });
    const shaft = new THREE.Mesh(new THREE.CylinderBufferGeometry(1, 1, 1, 12), material);
    const head = new THREE.Mesh(new THREE.ConeBufferGeometry(1, 1, 16), material);
    const object = new THREE.Group();
    object.add(shaft, head);
    const up = new THREE.Vector3(0, 1, 0);
    function place(origin, direction, length) {
      const headLength = Math.min(0.4 * length, size * 0.025);
      const radius = size * 0.002;
      object.position.copy(origin);
      object.quaternion.setFromUnitVectors(up, direction);
      shaft.scale.set(radius, length - headLength, radius);
      shaft.position.set(0, (length - headLength) / 2, 0);
      head.scale.set(2.5 * radius, headLength, 2.5 * radius);
      head.position.set(0, length - headLength / 2, 0);
    }
    return { object: object, material: material, place: place };
  }

  const contact = (function () {
    const group = new THREE.Group();
    const marker = new THREE.SphereBufferGeometry(size * 0.0035, 16, 8);
    const pointA = new THREE.Mesh(marker, new THREE.MeshBasicMaterial({ color: 0x1a3cc8, depthTest: false, transparent: true }));
    const pointB = new THREE.Mesh(marker, new THREE.MeshBasicMaterial({ color: 0xc81a9c, depthTest: false, transparent: true }));
    const arrow = makeArrow(0x22aa22);
    // Drawn last, over everything (transparent objects are drawn after opaque ones).
    for (const o of [pointA, pointB, arrow.object]) o.traverse((x) => { x.renderOrder = 2; });
    group.add(pointA, pointB, arrow.object);
    scene.add(group);
    return { group: group, pointA: pointA, pointB: pointB, arrow: arrow, present: false };
  })();

  // The body-level push-out: the pair's two bodies as unions of their pieces. Orange, from B's
  // witness along the normal, its length the body depth: the translation of B that separates the
  // bodies (the pairwise red arrow separates only the deepest pair of pieces). Slightly thicker,
  // so that where both arrows agree the red one shows inside it.
  const bodyContact = (function () {
    const group = new THREE.Group();
    const arrow = makeArrow(0xf08c00);
    arrow.object.scale.set(1.8, 1, 1.8);
    arrow.object.traverse((x) => { x.renderOrder = 2; });
    group.add(arrow.object);
    scene.add(group);
    return { group: group, arrow: arrow, present: false, depth: 0 };
  })();

  function showBodyContact(f) {
    bodyContact.present = frames.bodyContact.has[f] === '1' && bodyContactDistance[f] < 0;
    if (!bodyContact.present) return;
    const p = bodyContactPoints;
    const o = 9 * f;
    const b = new THREE.Vector3(p[o + 3], p[o + 4], p[o + 5]);
    const n = new THREE.Vector3(p[o + 6], p[o + 7], p[o + 8]);
    bodyContact.depth = -bodyContactDistance[f];
    bodyContact.arrow.place(b, n.normalize(), bodyContact.depth);
  }

  function showContact(f) {
    contact.present = frames.contact.has[f] === '1';
    if (!contact.present) return;
    const p = contactPoints;
    const o = 9 * f;
    const a = new THREE.Vector3(p[o], p[o + 1], p[o + 2]);
    const b = new THREE.Vector3(p[o + 3], p[o + 4], p[o + 5]);
    const n = new THREE.Vector3(p[o + 6], p[o + 7], p[o + 8]);
    const d = contactDistance[f];
    contact.pointA.position.copy(a);
    contact.pointB.position.copy(b);
    // distance > 0: from A's witness to B's; penetration: depth x normal from B's witness to A's
    // (the translation of B that separates the pair). Both point along the normal.
    const length = Math.abs(d);
    contact.arrow.object.visible = length > 1e-9;
    if (length > 1e-9) contact.arrow.place(d >= 0 ? a : b, n.normalize(), length);
    contact.arrow.material.color.set(d >= 0 ? 0x22aa22 : 0xee1111);
  }

  // --- frames --------------------------------------------------------------------------------------
  let current = 0;
  function showFrame(f) {
    current = Math.max(0, Math.min(frames.count - 1, f));
    for (const b of bodies) {
      if (b.data.track < 0) continue;
      const offset = 7 * (current * frames.tracks + b.data.track);
      b.hiddenNow = Number.isNaN(poses[offset]);
      if (!b.hiddenNow) setPose(b.object, poses, offset);
    }
    showContact(current);
    showBodyContact(current);
    applyVisibility();
    slider.value = String(current);
    frameLabel.textContent = frameText(current);
    drawPlot();
    render();
  }

  function formatNumber(v) {
    return Number.isFinite(v) ? v.toPrecision(4) : 'none';
  }

  function frameText(f) {
    let text = 'frame ' + f + '/' + (frames.count - 1);
    if (frames.labels[f]) text += ' · ' + frames.labels[f];
    if (frames.contact.has[f] === '1') {
      text += ' · sd ' + formatNumber(contactDistance[f]) + ' m ' + frames.contact.names[2 * f] + ' – ' +
        frames.contact.names[2 * f + 1];
    }
    if (frames.bodyContact.has[f] === '1') text += ' · body depth ' + formatNumber(-bodyContactDistance[f]) + ' m';
    return text;
  }

  // --- clearance plot ---------------------------------------------------------------------------------
  const plot = document.getElementById('plot');
  const worst = (function () {
    let best = -1;
    for (let f = 0; f < frames.count; ++f) {
      if (Number.isFinite(values[f]) && (best < 0 || values[f] < values[best])) best = f;
    }
    return best;
  })();

  function plotRange() {
    let lo = Infinity;
    let hi = -Infinity;
    for (const v of values) {
      if (Number.isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); }
    }
    if (lo > hi) return null;
    lo = Math.min(lo, 0);
    hi = Math.max(hi, 0);
    const pad = 0.08 * (hi - lo || 1);
    return { lo: lo - pad, hi: hi + pad };
  }

  function drawPlot() {
    const width = plot.clientWidth;
    const height = plot.clientHeight;
    if (plot.width !== width) plot.width = width;
    const ctx = plot.getContext('2d');
    ctx.clearRect(0, 0, width, height);
    const range = plotRange();
    if (!range || frames.count < 2) return;
    const left = 46;
    const x = (f) => left + (width - left - 8) * f / (frames.count - 1);
    const y = (v) => 6 + (height - 22) * (range.hi - v) / (range.hi - range.lo);
    ctx.font = '11px sans-serif';
    ctx.fillStyle = '#555';
    ctx.fillText(data.valueName, left + 4, height - 3);
    ctx.fillText(formatNumber(range.hi), 2, 14);
    ctx.fillText(formatNumber(range.lo), 2, height - 16);
    ctx.strokeStyle = '#c33';
    ctx.setLineDash([4, 3]);
    ctx.beginPath(); ctx.moveTo(left, y(0)); ctx.lineTo(width - 8, y(0)); ctx.stroke();
    ctx.setLineDash([]);
    ctx.strokeStyle = '#2a6fb0';
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    let pen = false;
    for (let f = 0; f < frames.count; ++f) {
      if (!Number.isFinite(values[f])) { pen = false; continue; }
      if (pen) ctx.lineTo(x(f), y(values[f])); else ctx.moveTo(x(f), y(values[f]));
      pen = true;
    }
    ctx.stroke();
    drawPlotMarks(ctx, x, y);
  }

  function drawPlotMarks(ctx, x, y) {
    ctx.fillStyle = '#2a6fb0';
    if (frames.count <= 400) {
      for (let f = 0; f < frames.count; ++f) {
        if (frames.waypoint[f] === '1' && Number.isFinite(values[f])) ctx.fillRect(x(f) - 2, y(values[f]) - 2, 4, 4);
      }
    }
    if (worst >= 0) {
      ctx.strokeStyle = '#d22';
      ctx.lineWidth = 2;
      ctx.beginPath(); ctx.arc(x(worst), y(values[worst]), 5, 0, 2 * Math.PI); ctx.stroke();
      ctx.fillStyle = '#d22';
      const text = 'worst: frame ' + worst + ', ' + formatNumber(values[worst]) + ' m';
      ctx.fillText(text, Math.min(x(worst) + 8, plot.width - ctx.measureText(text).width - 4), 14);
    }
    ctx.strokeStyle = '#222';
    ctx.lineWidth = 1;
    ctx.beginPath(); ctx.moveTo(x(current), 0); ctx.lineTo(x(current), plot.height - 14); ctx.stroke();
  }

  function frameAt(event) {
    const rect = plot.getBoundingClientRect();
    const t = (event.clientX - rect.left - 46) / Math.max(1, rect.width - 54);
    return Math.round(t * (frames.count - 1));
  }
  plot.addEventListener('mousedown', (e) => showFrame(frameAt(e)));
  plot.addEventListener('mousemove', (e) => { if (e.buttons & 1) showFrame(frameAt(e)); });

  // --- timeline controls -------------------------------------------------------------------------------
  const slider = document.getElementById('slider');
  const frameLabel = document.getElementById('frame-label');
  const playButton = document.getElementById('play');
  slider.max = String(frames.count - 1);
  slider.addEventListener('input', () => { stop(); showFrame(Number(slider.value)); });
  let timer = null;
  function stop() {
    if (timer !== null) clearInterval(timer);
    timer = null;
    playButton.innerHTML = '&#9654;';
  }
  function play() {
    if (current >= frames.count - 1) showFrame(0);
    const step = Math.max(1, Math.round(frames.count / 300));  // about 10 s for any path
    timer = setInterval(() => {
      if (current >= frames.count - 1) { stop(); return; }
      showFrame(current + step);
    }, 33);
    playButton.innerHTML = '&#10073;&#10073;';
  }
  playButton.addEventListener('click', () => (timer === null ? play() : stop()));
  window.addEventListener('keydown', (e) => {
    if (e.code === 'Space' && e.target.tagName !== 'INPUT') { e.preventDefault(); timer === null ? play() : stop(); }
  });

  // --- panel: layers and bodies ------------------------------------------------------------------------
  function checkbox(parent, text, checked, onChange) {
    const label = document.createElement('label');
    const box = document.createElement('input');
    box.type = 'checkbox';
    box.checked = checked;
    box.addEventListener('change', () => { onChange(box.checked); applyVisibility(); render(); });
    label.append(box, ' ' + text);
    label.title = text;
    parent.appendChild(label);
  }

  function buildPanel() {
    document.title = data.title;
    document.getElementById('title').textContent = data.title;
    const layers = document.getElementById('layers');
    for (const key of Object.keys(layerVisible)) {
      checkbox(layers, key, layerVisible[key], (on) => { layerVisible[key] = on; });
    }
    const list = document.getElementById('bodies');
    for (const b of bodies) checkbox(list, b.data.name, b.on, (on) => { b.on = on; });
    if (data.caption) {
      // The first line always shown, the rest on demand.
      const caption = document.getElementById('caption');
      const lines = data.caption.replace(/\n+$/, '').split('\n');
      const details = document.createElement('details');
      const summary = document.createElement('summary');
      summary.textContent = lines[0];
      details.append(summary, lines.slice(1).join('\n'));
      details.open = lines.length <= 4;
      caption.appendChild(details);
      caption.hidden = false;
    }
    if (frames.count < 2) document.body.classList.add('single-frame');
  }

  // --- camera, rendering, start-up -----------------------------------------------------------------------
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.copy(center);
  camera.position.copy(center).add(new THREE.Vector3(-0.9, -1.5, 0.8).multiplyScalar(size * 0.55));
  camera.near = size * 0.002;
  camera.far = size * 50;
  controls.update();
  controls.addEventListener('change', () => render());

  function resize() {
    renderer.setSize(container.clientWidth, container.clientHeight);
    camera.aspect = container.clientWidth / Math.max(1, container.clientHeight);
    camera.updateProjectionMatrix();
    drawPlot();
    render();
  }
  window.addEventListener('resize', resize);

  function render() {
    renderer.render(scene, camera);
  }

  function frameFromHash() {
    const match = /t=(end|\d+)/.exec(window.location.hash);
    if (!match) return 0;
    return match[1] === 'end' ? frames.count - 1 : Number(match[1]);
  }
  window.addEventListener('hashchange', () => showFrame(frameFromHash()));

  /// Luminance variance and a hash of the drawn image, on <html> (for the browser test).
  function probePixels() {
    const gl = renderer.getContext();
    const w = gl.drawingBufferWidth;
    const h = gl.drawingBufferHeight;
    const px = new Uint8Array(w * h * 4);
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
    let sum = 0;
    let sum2 = 0;
    let hash = 2166136261;
    for (let i = 0; i < px.length; i += 4) {
      const l = 0.299 * px[i] + 0.587 * px[i + 1] + 0.114 * px[i + 2];
      sum += l;
      sum2 += l * l;
      hash = Math.imul(hash ^ px[i] ^ (px[i + 1] << 8) ^ (px[i + 2] << 16), 16777619) >>> 0;
    }
    const n = w * h;
    document.documentElement.setAttribute('data-pixel-variance', (sum2 / n - (sum / n) * (sum / n)).toFixed(3));
    document.documentElement.setAttribute('data-pixel-hash', hash.toString(16));
    const arrows = [];
    if (contact.group.visible && contact.arrow.object.visible) arrows.push('contact');
    if (bodyContact.group.visible) {
      arrows.push('body depth');
      document.documentElement.setAttribute('data-body-depth', bodyContact.depth.toPrecision(6));
    }
    document.documentElement.setAttribute('data-arrows', arrows.join(','));
  }

  /// Mean milliseconds to show a frame (poses, contact, plot, render), over up to 60 frames spread
  /// along the path, on <html> data-frame-ms (for bench/run_view_bench.sh).
  function timeFrames() {
    const shown = Math.min(frames.count, 60);
    const start = performance.now();
    for (let i = 0; i < shown; ++i) {
      showFrame(Math.round(i * (frames.count - 1) / Math.max(1, shown - 1)));
    }
    const gl = renderer.getContext();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array(4));  // waits for the drawing
    const ms = (performance.now() - start) / shown;
    document.documentElement.setAttribute('data-frame-ms', ms.toFixed(2));
  }

  buildPanel();
  camera.updateProjectionMatrix();
  resize();
  showFrame(frameFromHash());
  if (/probe/.test(window.location.hash)) probePixels();
  document.documentElement.setAttribute('data-load-ms', performance.now().toFixed(0));
  if (/timing/.test(window.location.hash)) timeFrames();
  document.documentElement.setAttribute('data-ready', '1');
})();
