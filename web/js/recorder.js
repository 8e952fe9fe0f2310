// Recording from the page: the frames the page receives go into a recording (recording.js, the
// layout `floectl record` writes), offered for download and for replay here when stopped.

import { showError } from './notify.js';
import { RecordingWriter } from './recording.js';

const mb = (bytes) => `${(bytes / 1e6).toFixed(1)} MB`;

/** The Record button, its status line and the recording in progress. */
export class Recorder {
  /**
   * @param {{button: HTMLButtonElement, status: HTMLElement, errorId: string,
   *   onReplay: (blob: Blob, name: string) => void}} ui
   */
  constructor(ui) {
    this.ui = ui;
    /** @type {RecordingWriter|null} */
    this.writer = null;
    this.name = '';
    /** The last recording's download address, released when the next starts. */
    this.url = null;
  }

  /** Whether frames are being recorded. */
  get active() {
    return this.writer !== null;
  }

  /** Starts recording; `name` names the file. */
  start(name) {
    if (this.url) URL.revokeObjectURL(this.url);
    this.url = null;
    this.writer = new RecordingWriter();
    this.name = name;
    this.ui.button.textContent = 'Stop recording';
    this.ui.button.setAttribute('aria-pressed', 'true');
    this.ui.status.textContent = 'recording: waiting for a frame';
    showError(this.ui.errorId, null);
  }

  /** Takes a frame as received (copied: the caller may transfer the buffer afterwards). */
  push(buffer) {
    if (!this.writer) return;
    const frame = new Uint8Array(buffer.slice(0));
    if (this.writer.full(frame.length)) {
      this.stop(`the recording reached its limit of ${mb(this.writer.maxBytes)}`);
      return;
    }
    try {
      this.writer.push(frame);
    } catch (e) {
      this.stop(`a frame could not be recorded: ${e.message}`);
      return;
    }
    this.ui.status.textContent = `recording: ${this.writer.frames} frames, ${mb(this.writer.bytes)}`;
  }

  /** Stops and offers the file; `why` says why if it was not the user. */
  stop(why = null) {
    const writer = this.writer;
    if (!writer) return;
    this.writer = null;
    this.ui.button.textContent = 'Record';
    this.ui.button.setAttribute('aria-pressed', 'false');
    showError(this.ui.errorId, why);
    if (writer.frames === 0) {
      this.ui.status.textContent = 'nothing recorded: no frame arrived (is the scene running?)';
      return;
    }
    const blob = writer.blob();
    const file = `${this.name}.rec`;
    const link = document.createElement('a');
    this.url = URL.createObjectURL(blob);
    link.href = this.url;
    link.download = file;
    link.textContent = `Download ${file}`;
    link.className = 'recording-download';
    const replay = document.createElement('button');
    replay.textContent = 'Replay';
    replay.onclick = () => this.ui.onReplay(blob, file);
    this.ui.status.replaceChildren(`${writer.frames} frames, ${mb(writer.bytes)}: `, link, ' ', replay);
  }
}
