// The page's WebSocket to `dnurbs serve` (docs/serve.md, "The protocol"): JSON requests out,
// JSON replies and binary "DNF1" frames in, and request(message) that matches a reply to its
// request by the integer `id` the server echoes.

const kReplyTimeoutMs = 10000;

// The reply each request waits for. Requests answered by a typed reply carry the id back;
// `set`, `play`, `pause`, `reset`, `undo` are answered by the next status (which carries no id),
// `step` by the next status too, `move` by nothing (it resolves once sent).
function replyPredicate(message) {
  switch (message.type) {
    case 'set':
      return (m) => m.type === 'status' && m.settings && m.settings[message.key] === message.value;
    case 'play':
      return (m) => m.type === 'status' && m.playing === true;
    case 'pause':
      return (m) => m.type === 'status' && m.playing === false;
    case 'reset':
    case 'undo':
    case 'step':
      return (m) => m.type === 'status';
    case 'move':
      return null;
    default:
      return (m) => m.id === message.id && m.type !== 'error';
  }
}

// One binary frame: "DNF1", uint32 frame number, uint32 model count, then per model its index,
// vertex count n, control point count c, float32[3n] positions, float32[3n] normals,
// float32[3c] control points, all little endian. The arrays are views into `buffer` (every
// offset is a multiple of 4; the page assumes a little-endian machine, as every browser runs on).
export function parseFrame(buffer) {
  const view = new DataView(buffer);
  const magic = String.fromCharCode(...new Uint8Array(buffer, 0, Math.min(4, buffer.byteLength)));
  if (magic !== 'DNF1' || buffer.byteLength < 12) {
    throw new Error(`a binary message of ${buffer.byteLength} bytes is not a DNF1 frame`);
  }
  const frame = { number: view.getUint32(4, true), models: [] };
  const count = view.getUint32(8, true);
  let offset = 12;
  for (let m = 0; m < count; m++) {
    if (offset + 12 > buffer.byteLength) throw new Error(`frame ${frame.number} is truncated`);
    const index = view.getUint32(offset, true);
    const n = view.getUint32(offset + 4, true);
    const c = view.getUint32(offset + 8, true);
    offset += 12;
    const end = offset + 4 * (6 * n + 3 * c);
    if (end > buffer.byteLength) throw new Error(`frame ${frame.number} model ${index} is truncated`);
    frame.models.push({
      index,
      positions: new Float32Array(buffer, offset, 3 * n),
      normals: new Float32Array(buffer, offset + 12 * n, 3 * n),
      controls: new Float32Array(buffer, offset + 24 * n, 3 * c),
    });
    offset = end;
  }
  return frame;
}

export class Connection {
  // handlers: { open(), close(event), message(json), frame(parsed frame), error(text) }
  constructor(url, handlers) {
    this.handlers = handlers;
    this.nextId = 1;
    this.waiters = [];
    this.socket = new WebSocket(url);
    this.socket.binaryType = 'arraybuffer';
    this.socket.addEventListener('open', () => handlers.open());
    this.socket.addEventListener('close', (event) => {
      for (const w of this.waiters) w.reject(new Error(`connection closed (${event.code})`));
      this.waiters = [];
      handlers.close(event);
    });
    this.socket.addEventListener('message', (event) => this.receive(event.data));
  }

  get open() { return this.socket.readyState === WebSocket.OPEN; }

  receive(data) {
    if (data instanceof ArrayBuffer) {
      let frame;
      try {
        frame = parseFrame(data);
      } catch (error) {
        this.handlers.error(error.message);
        return;
      }
      this.handlers.frame(frame);
      return;
    }
    let message;
    try {
      message = JSON.parse(data);
    } catch (error) {
      this.handlers.error(`the server sent malformed JSON: ${String(data).slice(0, 80)}`);
      return;
    }
    this.handlers.message(message);
    this.settle(message);
  }

  settle(message) {
    const left = [];
    for (const w of this.waiters) {
      if (message.type === 'error' && message.id === w.id) {
        w.reject(Object.assign(new Error(message.message), { reply: message }));
      } else if (w.predicate(message)) {
        w.resolve(message);
      } else {
        left.push(w);
        continue;
      }
      clearTimeout(w.timer);
    }
    this.waiters = left;
  }

  // Sends a message as it is (text); false when the socket is not open.
  sendRaw(text) {
    if (!this.open) return false;
    this.socket.send(text);
    return true;
  }

  send(message) { return this.sendRaw(JSON.stringify(message)); }

  // Sends `message` with a fresh integer id; resolves with its reply, rejects on an error reply
  // with that id, a closed socket or no reply within 10 s.
  request(message) {
    const sent = { ...message, id: this.nextId++ };
    return new Promise((resolve, reject) => {
      if (!this.send(sent)) {
        reject(new Error(`not connected: ${sent.type} not sent`));
        return;
      }
      const predicate = replyPredicate(sent);
      if (!predicate) {
        resolve(null);
        return;
      }
      const waiter = { id: sent.id, predicate, resolve, reject };
      waiter.timer = setTimeout(() => {
        this.waiters = this.waiters.filter((w) => w !== waiter);
        reject(new Error(`no reply to ${sent.type} (id ${sent.id}) within ${kReplyTimeoutMs} ms`));
      }, kReplyTimeoutMs);
      this.waiters.push(waiter);
    });
  }
}
