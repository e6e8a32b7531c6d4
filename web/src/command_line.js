// The command line: one action line of the console's script vocabulary (docs/console.md) sent
// on Enter, its `result` shown beside it. Buttons report their results here too, so the
// operator always sees what the last action did. Up / Down walk the lines sent before.

const kHistory = 100;

export class CommandLine {
  constructor(form, send) {
    this.input = form.querySelector('[data-telear="command"]');
    this.output = form.querySelector('[data-role="result"]');
    this.send = send;
    this.history = [];
    this.cursor = 0;
    form.addEventListener('submit', (event) => {
      event.preventDefault();
      const line = this.input.value.trim();
      if (line === '') return;
      this.history.push(line);
      if (this.history.length > kHistory) this.history.shift();
      this.cursor = this.history.length;
      this.input.value = '';
      send(line);
    });
    this.input.addEventListener('keydown', (event) => {
      if (event.key !== 'ArrowUp' && event.key !== 'ArrowDown') return;
      event.preventDefault();
      this.cursor = Math.max(0, Math.min(this.history.length, this.cursor + (event.key === 'ArrowUp' ? -1 : 1)));
      this.input.value = this.history[this.cursor] ?? '';
    });
  }

  showPending(line) {
    this.output.textContent = `${line}: …`;
    this.output.className = 'result';
  }

  showResult(result) {
    this.output.textContent = `${result.line}: ${result.ok ? 'ok' : 'failed'}${result.message ? ` – ${result.message}` : ''}`;
    this.output.className = `result ${result.ok ? 'ok' : 'failed'}`;
  }
}
