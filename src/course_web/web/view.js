// The live view: the frames of /ws drawn by scene.js, and the teleops' keys sent back, from the
// keyboard or from the on-screen pads of a touch screen. Plain JavaScript, no library: every file
// comes from this server.
'use strict';
(function () {
  const KEYS = new Set(['ArrowUp', 'ArrowDown', 'ArrowLeft', 'ArrowRight', 'w', 'a', 's', 'd', 'x', ' ']);
  // A held pad button repeats as a held key does: after a pause, about 30 times a second, and only
  // the one pressed last (course_web.pacing lets a page send 40 keys a second).
  const REPEAT_DELAY_MS = 500;
  const REPEAT_PERIOD_MS = 33;

  const $ = (id) => document.getElementById(id);
  let socket = null;
  let queue = Promise.resolve();

  function setStatus(text) { $('status').textContent = text; }

  function connect() {
    socket = new WebSocket((location.protocol === 'https:' ? 'wss://' : 'ws://') + location.host + '/ws');
    socket.onopen = () => setStatus('connected');
    socket.onclose = () => {
      setStatus('disconnected: trying again…');
      queue = queue.then(() => courseScene.clear());
      setTimeout(connect, 1000);
    };
    socket.onmessage = (event) => {
      const frame = JSON.parse(event.data);
      queue = queue.then(() => courseScene.show(frame)).catch((error) => console.error(error));
    };
  }

  function sendKey(key) {
    if (socket && socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify({key: key}));
  }

  // ---------------------------------------------------------------- keys
  document.addEventListener('keydown', (event) => {
    if (event.ctrlKey || event.altKey || event.metaKey) return;
    const key = event.key.length === 1 ? event.key.toLowerCase() : event.key;
    if (!KEYS.has(key)) return;
    event.preventDefault();
    sendKey(key);  // a held key repeats: the browser sends keydown again
  });

  // ---------------------------------------------------------------- pads
  // Each button carries the key it presses (data-key): a touch sends it as the key would, holding
  // repeats it. view.css shows the pads on a touch screen only.
  let repeating = null;  // {button, timer} of the button that repeats

  function stopRepeating() {
    if (repeating) { clearTimeout(repeating.timer); repeating = null; }
  }

  function press(button) {
    button.classList.add('held');
    sendKey(button.dataset.key);
    stopRepeating();
    const entry = {button: button, timer: null};
    const again = () => { sendKey(button.dataset.key); entry.timer = setTimeout(again, REPEAT_PERIOD_MS); };
    entry.timer = setTimeout(again, REPEAT_DELAY_MS);
    repeating = entry;
  }

  function release(button) {
    button.classList.remove('held');
    if (repeating && repeating.button === button) stopRepeating();
  }

  for (const button of document.querySelectorAll('.pad button[data-key]')) {
    button.addEventListener('pointerdown', (event) => {
      if (event.button !== 0) return;
      event.preventDefault();  // no focus, no text selection, no mouse events after the touch
      button.setPointerCapture(event.pointerId);  // a finger sliding off still releases this button
      press(button);
    });
    for (const type of ['pointerup', 'pointercancel', 'lostpointercapture']) {
      button.addEventListener(type, () => release(button));
    }
    button.addEventListener('contextmenu', (event) => event.preventDefault());  // a long press
  }
  // A page that loses the screen stops repeating, as a window that loses the keyboard does.
  const releaseAll = () => { for (const b of document.querySelectorAll('.pad .held')) release(b); stopRepeating(); };
  window.addEventListener('blur', releaseAll);
  document.addEventListener('visibilitychange', releaseAll);
  // A touch screen that does not say so (pointer: fine) shows the pads from its first touch.
  window.addEventListener('touchstart', () => document.documentElement.classList.add('touch'),
                          {once: true, passive: true});

  connect();
}());
