// SPDX-License-Identifier: GPL-3.0-or-later
// The page of `morphex serve`: the mesh list, a 3D view (three.js r111 from Debian's libjs-three,
// the global THREE), the granulometry curves, queries and failures, over the server's JSON API
// (docs/serve.md). The address drives it too: #query=NAME&kind=KIND&metric=METRIC&k=K selects
// NAME and runs its query (the browser test uses it), #mesh=NAME selects a mesh.
// Text from the index is only ever set as textContent, never parsed as HTML.
'use strict';

(function () {
  const $ = (id) => document.getElementById(id);
  const state = {
    info: null,
    meshes: [],
    byName: new Map(),
    selected: null, // the id of the mesh in the view
    query: null, // the last query's answer
  };
  const BACKGROUND = 0xf4f6f9;

  // ---- helpers ---------------------------------------------------------------------------------

  function el(tag, attributes, ...children) {
    const node = document.createElement(tag);
    for (const [name, value] of Object.entries(attributes || {})) {
      if (name === 'className') node.className = value;
      else if (name === 'dataset') Object.assign(node.dataset, value);
      else node.setAttribute(name, value);
    }
    for (const child of children)
      node.append(child instanceof Node ? child : document.createTextNode(String(child)));
    return node;
  }

  async function fetchOk(url, options) {
    const response = await fetch(url, options);
    if (response.ok) return response;
    let message = response.status + ' ' + response.statusText;
    try {
      message = (await response.json()).error || message;
    } catch (e) {
      // not JSON: the status says enough
    }
    throw new Error(message);
  }
  const getJSON = async (url, options) => (await fetchOk(url, options)).json();

  function showMessage(text) {
    const box = $('message');
    box.textContent = text || '';
    box.hidden = !text;
  }

  function number(value, digits) {
    if (typeof value !== 'number' || !isFinite(value)) return String(value);
    return Number(value.toPrecision(digits || 4)).toString();
  }

  // ---- the 3D view -----------------------------------------------------------------------------

  const view = { renderer: null, scene: null, camera: null, controls: null, model: null };

  function initView() {
    const canvas = $('view');
    try {
      view.renderer = new THREE.WebGLRenderer({
        canvas,
        antialias: true,
        preserveDrawingBuffer: true, // so that the test can read what was drawn
      });
    } catch (e) {
      canvas.dataset.rendered = 'no-webgl';
      viewNote('This browser gives the page no WebGL: the 3D view is off.');
      return;
    }
    view.renderer.setPixelRatio(window.devicePixelRatio || 1);
    view.scene = new THREE.Scene();
    view.scene.background = new THREE.Color(BACKGROUND);
    view.camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
    view.scene.add(view.camera);
    view.scene.add(new THREE.HemisphereLight(0xffffff, 0x9aa8b8, 0.6));
    // A key light from the upper left and a fill from the right, both following the camera, so
    // that the faces in view always get distinct shades.
    const key = new THREE.DirectionalLight(0xffffff, 0.45);
    const fill = new THREE.DirectionalLight(0xffffff, 0.25);
    key.position.set(-0.5, 1, 0.8);
    fill.position.set(1, 0.1, 0.5);
    view.camera.add(key, fill);
    view.controls = new THREE.OrbitControls(view.camera, canvas);
    view.controls.addEventListener('change', render);
    window.addEventListener('resize', () => {
      resizeView();
      drawCurves();
    });
    resizeView();
  }

  function viewNote(text) {
    const note = $('view-note');
    note.textContent = text || '';
    note.hidden = !text;
  }

  function resizeView() {
    if (!view.renderer) return;
    const canvas = $('view');
    const width = canvas.clientWidth || 600, height = canvas.clientHeight || 380;
    view.renderer.setSize(width, height, false);
    view.camera.aspect = width / height;
    view.camera.updateProjectionMatrix();
    render();
  }

  function render() {
    if (view.renderer) view.renderer.render(view.scene, view.camera);
  }

  // Whether the view shows something: pixels that are not the background (the test asks).
  function checkRendered() {
    const gl = view.renderer.getContext();
    const width = gl.drawingBufferWidth, height = gl.drawingBufferHeight;
    const pixels = new Uint8Array(width * height * 4);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    const background = new THREE.Color(BACKGROUND);
    const rgb = [background.r, background.g, background.b].map((c) => Math.round(c * 255));
    let drawn = 0;
    for (let i = 0; i < pixels.length; i += 4)
      if (Math.abs(pixels[i] - rgb[0]) + Math.abs(pixels[i + 1] - rgb[1]) +
          Math.abs(pixels[i + 2] - rgb[2]) > 24)
        ++drawn;
    $('view').dataset.rendered = drawn > width * height * 0.005 ? 'true' : 'blank';
  }

  // A solid seen from outside is blue; the inside of an open or inward mesh shows orange, as in
  // the thumbnails. Edges sharper than 25 degrees are drawn, so that flat faces read as faces.
  function modelFrom(gltf) {
    let source = null;
    gltf.scene.traverse((node) => {
      if (!source && node.isMesh) source = node;
    });
    const group = new THREE.Group();
    if (!source) return group;
    const geometry = source.geometry.toNonIndexed();
    geometry.computeVertexNormals(); // per face: the vertices are no longer shared
    const front = new THREE.MeshStandardMaterial({
      color: 0x5b8fd0, roughness: 0.7, metalness: 0.05, flatShading: true,
      polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1,
    });
    const back = new THREE.MeshStandardMaterial({
      color: 0xdb7550, roughness: 0.7, flatShading: true, side: THREE.BackSide,
    });
    group.add(new THREE.Mesh(geometry, front), new THREE.Mesh(geometry, back));
    if (geometry.attributes.position.count <= 600000) {
      const edges = new THREE.EdgesGeometry(source.geometry, 25);
      group.add(new THREE.LineSegments(edges, new THREE.LineBasicMaterial({
        color: 0x1d3557, transparent: true, opacity: 0.35,
      })));
    }
    return group;
  }

  function frame(group) {
    const sphere = new THREE.Box3().setFromObject(group).getBoundingSphere(new THREE.Sphere());
    const radius = sphere.radius || 1;
    const direction = new THREE.Vector3().fromArray(state.info.view).normalize();
    const distance = radius / Math.sin(view.camera.fov * Math.PI / 360) * 1.08;
    view.camera.position.copy(sphere.center).addScaledVector(direction, distance);
    view.camera.near = distance / 100;
    view.camera.far = distance * 100;
    view.camera.updateProjectionMatrix();
    view.controls.target.copy(sphere.center);
    view.controls.update();
  }

  async function showModel(id) {
    if (!view.renderer) return;
    $('view').dataset.rendered = 'loading';
    viewNote('Loading…');
    try {
      const buffer = await (await fetchOk('/api/mesh/' + id + '.glb')).arrayBuffer();
      const gltf = await new Promise((resolve, reject) =>
        new THREE.GLTFLoader().parse(buffer, '', resolve, reject));
      if (state.selected !== id) return; // another mesh was chosen meanwhile
      if (view.model) view.scene.remove(view.model);
      view.model = modelFrom(gltf);
      view.scene.add(view.model);
      frame(view.model);
      viewNote('');
      render();
      checkRendered();
    } catch (e) {
      if (state.selected !== id) return;
      if (view.model) view.scene.remove(view.model);
      view.model = null;
      render();
      $('view').dataset.rendered = 'error';
      viewNote('Cannot show this mesh: ' + e.message);
    }
  }

  // ---- the granulometry curves -----------------------------------------------------------------

  let curveSets = []; // [{label, curves, colour, dashed}]

  // One chart: points (x, y) on a log x axis when the radii are known, else by scale index.
  function chart(ctx, box, title, xLabel, series, yMax) {
    const [left, top, width, height] = box;
    const xs = series.flatMap((s) => s.x);
    const logX = xs.every((x) => x > 0);
    const fx = logX ? Math.log : (x) => x;
    const lo = Math.min(...xs.map(fx)), hi = Math.max(...xs.map(fx));
    const px = (x) => left + (hi > lo ? (fx(x) - lo) / (hi - lo) : 0.5) * width;
    const py = (y) => top + height - (y / yMax) * height;
    ctx.strokeStyle = '#d9e2ec';
    ctx.fillStyle = '#616e7c';
    ctx.lineWidth = 1;
    ctx.font = '11px system-ui, sans-serif';
    ctx.textAlign = 'right';
    for (const y of [0, yMax / 2, yMax]) {
      ctx.beginPath();
      ctx.moveTo(left, py(y));
      ctx.lineTo(left + width, py(y));
      ctx.stroke();
      ctx.fillText(number(y, 2), left - 4, py(y) + 4);
    }
    ctx.textAlign = 'center';
    const ticks = series.length ? series[0].x : [];
    for (const [i, x] of ticks.entries())
      if (i === 0 || i === ticks.length - 1 || i === Math.floor(ticks.length / 2))
        ctx.fillText(number(x, 2), px(x), top + height + 14);
    ctx.fillText(xLabel, left + width / 2, top + height + 28);
    ctx.font = '600 12px system-ui, sans-serif';
    ctx.fillStyle = '#1f2933';
    ctx.fillText(title, left + width / 2, top - 8);
    for (const s of series) {
      ctx.strokeStyle = ctx.fillStyle = s.colour;
      ctx.lineWidth = 2;
      ctx.setLineDash(s.dashed ? [5, 4] : []);
      ctx.beginPath();
      s.x.forEach((x, i) => (i ? ctx.lineTo(px(x), py(s.y[i])) : ctx.moveTo(px(x), py(s.y[i]))));
      ctx.stroke();
      ctx.setLineDash([]);
      s.x.forEach((x, i) => {
        ctx.beginPath();
        ctx.arc(px(x), py(s.y[i]), 2.5, 0, 2 * Math.PI);
        ctx.fill();
      });
    }
  }

  function drawCurves() {
    const canvas = $('curves');
    const scale = window.devicePixelRatio || 1;
    canvas.width = Math.round(canvas.clientWidth * scale);
    canvas.height = Math.round(canvas.clientHeight * scale);
    const ctx = canvas.getContext('2d');
    ctx.setTransform(scale, 0, 0, scale, 0, 0);
    ctx.clearRect(0, 0, canvas.clientWidth, canvas.clientHeight);
    const sets = curveSets.filter((s) => s.curves && s.curves.granulometry);
    if (!sets.length) {
      canvas.dataset.drawn = 'none';
      $('curves-note').textContent = 'No granulometry stored for this mesh.';
      return;
    }
    const radii = (c, key, n) => c[key] || Array.from({length: n}, (_, i) => i + 1);
    const width = canvas.clientWidth, height = canvas.clientHeight;
    const closings = sets.some((s) => s.curves.anti_granulometry);
    const chartWidth = closings ? width / 2 - 60 : width - 70;
    const opened = sets.map((s) => ({
      x: radii(s.curves, 'open_radii', s.curves.granulometry.length),
      y: s.curves.granulometry, colour: s.colour, dashed: s.dashed,
    }));
    chart(ctx, [48, 24, chartWidth, height - 70], 'Volume left after opening',
        sets[0].curves.open_radii ? 'cube half side r / T' : 'scale', opened, 1);
    if (closings) {
      const closed = sets.filter((s) => s.curves.anti_granulometry).map((s) => ({
        x: radii(s.curves, 'close_radii', s.curves.anti_granulometry.length),
        y: s.curves.anti_granulometry, colour: s.colour, dashed: s.dashed,
      }));
      const top = Math.max(0.05, ...closed.flatMap((s) => s.y)) * 1.1;
      chart(ctx, [width / 2 + 40, 24, chartWidth, height - 70], 'Volume added by closing',
          sets[0].curves.close_radii ? 'cube half side s / L' : 'scale', closed, top);
    }
    $('curves-note').textContent = sets.map((s) => (s.dashed ? '- - ' : '— ') + s.label).join('   ') +
        '.  T = 3 volume / area, L = cbrt(volume).';
    canvas.dataset.drawn = 'true';
  }

  function setCurves(mesh) {
    curveSets = [{label: mesh.name, curves: mesh.curves, colour: '#3b6fb0', dashed: false}];
    const q = state.query;
    if (q && q.curves && q.query.name !== mesh.name)
      curveSets.push({label: 'query ' + q.query.name, curves: q.curves, colour: '#d9653b', dashed: true});
    drawCurves();
  }

  // ---- the mesh list and the selected mesh -----------------------------------------------------

  function thumbnail(id, size) {
    return el('img', {src: '/api/thumb/' + id + '.png', width: size, height: size, alt: '', loading: 'lazy'});
  }

  function renderGallery() {
    const gallery = $('gallery');
    const filter = $('filter').value.trim().toLowerCase();
    const results = new Set(state.query ? state.query.neighbours.map((n) => n.id) : []);
    gallery.replaceChildren();
    for (const m of state.meshes) {
      if (filter && !m.name.toLowerCase().includes(filter) && !m['class'].toLowerCase().includes(filter))
        continue;
      const item = el('li', {dataset: {id: m.id, name: m.name}, title: m.name},
          thumbnail(m.id, 96), el('div', {className: 'name'}, m.name),
          el('div', {className: 'cls'}, m['class'] || (m.repaired ? 'repaired' : '')));
      if (m.id === state.selected) item.classList.add('selected');
      if (results.has(m.id)) item.classList.add('result');
      item.addEventListener('click', () => select(m.id));
      gallery.append(item);
    }
  }

  function showDetails(mesh) {
    const rows = [['class', mesh['class']], ['faces', mesh.faces],
      ['volume', mesh.volume === null ? '' : number(mesh.volume, 6)],
      ['repaired', mesh.repair ? (mesh.repair.summary || 'yes') : 'no'],
      ['described in', number(mesh.seconds, 3) + ' s'], ['indexed', mesh.indexed_at + ' UTC'],
      ['status', mesh.status + (mesh.error ? ': ' + mesh.error : '')], ['file', mesh.path]];
    $('details').replaceChildren(...rows.filter(([, v]) => v !== '' && v !== undefined)
        .flatMap(([k, v]) => [el('dt', {}, k), el('dd', {}, v)]));
  }

  async function select(id) {
    state.selected = id;
    for (const item of document.querySelectorAll('#gallery li, #results li'))
      item.classList.toggle('selected', Number(item.dataset.id) === id);
    try {
      const mesh = await getJSON('/api/mesh/' + id);
      if (state.selected !== id) return;
      $('view-title').textContent = mesh.name + (mesh['class'] ? '  (' + mesh['class'] + ')' : '');
      if (!state.query) history.replaceState(null, '', '#mesh=' + encodeURIComponent(mesh.name));
      showDetails(mesh);
      setCurves(mesh);
      await showModel(id);
    } catch (e) {
      showMessage(e.message);
    }
  }

  // ---- queries ---------------------------------------------------------------------------------

  function queryParams() {
    return new URLSearchParams({kind: $('kind').value, metric: $('metric').value, k: $('k').value});
  }

  function showResults(answer) {
    state.query = answer;
    const q = answer.query;
    const head = $('query-head');
    head.replaceChildren();
    if (q.thumbnail) head.append(el('img', {src: q.thumbnail, alt: ''}));
    else if (q.id !== undefined) head.append(thumbnail(q.id, 48));
    head.append(el('span', {}, (q.upload ? 'Upload ' : '') + q.name +
        (q['class'] ? ' (' + q['class'] + ')' : '') + ': ' + answer.kind + ', ' + answer.metric));
    const list = $('results');
    list.replaceChildren(...answer.neighbours.map((n) => {
      const item = el('li', {dataset: {id: n.id, name: n.name, distance: n.distance}},
          el('span', {className: 'rank'}, n.rank), thumbnail(n.id, 48),
          el('span', {}, el('div', {className: 'name'}, n.name), el('div', {className: 'cls'}, n['class'])),
          el('span', {className: 'distance'}, number(n.distance, 5)));
      if (q['class'] && n['class'] === q['class']) item.classList.add('same');
      item.addEventListener('click', () => select(n.id));
      return item;
    }));
    list.dataset.count = answer.neighbours.length;
    $('query-status').textContent = answer.neighbours.length + ' neighbours in ' +
        number(answer.seconds, 3) + ' s';
    renderGallery();
    document.body.dataset.query = 'done';
  }

  async function runQuery(target) {
    showMessage('');
    $('query-status').textContent = 'Querying…';
    document.body.dataset.query = 'running';
    const params = queryParams();
    if (target.id !== undefined) params.set('id', target.id);
    else params.set('name', target.name);
    try {
      showResults(await getJSON('/api/query?' + params));
      const name = state.query.query.name;
      history.replaceState(null, '', '#query=' + encodeURIComponent(name) + '&' + queryParams());
      if (state.selected !== state.query.query.id) await select(state.query.query.id);
      else setCurves(await getJSON('/api/mesh/' + state.selected));
    } catch (e) {
      $('query-status').textContent = '';
      document.body.dataset.query = 'error';
      showMessage(e.message);
    }
  }

  async function upload(event) {
    event.preventDefault();
    const file = $('upload-file').files[0];
    if (!file) return showMessage('Choose a mesh file to upload first.');
    if (file.size > state.info.max_upload_bytes)
      return showMessage(file.name + ' is larger than the upload limit of ' +
          number(state.info.max_upload_bytes / 1048576, 3) + ' MiB.');
    showMessage('');
    const button = event.target.querySelector('button');
    button.disabled = true;
    $('query-status').textContent = 'Describing ' + file.name + ' with the index\'s pipeline…';
    const form = new FormData();
    form.append('mesh', file, file.name);
    try {
      showResults(await getJSON('/api/query?' + queryParams(), {method: 'POST', body: form}));
      if (state.selected !== null) setCurves(await getJSON('/api/mesh/' + state.selected));
    } catch (e) {
      $('query-status').textContent = '';
      showMessage(e.message);
    } finally {
      button.disabled = false;
    }
  }

  // ---- failures and start ----------------------------------------------------------------------

  function renderFailures(failures) {
    $('failed-count').textContent = '(' + failures.length + ')';
    $('failures').tBodies[0].replaceChildren(...failures.map((f) => {
      const name = el('td', {}, f.name);
      if (f.readable) {
        name.style.cursor = 'pointer';
        name.title = 'Show the mesh as read';
        name.addEventListener('click', () => select(f.id));
      }
      return el('tr', {dataset: {id: f.id}}, name, el('td', {className: 'error'}, f.error),
          el('td', {className: 'path'}, f.path));
    }));
    if (!failures.length)
      $('failures').tBodies[0].append(el('tr', {}, el('td', {colspan: 3}, 'None: every mesh was described.')));
  }

  function fillSelect(select, values, chosen) {
    select.replaceChildren(...values.map((v) => el('option', {value: v}, v)));
    if (values.includes(chosen)) select.value = chosen;
  }

  // #query=NAME[&kind=&metric=&k=] selects NAME and runs its query; #mesh=NAME shows NAME; without
  // either, the first mesh is shown.
  async function applyAddress() {
    const hash = new URLSearchParams(location.hash.slice(1));
    for (const key of ['kind', 'metric']) {
      const value = hash.get(key);
      if (value && [...$(key).options].some((o) => o.value === value)) $(key).value = value;
      else if (value) showMessage(key + ' ' + value + ': not one this index offers.');
    }
    if (hash.get('k')) $('k').value = hash.get('k');
    const wanted = hash.get('query') || hash.get('mesh');
    const mesh = wanted ? state.byName.get(wanted) : state.meshes[0];
    if (wanted && !mesh) showMessage(wanted + ': no indexed mesh has this name.');
    if (hash.get('query') && mesh) await runQuery({name: mesh.name});
    else if (mesh) await select(mesh.id);
  }

  async function start() {
    initView();
    try {
      const [info, meshes, failures] = await Promise.all(
          [getJSON('/api/info'), getJSON('/api/meshes'), getJSON('/api/failures')]);
      state.info = info;
      state.meshes = meshes;
      for (const m of meshes) state.byName.set(m.name, m);
      $('index-name').textContent = info.index;
      $('index-stats').textContent = info.meshes + ' meshes, ' + info.failed + ' failed';
      document.title = info.index + ' — morphex';
      const kinds = info.kinds.length ? info.kinds : [info.default_kind];
      fillSelect($('kind'), kinds, info.default_kind);
      fillSelect($('metric'), info.metrics, info.default_metric);
      $('k').max = info.max_neighbours;
      $('upload-note').textContent = info.formats.join(', ') + ' (or .gz of them), up to ' +
          number(info.max_upload_bytes / 1048576, 3) + ' MiB; described with the index\'s own ' +
          'pipeline, then deleted.';
      $('footer').textContent = 'morphex ' + info.version + ' serving ' + info.index +
          '. The page only reads the index.';
      renderGallery();
      renderFailures(failures);
      document.body.dataset.ready = 'true';
      await applyAddress();
    } catch (e) {
      showMessage(e.message);
    }
  }

  $('filter').addEventListener('input', renderGallery);
  $('query-form').addEventListener('submit', (event) => {
    event.preventDefault();
    if (state.selected !== null) runQuery({id: state.selected});
    else showMessage('Select a mesh to query first.');
  });
  $('upload-form').addEventListener('submit', upload);
  // An address typed or pasted while the page is open (the page's own updates do not fire this).
  window.addEventListener('hashchange', () => {
    if (state.info) applyAddress();
  });
  start();
})();
