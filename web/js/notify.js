// Errors shown where the user acted: every control group has an error line (an element with
// class "error" and role "alert") beside it; an action's failure goes there and its next
// success clears it.

const $ = (id) => document.getElementById(id);

/**
 * Shows `message` in the error line `id`, or hides the line for null.
 * @param {string} id @param {string|null} message
 */
export function showError(id, message) {
  const line = $(id);
  line.hidden = !message;
  line.textContent = message ?? '';
}

/**
 * Runs `action`; a failure's message goes in the error line `id`, a success clears it.
 * @template T
 * @param {string} id
 * @param {() => Promise<T>|T} action
 * @returns {Promise<T|undefined>} the action's result, undefined after a failure
 */
export async function acting(id, action) {
  try {
    const result = await action();
    showError(id, null);
    return result;
  } catch (e) {
    showError(id, e?.message ?? String(e));
    return undefined;
  }
}
