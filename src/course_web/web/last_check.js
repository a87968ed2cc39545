// "Your last check": what `rosrun course_grader check LAB` showed in its terminal (check/LAB/STAMP/
// check.json, made by course_grader.check), its pictures and a link to play each run, from the
// server's check/ (course_web.last_check). A newer check replaces it within seconds. Texts go in
// with textContent only. Plain JavaScript, no library.
'use strict';
(function () {
  const POLL_MS = 3000;
  const $ = (id) => document.getElementById(id);
  // What tests read: the check shown ('LAB/STAMP', or null) and any error.
  const state = {check: null, error: null};
  window.courseLastCheck = state;

  function element(tag, text, className) {
    const made = document.createElement(tag);
    if (text !== undefined) made.textContent = text;
    if (className) made.className = className;
    return made;
  }

  const points = (c) => `${c.points} / ${c.max_points}`;

  function criterionItem(c) {
    const item = element('li', undefined, c.hidden ? 'hidden-criterion' : (c.passed ? 'pass' : 'fail'));
    item.dataset.id = c.id;
    const head = element('div', undefined, 'criterion');
    head.appendChild(element('span', c.hidden ? '----' : (c.passed ? 'PASS' : 'FAIL'), 'verdict'));
    head.appendChild(element('span', c.id, 'id'));
    head.appendChild(element('span', c.hidden ? c.hidden : points(c), 'points'));
    head.appendChild(element('span', c.title, 'title'));
    item.appendChild(head);
    if (!c.hidden && c.reason) item.appendChild(element('p', c.reason, 'reason'));
    for (const hint of c.hidden ? [] : c.hints) item.appendChild(element('p', hint, 'hint'));
    return item;
  }

  function show(check, summary) {
    const base = 'check/' + check.split('/').map(encodeURIComponent).join('/') + '/';
    const folder = base + encodeURIComponent(summary.folder) + '/';
    $('check-package-line').hidden = false;
    $('check-lab').textContent = summary.lab;
    $('check-when').textContent = summary.when;
    $('check-package').textContent = summary.package;
    $('check-total').textContent = summary.total;
    $('check-error').textContent = summary.error || '';
    $('check-error').hidden = !summary.error;
    $('check-criteria').replaceChildren(...summary.criteria.map(criterionItem));
    $('check-notes').replaceChildren(...summary.notes.map((note) => element('li', note)));
    $('check-counts').textContent = summary.counts;
    $('check-pictures').replaceChildren(...summary.pictures.map((name) => {
      const figure = element('figure');
      const picture = element('img');
      picture.src = folder + encodeURIComponent(name);
      picture.alt = name;
      figure.appendChild(picture);
      figure.appendChild(element('figcaption', name));
      return figure;
    }));
    $('check-runs').replaceChildren(...summary.runs.map((run) => {
      const item = element('li');
      if (run.error) {
        item.textContent = `${run.run}: cannot be replayed (${run.error})`;
      } else {
        const link = element('a', `${run.run}, played again`);
        // The player finds the run at ../FOLDER/RUN.replay.js, as in the teacher's report.
        link.href = `${base}_player/replay.html#${encodeURIComponent(summary.folder)}/${encodeURIComponent(run.run)}`;
        item.appendChild(link);
      }
      return item;
    }));
    $('check-runs-part').hidden = summary.runs.length === 0;
    $('last-check').hidden = false;
    state.check = check;
  }

  // A check.json that is not what the check writes (edited by hand, or by another version of the
  // course): said in the panel, the rest of it emptied, and not read again until a newer check.
  function unreadable(check, error) {
    const [lab, stamp] = check.split('/');
    for (const id of ['check-package', 'check-total', 'check-counts']) $(id).textContent = '';
    $('check-package-line').hidden = true;
    $('check-when').textContent = stamp;
    for (const id of ['check-criteria', 'check-notes', 'check-pictures', 'check-runs']) $(id).replaceChildren();
    $('check-lab').textContent = lab;
    $('check-error').textContent = `This check (${check}) cannot be shown: its check.json is not what ` +
      `the check writes (${error.message}). Run \`rosrun course_grader check ${lab}\` again.`;
    $('check-error').hidden = false;
    $('check-runs-part').hidden = true;
    $('last-check').hidden = false;
    state.check = check;
  }

  async function refresh() {
    try {
      const latest = await (await fetch('check/latest', {cache: 'no-store'})).json();
      if (latest.check && latest.check !== state.check) {
        const answer = await fetch('check/' + latest.check.split('/').map(encodeURIComponent).join('/') + '/check.json',
                                   {cache: 'no-store'});
        if (answer.ok) {  // not yet written: the next poll
          const text = await answer.text();
          try {
            show(latest.check, JSON.parse(text));
          } catch (error) {
            unreadable(latest.check, error);
          }
        }
      }
      state.error = null;
    } catch (error) {
      state.error = String(error);  // the server went away: the next poll tries again
    }
    setTimeout(refresh, POLL_MS);
  }

  refresh();
}());
