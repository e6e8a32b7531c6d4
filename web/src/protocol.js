// The wire format of docs/web.md, "The wire between the page and `telear web`": decoding of
// the binary messages and of the model's base64 meshes. Pure functions, no DOM and no GL, so
// that a bad message is a thrown Error with the reason rather than a broken picture.
//
// Every multi-byte number on the wire is little-endian; typed arrays are viewed directly on
// the received bytes, which is correct on every platform a browser runs on (all little-endian).

export const kVideoFrame = 1;
export const kLookUpTable = 2;

// The LUT marks raw pixels with no ray by NaN; GLSL's isnan() is unreliable under fast-math
// drivers, so they become a position far outside any region, which the composite discards
// with its bounds check (the native overlay does the same, src/render/overlay.cpp).
export const kNoRay = -1.0e9;

const decoder = new TextDecoder();

// A video frame: {header, left, right} with left/right the two JPEGs as Uint8Array views.
// A look-up table: {eye: 0|1, width, height, uv: Float32Array(width * height * 2)}, row 0
// first (the image's top row), NaN already replaced by kNoRay.
export function parseBinary(buffer) {
  if (!(buffer instanceof ArrayBuffer)) throw new Error('binary message: not an ArrayBuffer');
  if (buffer.byteLength < 8) throw new Error(`binary message: ${buffer.byteLength} bytes, need at least 8`);
  const bytes = new Uint8Array(buffer);
  const view = new DataView(buffer);
  switch (bytes[0]) {
    case kVideoFrame: return parseVideoFrame(buffer, view);
    case kLookUpTable: return parseLookUpTable(buffer, bytes, view);
    default: throw new Error(`binary message: unknown kind ${bytes[0]} (expected 1 or 2)`);
  }
}

function parseVideoFrame(buffer, view) {
  const headerLength = view.getUint32(4, true);
  if (8 + headerLength > buffer.byteLength) {
    throw new Error(`video frame: header of ${headerLength} bytes overruns the ${buffer.byteLength}-byte message`);
  }
  let header;
  try {
    header = JSON.parse(decoder.decode(new Uint8Array(buffer, 8, headerLength)));
  } catch (e) {
    throw new Error(`video frame: header is not JSON (${e.message})`);
  }
  const leftBytes = Number(header.left_bytes) || 0;
  const rightBytes = Number(header.right_bytes) || 0;
  const start = 8 + headerLength;
  if (start + leftBytes + rightBytes > buffer.byteLength) {
    throw new Error(`video frame ${header.frame_id}: left_bytes ${leftBytes} + right_bytes ${rightBytes} ` +
                    `overrun the message (${buffer.byteLength - start} bytes after the header)`);
  }
  return {
    kind: 'video',
    header,
    left: new Uint8Array(buffer, start, leftBytes),
    right: new Uint8Array(buffer, start + leftBytes, rightBytes),
  };
}

function parseLookUpTable(buffer, bytes, view) {
  if (buffer.byteLength < 12) throw new Error(`look-up table: ${buffer.byteLength} bytes, need at least 12`);
  const eye = bytes[1];
  const width = view.getUint32(4, true);
  const height = view.getUint32(8, true);
  const expected = 12 + width * height * 8;
  if (eye > 1) throw new Error(`look-up table: eye ${eye} (expected 0 left or 1 right)`);
  if (buffer.byteLength !== expected) {
    throw new Error(`look-up table: ${buffer.byteLength} bytes for ${width}x${height}, expected ${expected}`);
  }
  // A copy: the NaN replacement must not write into the socket's buffer, and the offset 12
  // keeps the floats aligned so the copy is one typed-array slice.
  const uv = new Float32Array(buffer.slice(12));
  for (let i = 0; i < uv.length; ++i) {
    if (Number.isNaN(uv[i])) uv[i] = kNoRay;
  }
  return {kind: 'lut', eye, width, height, uv};
}

export function decodeBase64(text) {
  if (typeof text !== 'string') return new Uint8Array(0);
  if (typeof Uint8Array.fromBase64 === 'function') return Uint8Array.fromBase64(text);
  const binary = atob(text);
  const out = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) out[i] = binary.charCodeAt(i);
  return out;
}

// One part or object of the `model` message: {vertices: Float32Array (9 per vertex),
// triangles, lines: Uint32Array}, every index checked against the vertex count.
export function decodeMesh(entry, what) {
  const vertexBytes = decodeBase64(entry.vertices);
  if (vertexBytes.length % 36 !== 0) {
    throw new Error(`${what}: vertices are ${vertexBytes.length} bytes, not a multiple of 36 (9 float32 per vertex)`);
  }
  const vertices = new Float32Array(vertexBytes.buffer, vertexBytes.byteOffset, vertexBytes.length / 4);
  const count = vertices.length / 9;
  const indices = (name) => {
    const b = decodeBase64(entry[name]);
    if (b.length % 4 !== 0) throw new Error(`${what}: ${name} are ${b.length} bytes, not a multiple of 4`);
    const a = new Uint32Array(b.buffer, b.byteOffset, b.length / 4);
    for (let i = 0; i < a.length; ++i) {
      if (a[i] >= count) throw new Error(`${what}: ${name}[${i}] = ${a[i]}, but there are ${count} vertices`);
    }
    return a;
  };
  return {vertices, triangles: indices('triangles'), lines: indices('lines')};
}

// A column-major 4x4 from `array` at `offset`, or null when it is not 16 finite numbers.
export function matrixAt(array, offset = 0) {
  if (!Array.isArray(array) || array.length < offset + 16) return null;
  for (let i = offset; i < offset + 16; ++i) {
    if (!Number.isFinite(array[i])) return null;
  }
  return array.slice(offset, offset + 16);
}
