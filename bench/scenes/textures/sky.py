# A procedural sky for glint's bench scene: blue above, paler at the horizon, a dark ground,
# and a sun of about 2.5 degrees' radius with a glow. Written as a colour PFM, rows from the
# bottom, little-endian.
import math, struct, sys
W, H = 128, 64
sun_u, sun_v = 0.37, 0.27          # the sun's place in the image (u right, v down from the top)
sun_theta = math.pi * sun_v
sun_lon = 2 * math.pi * (sun_u - 0.5)
def direction(theta, lon):
    return (math.sin(theta) * math.sin(lon), math.cos(theta), math.sin(theta) * math.cos(lon))
sun = direction(sun_theta, sun_lon)
rows = []
for y in range(H):
    theta = math.pi * (y + 0.5) / H
    row = []
    for x in range(W):
        lon = 2 * math.pi * ((x + 0.5) / W - 0.5)
        d = direction(theta, lon)
        up = d[1]
        if up < 0:
            g = 0.12 + 0.05 * math.exp(8 * up)
            c = [g * 1.0, g * 0.9, g * 0.75]
        else:
            t = 1 - math.exp(-4 * up)
            c = [0.9 * (1 - t) + 0.25 * t, 0.95 * (1 - t) + 0.45 * t, 1.0 * (1 - t) + 0.95 * t]
            c = [1.2 * v for v in c]
        cos_sun = sum(a * b for a, b in zip(d, sun))
        angle = math.acos(max(-1.0, min(1.0, cos_sun)))
        if angle < math.radians(2.5):
            c = [v + s for v, s in zip(c, (900.0, 820.0, 650.0))]
        glow = 6.0 * math.exp(-angle / math.radians(6))
        c = [v + glow * s for v, s in zip(c, (1.0, 0.85, 0.6))]
        row.append(c)
    rows.append(row)
with open(sys.argv[1], 'wb') as f:
    f.write(b"PF\n%d %d\n-1.0\n" % (W, H))
    for row in reversed(rows):
        for c in row:
            f.write(struct.pack('<3f', *c))
