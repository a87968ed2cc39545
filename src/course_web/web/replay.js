// A run of the grader played back (report.html shows this page in a frame per run): the run's frames,
// made by course_grader.replay as the live view's server makes them, drawn by scene.js as the live
// view draws them. Play/pause, speed, a time slider with the moments the checks judged (the marks).
// The data comes as a script, ../FOLDER/RUN.replay.js (a page from file:// cannot fetch()), named
// by this page's #FOLDER/RUN. Plain JavaScript, no library, nothing from the network.
'use strict';
(function () {
  const $ = (id) => document.getElementById(id);
  const scene = window.courseScene;
  // What tests read: the run's time shown, the frame drawn, whether it plays, the mark shown.
  const state = {time: 0, index: -1, playing: false, speed: 1, duration: 0, mark: null, error: null};
  window.courseReplayState = state;
  let data = null;
  let keyIndices = [];        // the frames from which a seek may start (whole frames), ascending
  const keyFrames = new Map();
  let wanted = 0;             // the time to show; drawing catches up with it, one frame at a time
  let drawing = false;

  function fail(text) {
    state.error = text;
    $('waiting').textContent = text;
    $('waiting').hidden = false;
    tellHeight();
  }

  // ------------------------------------------------------------------ loading
  function load() {
    const parts = location.hash.slice(1).split('/').map(decodeURIComponent);
    const named = (part) => part && part !== '.' && part !== '..' && !/[\/\\]/.test(part);
    if (parts.length !== 2 || !parts.every(named)) { fail('No run named (expected replay.html#FOLDER/RUN).'); return; }
    const script = document.createElement('script');
    script.src = '../' + parts.map(encodeURIComponent).join('/') + '.replay.js';
    script.onload = () => (window.courseReplay ? start(window.courseReplay) : fail('The run\'s file holds no replay.'));
    script.onerror = () => fail('The run\'s file ' + parts.join('/') + '.replay.js is missing: grade again to make it.');
    document.body.appendChild(script);
  }

  function start(replay) {
    data = replay;
    state.duration = data.duration;
    keyFrames.set(0, data.frames[0]);
    for (const [index, frame] of data.keys) keyFrames.set(index, frame);
    keyIndices = Array.from(keyFrames.keys()).sort((a, b) => a - b);
    const slider = $('slider');
    slider.max = String(data.duration);
    drawMarks();
    $('player').hidden = false;
    seek(0);
    tellHeight();
  }

  // ------------------------------------------------------------------ drawing
  // The last frame at or before t (the first one before it: it is the run's first picture).
  function indexAt(t) {
    let low = 0, high = data.times.length - 1;
    while (low < high) {
      const middle = (low + high + 1) >> 1;
      if (data.times[middle] <= t) low = middle; else high = middle - 1;
    }
    return low;
  }

  // Frame `target` drawn: onwards from the one shown, or from the last whole frame before it (a
  // whole frame replaces all that the scene shows, as for a page that connects to the live view).
  async function drawUpTo(target) {
    let key = keyIndices[0];
    for (const index of keyIndices) if (index <= target) key = index;
    let next;
    if (state.index >= key && state.index <= target) next = state.index + 1;
    else { await scene.show(keyFrames.get(key)); next = key + 1; state.index = key; }
    for (; next <= target; next++) { await scene.show(data.frames[next]); state.index = next; }
  }

  async function catchUp() {
    if (drawing || !data) return;
    drawing = true;
    try {
      while (state.index !== indexAt(wanted)) await drawUpTo(indexAt(wanted));
    } catch (error) {
      console.error(error);
    } finally {
      drawing = false;
    }
  }

  function seek(t) {
    state.time = Math.min(Math.max(0, t), state.duration);
    wanted = state.time;
    showTime();
    catchUp();
  }

  // ------------------------------------------------------------------ controls
  function showTime() {
    $('slider').value = String(state.time);
    $('clock').textContent = state.time.toFixed(1) + ' / ' + state.duration.toFixed(1) + ' s';
    let mark = null;
    data.marks.forEach((m, i) => { if (m.t <= state.time + 1e-6) mark = i; });
    if (mark !== state.mark) {
      state.mark = mark;
      const m = mark === null ? null : data.marks[mark];
      $('mark-now').textContent = m ? `${m.t.toFixed(1)} s: ${m.what}` + (m.criterion ? ` (${m.criterion})` : '') : '';
      document.querySelectorAll('#marks li, #ticks span').forEach((el) => el.classList.toggle('now', Number(el.dataset.mark) === mark));
    }
  }

  function drawMarks() {
    const ticks = $('ticks'), list = $('marks');
    data.marks.forEach((m, i) => {
      const where = data.duration > 0 ? Math.min(100, 100 * m.t / data.duration) : 0;
      const tick = document.createElement('span');
      tick.dataset.mark = i;
      tick.style.left = where + '%';
      tick.textContent = String(i + 1);
      tick.title = m.what;
      ticks.appendChild(tick);
      const item = document.createElement('li');
      item.dataset.mark = i;
      const button = document.createElement('button');
      button.type = 'button';
      button.textContent = `${m.t.toFixed(1)} s: ${m.what}` + (m.criterion ? ` (${m.criterion})` : '');
      button.addEventListener('click', () => { pause(); seek(m.t); });
      item.appendChild(button);
      list.appendChild(item);
    });
  }

  let last = null;
  function step(now) {
    if (!state.playing) { last = null; return; }
    if (last !== null) {
      const t = state.time + (now - last) / 1000 * state.speed;
      seek(t);
      if (t >= state.duration) { pause(); return; }
    }
    last = now;
    requestAnimationFrame(step);
  }

  function play() {
    if (state.time >= state.duration) seek(0);
    state.playing = true;
    $('play').textContent = '❚❚';
    $('play').setAttribute('aria-label', 'pause');
    last = null;
    requestAnimationFrame(step);
  }

  function pause() {
    state.playing = false;
    $('play').textContent = '▶';
    $('play').setAttribute('aria-label', 'play');
  }

  $('play').addEventListener('click', () => (state.playing ? pause() : play()));
  $('slider').addEventListener('input', (event) => seek(Number(event.target.value)));
  document.querySelectorAll('.speeds button').forEach((button) => button.addEventListener('click', () => {
    state.speed = Number(button.dataset.speed);
    document.querySelectorAll('.speeds button').forEach((b) => {
      b.classList.toggle('chosen', b === button);
      b.setAttribute('aria-pressed', String(b === button));
    });
  }));
  document.addEventListener('keydown', (event) => {
    if (event.key === ' ' && event.target.tagName !== 'BUTTON') { event.preventDefault(); state.playing ? pause() : play(); }
  });

  // The page that holds this one in a frame sizes the frame to it (report.html listens).
  function tellHeight() {
    if (window.parent !== window) window.parent.postMessage({courseReplayHeight: document.documentElement.scrollHeight}, '*');
  }
  new ResizeObserver(tellHeight).observe(document.body);

  load();
}());
