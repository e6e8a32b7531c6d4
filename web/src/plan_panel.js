// The Plan panel and the ghost's jog buttons (docs/console.md, "Plan", "Ghost"). Every button
// sends an action line of the console's script vocabulary, the same line the command line
// would send, so the server runs one code path (console::apply_action) whatever was clicked.
// The panel shows the state's plan and joints; it keeps no plan of its own.

const kPlanActions = [
  ['Take control', 'take-control'],
  ['Release control', 'release-control'],
  ['Add waypoint (1 s)', 'plan add 1.0'],
  ['Clear plan', 'plan clear'],
  ['Preview', 'preview play'],
  ['Stop preview', 'preview stop'],
  ['Validate', 'validate'],
  ['Execute', 'execute'],
  ['Cancel', 'cancel'],
  ['Reset e-stop', 'reset-estop'],
];
const kGhostActions = [['Ghost = real', 'ghost reset']];
const kJogStepDeg = 5;

function button(label, line, send) {
  const b = document.createElement('button');
  b.type = 'button';
  b.textContent = label;
  b.dataset.line = line;
  b.addEventListener('click', () => send(line));
  return b;
}

function degrees(value) {
  return Number.isFinite(value) ? `${value.toFixed(1)}°` : '–';
}

export class PlanPanel {
  constructor(root, send) {
    this.root = root;
    this.send = send;
    this.facts = root.querySelector('[data-role="plan-facts"]');
    this.waypoints = root.querySelector('[data-role="waypoints"]');
    this.joints = root.querySelector('[data-role="joints"] tbody');
    this.jointCells = [];
    this.waypointsKey = '';
    root.querySelector('[data-role="plan-actions"]').append(...kPlanActions.map(([l, line]) => button(l, line, send)));
    root.querySelector('[data-role="ghost-actions"]').append(...kGhostActions.map(([l, line]) => button(l, line, send)));
  }

  // One row per joint: name, ghost, real, and the ghost's jog buttons (joints count from 1).
  setJoints(names) {
    this.joints.replaceChildren();
    this.jointCells = names.map((name, i) => {
      const tr = document.createElement('tr');
      const label = document.createElement('td');
      label.textContent = name || `joint ${i + 1}`;
      const ghost = document.createElement('td');
      ghost.className = 'num';
      ghost.title = 'ghost';
      const real = document.createElement('td');
      real.className = 'num';
      real.title = 'reported';
      const jog = document.createElement('td');
      jog.append(button(`−${kJogStepDeg}°`, `ghost joint ${i + 1} -${kJogStepDeg}deg`, this.send),
                 button(`+${kJogStepDeg}°`, `ghost joint ${i + 1} +${kJogStepDeg}deg`, this.send));
      tr.append(label, ghost, real, jog);
      this.joints.append(tr);
      return {ghost, real};
    });
  }

  update(state) {
    const ghostQ = Array.isArray(state.ghost_q_deg) ? state.ghost_q_deg : [];
    if (this.jointCells.length === 0 && ghostQ.length > 0) {
      this.setJoints(ghostQ.map((_, i) => `joint ${i + 1}`));
    }
    const realQ = Array.isArray(state.real_q_deg) ? state.real_q_deg : [];
    this.jointCells.forEach((cells, i) => {
      const g = degrees(ghostQ[i]);
      const r = degrees(realQ[i]);
      if (cells.ghost.textContent !== g) cells.ghost.textContent = g;
      if (cells.real.textContent !== r) cells.real.textContent = r;
    });

    const plan = state.plan || {};
    const short = (hash) => (hash ? String(hash).slice(0, 10) : '–');
    const activity = plan.executing ? 'executing' : plan.previewing ? 'previewing' : 'idle';
    const facts = `${(plan.waypoints || []).length} waypoints, ${Number(plan.duration_s || 0).toFixed(2)} s, ${activity}` +
                  `; last: ${plan.last_result || '–'}; hash ${short(plan.hash)}, previewed ${short(plan.previewed_hash)}, ` +
                  `executed ${short(plan.executed_hash)}`;
    if (this.facts.textContent !== facts) this.facts.textContent = facts;

    const waypoints = Array.isArray(plan.waypoints) ? plan.waypoints : [];
    const key = JSON.stringify(waypoints);
    if (key !== this.waypointsKey) {
      this.waypointsKey = key;
      this.waypoints.replaceChildren(...waypoints.map((w) => {
        const li = document.createElement('li');
        const q = Array.isArray(w.q_deg) ? w.q_deg.map((v) => Number(v).toFixed(1)).join(', ') : '';
        li.textContent = `${w.label ? `${w.label}: ` : ''}${Number(w.duration_s || 0).toFixed(2)} s  [${q}]`;
        return li;
      }));
    }
  }
}
