"""Writes scenes/calcite_text.png: black words on white paper in a 5 × 7 pixel font, for the
calcite rhomb to double (8-bit greyscale PNG, written with zlib alone)."""
import struct, sys, zlib

GLYPHS = {
    "C": ["01110", "10001", "10000", "10000", "10000", "10001", "01110"],
    "A": ["01110", "10001", "10001", "11111", "10001", "10001", "10001"],
    "L": ["10000", "10000", "10000", "10000", "10000", "10000", "11111"],
    "I": ["11111", "00100", "00100", "00100", "00100", "00100", "11111"],
    "T": ["11111", "00100", "00100", "00100", "00100", "00100", "00100"],
    "E": ["11111", "10000", "10000", "11110", "10000", "10000", "11111"],
    "G": ["01110", "10001", "10000", "10111", "10001", "10001", "01111"],
    "R": ["11110", "10001", "10001", "11110", "10100", "10010", "10001"],
    "N": ["10001", "11001", "10101", "10011", "10001", "10001", "10001"],
    "H": ["10001", "10001", "10001", "11111", "10001", "10001", "10001"],
    " ": ["00000"] * 7,
}
LINES = ["CALCITE", "GRINLIGHT", "CALCITE", "GRINLIGHT"]
SCALE, MARGIN, GAP = 6, 12, 2  # pixels a font pixel, margins, font pixels between glyphs
width = 2 * MARGIN + SCALE * (max(len(l) for l in LINES) * (5 + GAP) - GAP)
height = 2 * MARGIN + SCALE * (len(LINES) * (7 + 4) - 4)
pixels = [[235] * width for _ in range(height)]
for row, line in enumerate(LINES):
    x0 = (width - SCALE * (len(line) * (5 + GAP) - GAP)) // 2
    y0 = MARGIN + row * SCALE * 11
    for i, ch in enumerate(line):
        for gy, bits in enumerate(GLYPHS[ch]):
            for gx, bit in enumerate(bits):
                if bit == "1":
                    for dy in range(SCALE):
                        for dx in range(SCALE):
                            pixels[y0 + gy * SCALE + dy][x0 + (i * (5 + GAP) + gx) * SCALE + dx] = 20
raw = b"".join(b"\x00" + bytes(r) for r in pixels)
chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 0, 0, 0, 0))
png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
open(sys.argv[1], "wb").write(png)
print(width, height)
