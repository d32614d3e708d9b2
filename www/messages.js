// Messages next to their cause: one message element (`#message`), moved
// beside the control that caused it (after the field, row or panel that
// holds the control), or beside the drawing (`#stage-notes`) when the
// drawing caused it or nothing is named. So a refusal shows where the
// user is looking, not under a control off screen.

/** What holds a control: the block the message goes after. */
const HOLDER = '.field, .place, .row, .takeaway, .tour, li, details, .bench-actions';

/**
 * `messenger(root)` for the message element `#message` under `root`:
 * `{ show(text, kind, sticky, near), clear(), attempt(fn, kind, near) }`.
 * `kind` is 'error', 'warn' or 'info'; a message not `sticky` goes after
 * six seconds; `near` is the element that caused it.
 */
export function messenger(root) {
  const message = root.querySelector('#message');
  const notes = root.querySelector('#stage-notes');
  let timer = 0;

  function place(near) {
    if (!message) return;
    const stage = near && near.closest && near.closest('.stage-card');
    const holder = near && near.closest && !stage ? near.closest(HOLDER) : null;
    if (holder && holder !== message.previousElementSibling) holder.after(message);
    else if (!holder && notes && message.parentElement !== notes) notes.append(message);
  }

  function show(text, kind = 'error', sticky = false, near = undefined) {
    if (!message) return;
    place(near);
    message.textContent = text;
    message.dataset.kind = kind;
    message.hidden = false;
    clearTimeout(timer);
    if (!sticky) timer = setTimeout(() => (message.hidden = true), 6000);
  }

  function clear() {
    if (message) message.hidden = true;
  }

  function attempt(fn, kind = 'error', near = undefined, describe = String) {
    try {
      fn();
      return true;
    } catch (e) {
      show(describe(e), kind, false, near);
      return false;
    }
  }

  return { show, clear, attempt };
}

/**
 * Settings applied one at a time, each refused on its own so that no
 * refusal hides another: `one(key, fn)` runs `fn` and keeps `key: why` of
 * a refusal (`describe` words the error) in `refused`, which starts with
 * `already` (the problems found before).
 */
export function oneByOne(describe, already = []) {
  const refused = [...already];
  const one = (key, fn) => {
    try {
      fn();
    } catch (e) {
      refused.push(`${key}: ${describe(e)}`);
    }
  };
  return { refused, one };
}
