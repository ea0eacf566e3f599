#!/usr/bin/env python3
"""Puts PNG images side by side (or one above the other) in one PNG, for the figures of doc/ (before / after).

Pure Python (zlib only), so the figures can be remade where ImageMagick is not installed. Reads 8-bit grey, grey +
alpha, RGB and RGBA PNGs (non-interlaced: what OpenCV and gridtopo write); alpha is dropped. Each image is first
scaled (nearest neighbour) to the given width, or to the height of the first image with --vertical off and
--height given; the gap between images is white.

  usage: scripts/png_side_by_side.py [--vertical] [--width PX] [--gap PX] -o OUT.png IN.png [IN.png ...]
  e.g.   scripts/png_side_by_side.py --width 600 -o doc/img/x.png before/overlay.png after/overlay.png
"""
import argparse
import struct
import sys
import zlib


def read_png(path):
    with open(path, 'rb') as f:
        data = f.read()
    if data[:8] != b'\x89PNG\r\n\x1a\n':
        sys.exit(f'png_side_by_side: {path}: not a PNG file')
    pos, idat, w = 8, [], None
    while pos < len(data):
        n, kind = struct.unpack('>I4s', data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b'IHDR':
            w, h, depth, ctype, _, _, interlace = struct.unpack('>IIBBBBB', body)
            if depth != 8 or ctype not in (0, 2, 4, 6) or interlace:
                sys.exit(f'png_side_by_side: {path}: only 8-bit grey/RGB(A), non-interlaced PNGs are read '
                         f'(depth {depth}, colour type {ctype}, interlace {interlace})')
        elif kind == b'IDAT':
            idat.append(body)
        elif kind == b'IEND':
            break
        pos += 12 + n
    if w is None:
        sys.exit(f'png_side_by_side: {path}: no IHDR chunk')
    bpp = {0: 1, 2: 3, 4: 2, 6: 4}[ctype]
    raw = zlib.decompress(b''.join(idat))
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + ((a + b) >> 1)) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        prev = line
        if bpp == 3:
            rows.append(bytes(line))
        else:  # to RGB
            out = bytearray(w * 3)
            for x in range(w):
                px = line[x * bpp:(x + 1) * bpp]
                out[3 * x:3 * x + 3] = bytes([px[0]] * 3) if ctype in (0, 4) else px[:3]
            rows.append(bytes(out))
    return w, h, rows


def scale(img, new_w):
    w, h, rows = img
    if new_w == w:
        return img
    new_h = max(1, round(h * new_w / w))
    xs = [min(w - 1, int((x + 0.5) * w / new_w)) for x in range(new_w)]
    out = []
    for y in range(new_h):
        src = rows[min(h - 1, int((y + 0.5) * h / new_h))]
        out.append(b''.join(src[3 * x:3 * x + 3] for x in xs))
    return new_w, new_h, out


def write_png(path, w, h, rows):
    raw = b''.join(b'\x00' + r for r in rows)
    def chunk(kind, body):
        return struct.pack('>I', len(body)) + kind + body + struct.pack('>I', zlib.crc32(kind + body) & 0xffffffff)
    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0)) +
                chunk(b'IDAT', zlib.compress(raw, 9)) + chunk(b'IEND', b''))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('-o', '--output', required=True)
    ap.add_argument('--vertical', action='store_true', help='one above the other (default: side by side)')
    ap.add_argument('--width', type=int, default=0, help='scale every image to this width (px); 0: as they are')
    ap.add_argument('--gap', type=int, default=10, help='white pixels between images')
    ap.add_argument('inputs', nargs='+')
    a = ap.parse_args()
    imgs = [read_png(p) for p in a.inputs]
    if a.width > 0:
        imgs = [scale(i, a.width) for i in imgs]
    white = lambda n: b'\xff' * (3 * n)
    if a.vertical:
        W = max(i[0] for i in imgs)
        rows = []
        for k, (w, h, r) in enumerate(imgs):
            if k:
                rows += [white(W)] * a.gap
            rows += [line + white(W - w) for line in r]
        write_png(a.output, W, len(rows), rows)
    else:
        H = max(i[1] for i in imgs)
        W = sum(i[0] for i in imgs) + a.gap * (len(imgs) - 1)
        rows = []
        for y in range(H):
            parts = []
            for k, (w, h, r) in enumerate(imgs):
                if k:
                    parts.append(white(a.gap))
                parts.append(r[y] if y < h else white(w))
            rows.append(b''.join(parts))
        write_png(a.output, W, H, rows)


if __name__ == '__main__':
    main()
