// casmap view: asks the server what DIR holds and shows the matching page.
'use strict';

(async () => {
  const main = document.getElementById('main');
  try {
    const info = await cm.json('/api/info');
    document.title = `casmap view: ${info.name} (${info.kind})`;
    document.getElementById('title').textContent = 'casmap view: ' + info.name;
    document.getElementById('kind').textContent = info.kind;
    document.getElementById('status').remove();
    const show = { bench: cm.showBench, sweep: cm.showSweep, dataset: cm.showDataset, live: cm.showLive }[info.kind];
    await show(main);
    document.body.dataset.ready = 'true';
  } catch (e) {
    cm.error(main, e);
    document.body.dataset.ready = 'error';
  }
})();
