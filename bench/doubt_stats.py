#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The hybrid's doubt mask against the cubemap's large errors, from a
snell-bench --images directory (docs/methods.md, "hybrid"): for each scene,
marked = the hybrid:doubted=show image differs from the cubemap image drawn as
the hybrid's cubemap pass (a pixel with any doubted sample); large = the
cubemap's pixel off the reference (FULL, MATCHED) by more than T/255 in some
channel; over the glass pixels (the cubemap error map's non-grey pixels).
Usage: doubt_stats.py DIR CUBE_SUFFIX SHOW_SUFFIX T SCENE..., where an image
is DIR/<method>_scene=<SCENE>_size=192x192<SUFFIX>.png. Python 3 only."""
import struct
import sys
import zlib


def png(path):
    """8-bit RGB or RGBA PNG, non-interlaced (what snell writes): RGB tuples."""
    d = open(path, 'rb').read()
    pos, w, h, ct, idat = 8, 0, 0, 0, b''
    while pos < len(d):
        n, = struct.unpack('>I', d[pos:pos + 4])
        t, c = d[pos + 4:pos + 8], d[pos + 8:pos + 8 + n]
        if t == b'IHDR':
            w, h, _, ct = struct.unpack('>IIBB', c[:10])
        elif t == b'IDAT':
            idat += c
        pos += 12 + n
    bpp = {2: 3, 6: 4}[ct]
    raw, out, prev, stride = zlib.decompress(idat), bytearray(), bytearray(w * bpp), w * bpp + 1
    for y in range(h):
        f, line = raw[y * stride], bytearray(raw[y * stride + 1:(y + 1) * stride])
        for i in range(len(line)):
            a = line[i - bpp] if i >= bpp else 0
            b = prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        out += line
        prev = line
    return [tuple(out[i * bpp:i * bpp + 3]) for i in range(w * h)]


def main():
    d, cube_sfx, show_sfx, t = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    for scene in sys.argv[5:]:
        base = f'{d}/cubemap_scene={scene}_size=192x192{cube_sfx}'
        cube = png(base + '.png')
        show = png(f'{d}/hybrid_scene={scene}_size=192x192{show_sfx}.png')
        glass = [e != (64, 64, 64) for e in png(base + '.err-full.png')]
        marked = [g and s != c for s, c, g in zip(show, cube, glass)]
        n = sum(glass)
        line = f'{scene}: {n} glass pixels, {sum(marked) / n:.1%} marked'
        for ref in ('full', 'matched'):
            r = png(f'{base}.ref-{ref}.png')
            big = [g and max(abs(p - q) for p, q in zip(c, x)) > t for c, x, g in zip(cube, r, glass)]
            both = sum(1 for m, b in zip(marked, big) if m and b)
            line += (f'; vs {ref.upper()} {sum(big) / n:.1%} off by > {t}/255, precision '
                     f'{both / max(sum(marked), 1):.1%}, recall {both / max(sum(big), 1):.1%}')
        print(line)


if __name__ == '__main__':
    main()
