// The page around the viewer (accelviz.js, the native viewer compiled by emscripten):
//  * the URL becomes the viewer's command line, e.g.
//      accelviz.html?scene=bunny&structure=kdtree&param=traversal=recursive
//      accelviz.html?playlist=lecture&state=5        accelviz.html?script=my_script.txt
//    (the keys: script, scene, structure, param (repeatable), playlist, state, ui=off,
//    memory-limit, fetch (repeatable: files to copy from the server first));
//  * files the URL names are fetched from the served folder into the page's file system,
//    under /app, the stand-in for the repository root (the working directory);
//  * everything the viewer prints goes to the console as "accelviz: LINE";
//  * "Open mesh..." hands the chosen file to the viewer exactly as a drop onto the canvas.
'use strict';

(function () {
  const params = new URLSearchParams(window.location.search);
  const canvas = document.getElementById('canvas');
  const status = document.getElementById('status');
  let ready = false;

  function showStatus(text) {
    status.textContent = text;
    status.style.display = text ? 'block' : 'none';
  }
  function prefixed(line) {
    return line.startsWith('accelviz: ') ? line : 'accelviz: ' + line;
  }

  // A path inside the served folder: relative, without '..' (the page reads nothing else).
  function checkServedPath(key, path) {
    if (!path || path.startsWith('/') || path.split('/').includes('..') || /^[a-z]+:/i.test(path))
      throw new Error(key + '=' + path + ': expected a path inside the page\'s folder');
    return path;
  }
  function exists(path) {
    return FS.analyzePath(path).exists;
  }
  async function fetchIntoFs(key, path) {
    checkServedPath(key, path);
    if (exists('/app/' + path)) return path;  // bundled
    const response = await fetch(path);
    if (!response.ok) throw new Error(key + '=' + path + ': the server answered ' + response.status);
    const data = new Uint8Array(await response.arrayBuffer());
    const dir = path.split('/').slice(0, -1).join('/');
    if (dir) FS.mkdirTree('/app/' + dir);
    FS.writeFile('/app/' + path, data);
    return path;
  }

  // scene=: procedural:NAME, a bundled mesh by name (bunny, teapot, ...), a procedural
  // scene by name (cornell, stadium, ...), or a file of the served folder.
  async function sceneArgument(name) {
    if (name.startsWith('procedural:')) return name;
    for (const [dir, arg] of [['/shared/scenes/', '../shared/scenes/'], ['/app/scenes/', 'scenes/']]) {
      if (exists(dir + name + '.obj')) return arg + name + '.obj';
      if (exists(dir + name + '.scene2d')) return arg + name + '.scene2d';  // the blackboard's
      if (exists(dir + name)) return arg + name;
    }
    if (!name.includes('.') && !name.includes('/')) return 'procedural:' + name;
    return fetchIntoFs('scene', name);
  }
  async function playlistArgument(name) {
    if (exists('/app/scenes/' + name + '.playlist')) return 'scenes/' + name + '.playlist';
    return fetchIntoFs('playlist', name);
  }

  async function commandLine() {
    const args = [];
    for (const path of params.getAll('fetch')) await fetchIntoFs('fetch', path);
    if (params.has('script')) args.push('--script', await fetchIntoFs('script', params.get('script')));
    if (params.has('scene')) args.push(await sceneArgument(params.get('scene')));
    if (params.has('structure')) args.push('--structure', params.get('structure'));
    for (const p of params.getAll('param')) args.push('--param', p);
    if (params.has('playlist')) args.push('--playlist', await playlistArgument(params.get('playlist')));
    if (params.has('state')) args.push('--state', params.get('state'));
    if (params.get('ui') === 'off') args.push('--no-ui');
    if (params.has('memory-limit')) args.push('--memory-limit', params.get('memory-limit'));
    // The window fills the page (a script's `size` command still sets its own).
    const w = Math.max(64, Math.min(8192, window.innerWidth)), h = Math.max(64, Math.min(8192, window.innerHeight));
    args.push('--size', w + 'x' + h);
    return args;
  }

  window.Module = {
    canvas: canvas,
    print: (line) => {
      console.log(prefixed(line));
      if (line === 'ready') {
        ready = true;
        showStatus('');
        // For scripts/bench_web.py: when the viewer was up, and its first frame shown.
        window.accelvizReadyMs = performance.now();
        requestAnimationFrame(() => { window.accelvizFirstFrameMs = performance.now(); });
      }
    },
    printErr: (line) => {
      console.error(prefixed(line));
      if (!ready) showStatus(line);  // the page would stay empty: say why
    },
    // emscripten's own status lines: only the download of the bundled files is worth showing.
    setStatus: (text) => { if (!ready && text.startsWith('Downloading')) showStatus('Loading accelviz: ' + text); },
    onRuntimeInitialized: async () => {
      FS.mkdirTree('/app');
      FS.chdir('/app');
      let args;
      try {
        args = await commandLine();
      } catch (e) {
        console.error(prefixed(e.message));
        showStatus(e.message);
        return;
      }
      Module.callMain(args);
    },
  };
  // The viewer's own lines use print(); this one is the page's.
  window.addEventListener('error', (e) => showStatus('accelviz stopped: ' + e.message));

  // The window follows the page's size (not while a script owns the size).
  window.addEventListener('resize', () => {
    if (params.has('script') || typeof GLFW === 'undefined' || !GLFW.active) return;
    GLFW.setWindowSize(GLFW.active.id, Math.max(64, window.innerWidth), Math.max(64, window.innerHeight));
  });

  // "Open mesh...": the file goes the way a dropped one does (GLFW's drop callback).
  document.getElementById('file').addEventListener('change', (e) => {
    const file = e.target.files[0];
    if (!file) return;
    const transfer = new DataTransfer();
    transfer.items.add(file);
    canvas.dispatchEvent(new DragEvent('drop', {dataTransfer: transfer, bubbles: true, cancelable: true}));
    e.target.value = '';
  });
})();
