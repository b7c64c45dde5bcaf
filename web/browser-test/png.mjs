// PNG files for the browser tests without a package: 8-bit RGB or RGBA encoded, and 8-bit
// grey, grey + alpha, RGB or RGBA (non-interlaced) decoded, with node's zlib.

import { deflateSync, inflateSync } from 'node:zlib';

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});

function crc32(bytes) {
  let c = 0xffffffff;
  for (const b of bytes) c = CRC_TABLE[(c ^ b) & 255] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

function chunk(type, data) {
  const out = Buffer.alloc(12 + data.length);
  out.writeUInt32BE(data.length, 0);
  out.write(type, 4, 'latin1');
  data.copy(out, 8);
  out.writeUInt32BE(crc32(out.subarray(4, 8 + data.length)), 8 + data.length);
  return out;
}

const SIGNATURE = Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]);

/**
 * A PNG file of `pixels` (width * height * channels bytes, top row first), channels 3 or 4.
 * @returns {Buffer}
 */
export function encodePng(width, height, channels, pixels) {
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0);
  header.writeUInt32BE(height, 4);
  header[8] = 8;
  header[9] = channels === 4 ? 6 : 2;
  const row = width * channels;
  const raw = Buffer.alloc((row + 1) * height);
  for (let y = 0; y < height; ++y)
    Buffer.from(pixels.buffer, pixels.byteOffset + y * row, row).copy(raw, y * (row + 1) + 1);
  return Buffer.concat([
    SIGNATURE,
    chunk('IHDR', header),
    chunk('IDAT', deflateSync(raw)),
    chunk('IEND', Buffer.alloc(0)),
  ]);
}

/**
 * The pixels of a PNG file as RGBA: {width, height, data} (data: Uint8Array, top row first).
 * @param {Buffer} file
 */
export function decodePng(file) {
  if (!file.subarray(0, 8).equals(SIGNATURE)) throw new Error('decodePng: not a PNG file');
  let offset = 8, width = 0, height = 0, type = -1;
  const idat = [];
  while (offset < file.length) {
    const length = file.readUInt32BE(offset);
    const name = file.toString('latin1', offset + 4, offset + 8);
    const data = file.subarray(offset + 8, offset + 8 + length);
    if (name === 'IHDR') {
      width = data.readUInt32BE(0);
      height = data.readUInt32BE(4);
      type = data[9];
      if (data[8] !== 8 || data[12] !== 0)
        throw new Error(`decodePng: only 8-bit non-interlaced, got depth ${data[8]}`);
    } else if (name === 'IDAT') {
      idat.push(data);
    } else if (name === 'PLTE') {
      throw new Error('decodePng: palette images are not read');
    }
    offset += 12 + length;
  }
  const channels = { 0: 1, 2: 3, 4: 2, 6: 4 }[type];
  if (!channels) throw new Error(`decodePng: colour type ${type} is not read`);
  const raw = inflateSync(Buffer.concat(idat));
  const row = width * channels;
  const pixels = new Uint8Array(row * height);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (row + 1)];
    const line = raw.subarray(y * (row + 1) + 1, (y + 1) * (row + 1));
    const out = pixels.subarray(y * row, (y + 1) * row);
    const up = y > 0 ? pixels.subarray((y - 1) * row, y * row) : new Uint8Array(row);
    for (let i = 0; i < row; ++i) {
      const a = i >= channels ? out[i - channels] : 0;
      const b = up[i];
      const c = i >= channels ? up[i - channels] : 0;
      let predictor = 0;
      if (filter === 1) predictor = a;
      else if (filter === 2) predictor = b;
      else if (filter === 3) predictor = (a + b) >> 1;
      else if (filter === 4) {
        const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
        predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      }
      out[i] = (line[i] + predictor) & 255;
    }
  }
  const data = new Uint8Array(width * height * 4);
  for (let i = 0, j = 0; i < width * height; ++i, j += channels) {
    const grey = channels <= 2;
    data[4 * i] = pixels[j];
    data[4 * i + 1] = grey ? pixels[j] : pixels[j + 1];
    data[4 * i + 2] = grey ? pixels[j] : pixels[j + 2];
    data[4 * i + 3] = channels === 2 ? pixels[j + 1] : channels === 4 ? pixels[j + 3] : 255;
  }
  return { width, height, data };
}
