// window.telear: what scripts and the browser tests (tests/web/) read and call. Read-only
// views of the page's state plus a few read-backs of the drawing pipeline; nothing here
// changes what the operator sees.
//
//   state, cameras, model, hello     the last message of each type
//   framesShown                      video frames put on the eyes' video layers so far (both
//                                    eyes = one frame; its `shown` report follows at the next
//                                    animation frame, once the browser has composited it)
//   lastResult                       the last command's {id, ok, message, line}
//   lookUpTablesLoaded               how many eyes have their lens look-up table (0..2)
//   connection                       the connection text as shown
//   xrViews                          [{eye, projection[16], view[16], viewport}] of the last XR frame
//   onState(fn) -> unsubscribe       fn(state) for every state message, as it arrives
//   command(line) -> Promise<result> the same path as the command line and the buttons
//   ghostOnly(eye) -> Promise<PNG data URL>   the ghost alone, opaque, solid, on transparent
//                                    black, W x H, through the live pipeline (region + lens)
//   videoOnly(eye) -> Promise<{drawn, decoded}>  the eye's video layer read back (the newest
//                                    decoded frame drawn into it first, as the next animation
//                                    frame would), and the same decoded frame drawn by a fresh
//                                    2-D canvas: PNG data URLs, W x H

export function installDebugHooks(app) {
  const listeners = new Set();
  const eyeIndex = (eye) => {
    const i = {left: 0, right: 1}[eye];
    if (i === undefined) throw new Error(`eye '${eye}': expected 'left' or 'right'`);
    return i;
  };
  const hooks = {
    state: null,
    cameras: null,
    model: null,
    hello: null,
    framesShown: 0,
    lastResult: null,
    lookUpTablesLoaded: 0,
    connection: 'disconnected',
    xrViews: null,
    onState(fn) {
      listeners.add(fn);
      return () => listeners.delete(fn);
    },
    command: (line) => app.sendLine(line),
    ghostOnly: async (eye) => app.eyes[eyeIndex(eye)].ghostOnly(app.armScene),
    videoOnly: async (eye) => {
      const i = eyeIndex(eye);
      return app.eyes[i].videoOnly(app.video.bitmap(i));
    },
  };
  window.telear = hooks;
  return {
    hooks,
    stateArrived(state) {
      hooks.state = state;
      for (const fn of listeners) {
        try {
          fn(state);
        } catch (e) {
          console.warn('telear: an onState listener threw:', e);
        }
      }
    },
  };
}
